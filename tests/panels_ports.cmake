# SPDX-License-Identifier: MIT
# Glass panels where users see them (issue 51 item 4): snell-render --panels
# and --under, the kiosk's --panels and --slide (its --preview: no KMS device
# here), the panels file's errors, each with its line, and the example app
# (examples/panels_merge.c). The Android scene's panels are in test_android_scene.
if(TARGET snell-render AND SNELL_WITH_PANELS)
  set(cli $<TARGET_FILE:snell-render>)
  set(expect ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set(one_error ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_one_error.cmake)
  set(pdir ${CMAKE_CURRENT_BINARY_DIR}/panels_ports)
  add_executable(panels_diff panels_diff.c)
  target_link_libraries(panels_diff PRIVATE snell_static)
  target_compile_options(panels_diff PRIVATE ${SNELL_WARNINGS})
  # One clear panel (no shadow: the box is all it changes) in a 96x64 frame.
  file(WRITE ${pdir}/one.txt "# a clear panel, left of the sphere\ncenter=24,32 size=36,40 radius=10 shadow=none\n")
  set(box 6,12,42,52)
  add_test(NAME cli_panels COMMAND ${CMAKE_COMMAND} -DEXE=${cli} -DDIFF=$<TARGET_FILE:panels_diff>
           -DPANELS=${pdir}/one.txt -DBOX=${box} -DOUT_DIR=${pdir}/cli
           -DREFERENCE=$<BOOL:${SNELL_WITH_REF}> -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/cli_panels.cmake)
  set_tests_properties(cli_panels PROPERTIES LABELS "cli;gl")
  if(TARGET snell-kiosk)
    add_test(NAME kiosk_panels COMMAND ${CMAKE_COMMAND} -DDIFF=$<TARGET_FILE:panels_diff>
             -DKIOSK=$<TARGET_FILE:snell-kiosk> -DPANELS=${pdir}/one.txt -DBOX=${box} -DOUT_DIR=${pdir}/kiosk
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/cli_panels.cmake)
    set_tests_properties(kiosk_panels PROPERTIES LABELS "cli;gl")
  endif()

  # A malformed file: exit 2, its line and what is wrong, nothing drawn.
  file(WRITE ${pdir}/bad_form.txt "# fine\ncenter=10,10 size=20,20\ncenter=30,30 size=20,20 radius=1,2\n")
  add_test(NAME cli_panels_malformed COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--panels|${pdir}/bad_form.txt"
           -DCODE=2 "-DERR=^snell-render: --panels .*bad_form.txt line 3: radius wants R or R0,R1,R2,R3 \\(finite\\), got '1,2'$"
           -P ${one_error})
  file(WRITE ${pdir}/bad_key.txt "center=10,10 size=20,20 ior=1.5 blur=3\n")
  add_test(NAME cli_panels_unknown_key COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--panels|${pdir}/bad_key.txt"
           -DCODE=2 "-DERR=^snell-render: --panels .*bad_key.txt line 1: unknown key 'blur' \\(center, size, " -P ${one_error})
  # A value out of range is the library's refusal, mapped back to its line.
  file(WRITE ${pdir}/bad_ior.txt "center=10,10 size=20,20\n\n# the second panel\ncenter=30,30 size=20,20 ior=7\n")
  add_test(NAME cli_panels_range COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}"
           "-DARGS=--size|48x48|--panels|${pdir}/bad_ior.txt|-o|${pdir}/bad_ior.png" -DCODE=1
           "-DERR=^snell-render: render: .*panels\\[1\\]\\.ior .*\\(line 4 of .*bad_ior.txt\\)$" -P ${one_error})
  add_test(NAME cli_under_needs_panels COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--under|x.png" -DCODE=2
           "-DERR=^snell-render: --under draws glass panels: give --panels FILE$" -P ${one_error})
  set_tests_properties(cli_panels_malformed cli_panels_unknown_key cli_under_needs_panels PROPERTIES LABELS "cli")
  set_tests_properties(cli_panels_range PROPERTIES LABELS "cli;gl")
  if(TARGET snell-kiosk)
    set(kiosk $<TARGET_FILE:snell-kiosk>)
    # kiosk.conf's panels: the file's error names its line; a slide needs panels.
    file(WRITE ${pdir}/kiosk_bad.conf "# panels over the scene\n--panels ${pdir}/bad_form.txt\n")
    add_test(NAME kiosk_panels_malformed COMMAND ${CMAKE_COMMAND} "-DEXE=${kiosk}"
             "-DARGS=--config|${pdir}/kiosk_bad.conf|--preview|${pdir}/unused.png" -DCODE=2
             "-DERR=snell-kiosk: --panels .*bad_form.txt line 3: radius wants.*in .*kiosk_bad.conf line 2" -P ${expect})
    add_test(NAME kiosk_slide_needs_panels COMMAND ${CMAKE_COMMAND} "-DEXE=${kiosk}"
             "-DARGS=--slide|${pdir}/one.txt|--preview|${pdir}/unused.png" -DCODE=2
             "-DERR=^snell-kiosk: --slide shows pictures under glass panels: give --panels FILE$" -P ${one_error})
    add_test(NAME kiosk_slide_missing COMMAND ${CMAKE_COMMAND} "-DEXE=${kiosk}"
             "-DARGS=--panels|${pdir}/one.txt|--slide|${pdir}/none.png" -DCODE=2
             "-DERR=^snell-kiosk: --slide .*none.png: No such file or directory$" -P ${one_error})
    set_tests_properties(kiosk_panels_malformed kiosk_slide_needs_panels kiosk_slide_missing PROPERTIES LABELS "cli")
  endif()
endif()

# The panels file's parser alone: fields, lines and hostile text (no GL).
snell_add_test(test_cli_panels SOURCES test_cli_panels.c ${PROJECT_SOURCE_DIR}/ports/cli/cli_panels.c
               ${PROJECT_SOURCE_DIR}/ports/cli/cli_input.c LABELS "unit")
target_include_directories(test_cli_panels PRIVATE ${PROJECT_SOURCE_DIR}/ports/cli)

# examples/panels_merge.c: three glass panels of one group over the app's
# picture (its GL texture) merge and split as they move; six frames written.
# Exit 0 when the space between the drops is glass while they merge and the
# picture while they are apart.
if(SNELL_WITH_PANELS AND SNELL_WITH_PNG)
  add_executable(panels_merge ${PROJECT_SOURCE_DIR}/examples/panels_merge.c)
  target_link_libraries(panels_merge PRIVATE snell_static snell_dep::gles m)
  add_test(NAME example_panels_merge COMMAND panels_merge ${CMAKE_CURRENT_BINARY_DIR}/panels_merge 160x96)
  set_tests_properties(example_panels_merge PROPERTIES LABELS "render;gl" SKIP_RETURN_CODE 77
                       PASS_REGULAR_EXPRESSION "the drops merged and split")
endif()
