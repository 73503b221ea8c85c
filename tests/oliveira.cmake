# SPDX-License-Identifier: MIT
# Oliveira and Brauwers' conservative image-space search (issue 11:
# src/methods/oliveira.c, shaders_es/oliveira.frag): the sphere against its
# exact exit where the seed's model holds, a slab (both image-space methods),
# a deforming mesh, TIR bounces on a cube, invalid texels and off-screen rays.
# The method always shades in screen space; the forward variant checks that
# forcing FORWARD changes nothing for it.
snell_add_test(test_oliveira SOURCES test_oliveira.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_oliveira PRIVATE m)
