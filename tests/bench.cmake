# snell-bench: a tiny interleaved sweep and its outputs; bad specs.
if(TARGET snell-bench)
  set(bench $<TARGET_FILE:snell-bench>)
  add_test(NAME bench_sweep COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_sweep"
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench.cmake)
  set_tests_properties(bench_sweep PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  if(SNELL_WITH_MESHOPT)
    add_test(NAME bench_lod COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_lod"
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench_lod.cmake)
    set_tests_properties(bench_lod PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  endif()
  foreach(bad "-b|nosuch" "-b|cubemap:iterations=0" "-b|cubemap:face=99999" "--frames|0" "-b|auto"
              "-b|single:iterations=4" "-b|cubemap:encoding=rgb" "-b|cubemap:scene=pair:attenuation=2/1/1/1"
              "-b|single:lod=0" "-b|single:lod=1.5" "-b|single:lod=nan")
    string(MAKE_C_IDENTIFIER "bench_bad_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=${bad}" -DCODE=2 "-DERR=snell-bench: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
