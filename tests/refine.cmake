# SPDX-License-Identifier: MIT
# The refine stage (src/render/refine.c): progressive refinement of still frames.
snell_add_test(test_refine SOURCES test_refine.c LABELS "render;gl" SHADINGS forward screen TIMEOUT 300)
if(TARGET test_refine)
  target_link_libraries(test_refine PRIVATE snell_dep::gles)
  # Again without GL_EXT_color_buffer_float (a Pi's v3d): frames unrefined, the reason says so.
  add_test(NAME test_refine_no_float COMMAND test_refine WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(test_refine_no_float PROPERTIES LABELS "render;gl" SKIP_RETURN_CODE 77 TIMEOUT 300
    ENVIRONMENT "SNELL_TEST_DATA=${CMAKE_CURRENT_SOURCE_DIR}/data;SNELL_TEST_OUT=${CMAKE_CURRENT_BINARY_DIR};MESA_EXTENSION_OVERRIDE=-GL_EXT_color_buffer_float")
endif()
# snell-render --refine N: N still frames, their mean written (the stats say how many).
if(TARGET snell-render AND SNELL_WITH_REFINE)
  add_test(NAME cli_refine COMMAND $<TARGET_FILE:snell-render> --mesh sphere --refine 5 --stats --size 24x24
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_refine.png)
  # Under a device profile without float colour targets (CI's gles30-min) the frames are unrefined
  # and the stats say why: that is the documented fallback, not a failure.
  set_tests_properties(cli_refine PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "stats: stages run: [a-z_ ]* refine\n.*stats: refine: 5 of 5 samples since the first frame;stats: refine: off: no float colour target \\(GL_EXT_color_buffer_float\\)")
endif()
