# SPDX-License-Identifier: MIT
# The layered method (issue 25 item 1: src/methods/layered.c,
# shaders_es/layered.frag, layered_bake.frag): the bake's layers, memory and
# once-per-version rule, exit directions against MATCHED (sphere) and FULL
# (torus, goblet, an open mesh) beside single's.
snell_add_test(test_layered SOURCES test_layered.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_layered PRIVATE m)
# AUTO on meshes of several separate pieces (issue 40 item 10): within 1 dB of the best method.
snell_add_test(test_auto_pieces SOURCES test_auto_pieces.c LABELS "render;gl")
target_link_libraries(test_auto_pieces PRIVATE m)
