# SPDX-License-Identifier: MIT
# Wyman's image-space two-surface method (issue 11: src/methods/wyman.c,
# shaders_es/wyman.frag, the back-face pass in render/gbuffer.c): the sphere
# against a closed-form twin of the model and the reference, torus and goblet
# against single-surface, the back-face pass's sharing and skipping.
snell_add_test(test_wyman SOURCES test_wyman.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_wyman PRIVATE m)
