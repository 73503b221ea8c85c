# SPDX-License-Identifier: MIT
# Glass seen through glass and opaque objects seen through glass where they
# are (issue 13: src/render/layers.c, shaders_es/common/beyond.glsl): three
# glass + two opaque objects against the reference over the whole scene,
# the stage's rule, two spheres on the view axis.
snell_add_test(test_scene_layers SOURCES test_scene_layers.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_scene_layers PRIVATE m)
