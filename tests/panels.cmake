# SPDX-License-Identifier: MIT
# Glass panels over the frame (snell_panels.h, src/render/panels_stage.c):
# the header's model checked pixel by pixel, every source of what lies
# beneath, hostile panels and the budget.
snell_add_test(test_panels SOURCES test_panels.c LABELS "render;gl" TIMEOUT 120)
if(TARGET test_panels)
  target_link_libraries(test_panels PRIVATE snell_dep::egl snell_dep::gles m)
  # Again without OES_EGL_image_external_essl3: EXTERNAL falls back to the target and says so.
  add_test(NAME test_panels_no_external COMMAND test_panels WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(test_panels_no_external PROPERTIES LABELS "render;gl" SKIP_RETURN_CODE 77 TIMEOUT 120
    ENVIRONMENT "SNELL_TEST_DATA=${CMAKE_CURRENT_SOURCE_DIR}/data;SNELL_TEST_OUT=${CMAKE_CURRENT_BINARY_DIR};MESA_EXTENSION_OVERRIDE=-GL_OES_EGL_image_external_essl3")
endif()

# The panels over the host's framebuffer in each colour format apps and EGL configs use.
snell_add_test(test_panels_formats SOURCES test_panels_formats.c LABELS "render;gl" TIMEOUT 60)
if(TARGET test_panels_formats)
  target_link_libraries(test_panels_formats PRIVATE snell_dep::egl snell_dep::gles m)
endif()

# Hostile panels: 4,096 in a chain of overlaps, a 1x1 frame, a texture of another size read past 0..1.
snell_add_test(test_panels_stress SOURCES test_panels_stress.c LABELS "render;gl" TIMEOUT 60)
if(TARGET test_panels_stress)
  target_link_libraries(test_panels_stress PRIVATE snell_dep::egl snell_dep::gles m)
endif()
