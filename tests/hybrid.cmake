# SPDX-License-Identifier: MIT
# The hybrid (issue 50 item 2: src/methods/hybrid.c, shaders_es/hybrid.frag):
# the cubemap's doubt mask against exact on a sphere and a torus, and the
# hybrid's image exact's on the marked pixels and the cubemap's elsewhere,
# forward and in screen space.
snell_add_test(test_hybrid SOURCES test_hybrid.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_hybrid PRIVATE m)
