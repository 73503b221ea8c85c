# SPDX-License-Identifier: MIT
# What a user reads (issue 28 items 5-8): one message per error with the offending value and
# the reason, --help wherever it is given; snell-bench's progress lines agreeing with its table
# and JSON; the reference's progress only on a terminal; the README's counts and package list.
set(one_error ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_one_error.cmake)
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  set(o ${CMAKE_CURRENT_BINARY_DIR}/msg.png)
  # NAME CODE ERR ARGS (ARGS separated by |); without a GL context: label cli only
  set(msg_cases
    "msg_render_unknown|2|^snell-render: unknown option '--bogus'. see --help$|--bogus|1"
    "msg_render_no_value|2|^snell-render: --size needs a value. see --help$|--mesh|sphere|--size"
    "msg_render_param_no_value|2|^snell-render: --iterations needs a value. see --help$|--iterations"
    "msg_render_bad_value|2|^snell-render: --size wants WxH within 1..16384, got '0x5'$|--size|0x5"
    # issue 40 item 11: a drop's frame of 1e30 or NaN was accepted and never applied
    "msg_water_drop_frame_huge|2|^snell-render --water: --drop 0,0,0.08,-0.03,1e30: frame F must be a whole number 0..99999$|--water|--drop|0,0,0.08,-0.03,1e30"
    "msg_water_drop_frame_nan|2|^snell-render --water: --drop 0,0,0.08,-0.03,nan: frame F must be a whole number 0..99999$|--water|--drop|0,0,0.08,-0.03,nan"
    "msg_water_drop_frame_late|2|^snell-render --water: --drop 1: before frame 3, but only 1 frame.s. are made .--frames.$|--water|--drop|0,0,0.08,-0.03,3")
  set(msg_gl_cases
    "msg_render_missing_mesh|1|^snell-render: mesh: cannot open '/nonexistent/u28.obj': No such file or directory$|--mesh|/nonexistent/u28.obj|--size|8x8|-o|${o}"
    "msg_render_missing_env|1|^snell-render: environment: cannot open image \"/nonexistent/u28.png\": No such file or directory$|--env|/nonexistent/u28.png|--size|8x8|-o|${o}"
    "msg_render_missing_scene|1|^snell-render: scene: cannot open '/nonexistent/u28.gltf': No such file or directory$|--scene|/nonexistent/u28.gltf|--size|8x8|-o|${o}"
    "msg_render_unwritable_png|1|^snell-render: cannot write PNG \"/nonexistent/u28/x.png\": No such file or directory$|--size|8x8|-o|/nonexistent/u28/x.png"
    # issue 40 item 9: an eye 1e-24 from the target drew the background alone, exit 0
    "msg_render_camera_tiny|1|^snell-render: render: snell_render: camera.distance 1e-24 is too small .at least 1e-06: a millionth of the scene's scale.$|--camera|30,20,1e-24|--size|8x8|-o|${o}"
    # issue 40 item 11: a shape's segment count out of range is no "unknown mesh file extension"
    "msg_render_shape_segments|1|^snell-render: mesh: shape segments 1000000 / rings 500000 exceed 4096$|--mesh|sphere@1000000|--size|8x8|-o|${o}"
    # issue 40 item 7: a full device (stb ignored fwrite's and fclose's errors: exit 0, no message)
    "msg_render_full_device|1|^snell-render: cannot write PNG \"/dev/full\": No space left on device$|--size|8x8|-o|/dev/full"
    "msg_render_full_device_trace|1|^snell-render: cannot write PNG \"/dev/full\": No space left on device$|--size|8x8|--trace-pixel|4,4|-o|/dev/full"
    "msg_render_full_device_2d|1|^snell-render --2d: SNELL_E_IO: cannot write PNG \"/dev/full\": No space left on device$|--2d|${CMAKE_CURRENT_SOURCE_DIR}/data/lm2d/shadow.txt|--size|16x16|-o|/dev/full"
    "msg_render_full_device_water|1|^snell-render --water: cannot write PNG \"/dev/full\": No space left on device$|--water|--size|8x8|-o|/dev/full")
  foreach(gl 0 1)
    if(gl)
      set(cases ${msg_gl_cases})
      set(labels "cli;gl")
    else()
      set(cases ${msg_cases})
      set(labels "cli")
    endif()
    foreach(case IN LISTS cases)
      string(REPLACE "|" ";" f "${case}")
      list(POP_FRONT f name code err)
      string(REPLACE ";" "|" args "${f}")
      add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=${args}" -DCODE=${code} "-DERR=${err}"
               -P ${one_error})
      set_tests_properties(${name} PROPERTIES LABELS "${labels}")
    endforeach()
  endforeach()
  # issue 49: an argument's ESC sequence was echoed to the terminal in the error
  string(ASCII 27 esc)
  add_test(NAME msg_render_control_arg COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--mesh|x${esc}]0;T.obj" -DCODE=2
           "-DERR=^snell-render: argument 2 .'x.]0;T.obj'. holds a control character$" -P ${one_error})
  set_tests_properties(msg_render_control_arg PROPERTIES LABELS "cli")
  add_test(NAME msg_render_help_anywhere COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--size|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-render" -P ${one_error})
  add_test(NAME msg_render_water_help COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--water|--frames|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-render --water" -P ${one_error})
  set_tests_properties(msg_render_help_anywhere msg_render_water_help PROPERTIES LABELS "cli")
endif()
if(TARGET snell-bench)
  set(bench $<TARGET_FILE:snell-bench>)
  add_test(NAME msg_bench_unknown COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--bogus|3" -DCODE=2
           "-DERR=^snell-bench: unknown option '--bogus'. see --help$" -P ${one_error})
  add_test(NAME msg_bench_no_value COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=-b|single|--frames" -DCODE=2
           "-DERR=^snell-bench: --frames needs a value. see --help$" -P ${one_error})
  # issue 40 item 7: --images into a missing folder ran, wrote nothing and exited 0
  add_test(NAME msg_bench_images_missing_dir COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=-b|single|--images|/nonexistent/u40" -DCODE=2
           "-DERR=^snell-bench: --images '/nonexistent/u40' is not a directory .No such file or directory.$" -P ${one_error})
  set_tests_properties(msg_bench_images_missing_dir PROPERTIES LABELS "cli")
  add_test(NAME msg_bench_bad_value COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--plot-y|nope" -DCODE=2
           "-DERR=^snell-bench: --plot-y wants full-mean\\|full-p99\\|full-rmse\\|matched-mean, got 'nope'$" -P ${one_error})
  add_test(NAME msg_bench_water_help COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--water|--help" -DCODE=0 -DERR=
           "-DOUT=^usage: snell-bench --water" -P ${one_error})
  add_test(NAME msg_bench_help_after_value COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--frames|3|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-bench" -P ${one_error})
  add_test(NAME msg_bench_env_help COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--env-lookup|--size|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-bench --env-lookup" -P ${one_error})
  add_test(NAME msg_bench_2d_help COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--2d|--rays|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-bench --2d" -P ${one_error})
  add_test(NAME msg_bench_budget_help COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--budget|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-bench --budget" -P ${one_error})
  add_test(NAME msg_bench_budget_unknown COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--budget|4x|--bogus" -DCODE=2
           "-DERR=^snell-bench --budget: unknown option '--bogus'. see --budget --help$" -P ${one_error})
  add_test(NAME msg_bench_water_unknown COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--water|--grid|x" -DCODE=2
           "-DERR=^snell-bench --water: --grid wants a positive integer, got 'x'$" -P ${one_error})
  set_tests_properties(msg_bench_unknown msg_bench_no_value msg_bench_bad_value msg_bench_water_help
                       msg_bench_help_after_value msg_bench_env_help msg_bench_2d_help msg_bench_water_unknown
                       msg_bench_budget_help msg_bench_budget_unknown
                       PROPERTIES LABELS "cli")
  # Progress lines, table and JSON of one small run say the same (item 6).
  add_test(NAME bench_consistency COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}"
           "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_consistency" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench_consistency.cmake)
  set_tests_properties(bench_consistency PROPERTIES LABELS "cli;gl" TIMEOUT 300)
endif()
if(TARGET snell-kiosk)
  set(kiosk $<TARGET_FILE:snell-kiosk>)
  add_test(NAME msg_kiosk_unknown COMMAND ${CMAKE_COMMAND} "-DEXE=${kiosk}" "-DARGS=--bogus" -DCODE=2
           "-DERR=^snell-kiosk: unknown option '--bogus'. see --help$" -P ${one_error})
  add_test(NAME msg_kiosk_no_value COMMAND ${CMAKE_COMMAND} "-DEXE=${kiosk}" "-DARGS=--bench|--frames" -DCODE=2
           "-DERR=^snell-kiosk: --frames needs a value. see --help$" -P ${one_error})
  add_test(NAME msg_kiosk_help_anywhere COMMAND ${CMAKE_COMMAND} "-DEXE=${kiosk}" "-DARGS=--json|--help" -DCODE=0
           -DERR= "-DOUT=^usage: snell-kiosk" -P ${one_error})
  set_tests_properties(msg_kiosk_unknown msg_kiosk_no_value msg_kiosk_help_anywhere PROPERTIES LABELS "cli")
endif()
# The README and docs/ true for this build (tests/scripts/check_readme.cmake says what is checked):
# only where its counts are this build's, a native build with every component. readme_api builds
# the README's ten lines of API, extracted at build time, as an app would (the shared library).
if(NOT SNELL_COMPONENTS_OFF AND NOT CMAKE_CROSSCOMPILING AND TARGET snell-render AND TARGET snell-bench)
  if(TARGET snell-kiosk)
    set(readme_kiosk $<TARGET_FILE:snell-kiosk>)
  else()
    set(readme_kiosk "")
  endif()
  add_test(NAME readme_true COMMAND ${CMAKE_COMMAND} "-DSOURCE_DIR=${PROJECT_SOURCE_DIR}"
           "-DCTEST=${CMAKE_CTEST_COMMAND}" "-DBUILD_DIR=${PROJECT_BINARY_DIR}" "-DLIB=$<TARGET_FILE:snell_shared>"
           "-DRENDER=$<TARGET_FILE:snell-render>" "-DBENCH=$<TARGET_FILE:snell-bench>" "-DKIOSK=${readme_kiosk}"
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_readme.cmake)
  set_tests_properties(readme_true PROPERTIES LABELS "docs")
  # Every file, section and option a doc, a header or source comment or a tool's --help
  # names exists (issue 49 item 5; tests/scripts/check_doc_refs.py says what is checked).
  find_program(SNELL_PYTHON3 python3)
  if(SNELL_PYTHON3)
    add_test(NAME doc_references COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_doc_refs.py
             ${PROJECT_SOURCE_DIR} $<TARGET_FILE:snell-render> $<TARGET_FILE:snell-bench> ${readme_kiosk})
    set_tests_properties(doc_references PROPERTIES LABELS "docs" TIMEOUT 60)
    # and the check fails where references dangle (tests/data/docrefs holds four)
    add_test(NAME doc_references_fail COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_doc_refs.py
             ${CMAKE_CURRENT_SOURCE_DIR}/data/docrefs)
    set_tests_properties(doc_references_fail PROPERTIES LABELS "docs" PASS_REGULAR_EXPRESSION
                         "missing.md.*README.md#nowhere.*\"Nowhere\".*src/none.c.*4 dangling reference")
  endif()
  set(readme_api_c ${CMAKE_CURRENT_BINARY_DIR}/readme_api.c)
  add_custom_command(OUTPUT ${readme_api_c}
    COMMAND ${CMAKE_COMMAND} "-DREADME=${PROJECT_SOURCE_DIR}/README.md" "-DOUT=${readme_api_c}"
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/readme_api.cmake
    DEPENDS ${PROJECT_SOURCE_DIR}/README.md ${CMAKE_CURRENT_SOURCE_DIR}/scripts/readme_api.cmake)
  add_executable(readme_api ${readme_api_c})
  target_link_libraries(readme_api PRIVATE snell_shared)
  target_compile_options(readme_api PRIVATE ${SNELL_WARNINGS})
  add_test(NAME readme_api COMMAND readme_api)
  set_tests_properties(readme_api PROPERTIES LABELS "docs;gl" TIMEOUT 120)
endif()
