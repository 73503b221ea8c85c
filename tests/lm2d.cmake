# SPDX-License-Identifier: MIT
# 2D lightmap (lm2d) tests: unit (geometry, scene files, tracer, contour, the
# threaded exact CPU rasteriser) and render (GL lines vs the exact rasteriser,
# the rasteriser choice on a ctx, showcase scenes) on llvmpipe.
foreach(t geom scene trace contour raster_cpu)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c)
    snell_add_test(test_lm2d_${t} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c LABELS unit lm2d)
  endif()
endforeach()
foreach(t raster render)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c)
    snell_add_test(test_lm2d_${t} SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_lm2d_${t}.c LABELS render gl lm2d)
  endif()
endforeach()

# snell-render --2d: albedo multiply, contour extraction, and clear failures.
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  set(d ${CMAKE_CURRENT_SOURCE_DIR}/data)
  add_test(NAME cli_2d_albedo COMMAND ${cli} --2d ${d}/lm2d/shadow.txt --size 4x3 --albedo ${d}/images/ok_4x3.png
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_2d_albedo.png)
  set_tests_properties(cli_2d_albedo PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "cli_2d_albedo.png: 4x3")
  add_test(NAME cli_2d_contour COMMAND ${cli} --2d --contour ${d}/images/ok_4x3.png -o ${CMAKE_CURRENT_BINARY_DIR}/c.csv)
  set_tests_properties(cli_2d_contour PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "c.csv: 4 points")
  add_test(NAME cli_2d_albedo_jpeg COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}"
           "-DARGS=--2d|${d}/lm2d/shadow.txt|--albedo|${d}/images/bad_jpeg_huffman_overflow.jpg|-o|x.png"
           -DCODE=1 "-DERR=JPEG images are not decoded" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(cli_2d_albedo_jpeg PROPERTIES LABELS "cli")
  # the rasteriser: AUTO on llvmpipe is the CPU one (and says why); GL lines can be forced
  add_test(NAME cli_2d_raster_auto COMMAND ${cli} --2d ${d}/lm2d/shadow.txt --size 64x64
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_2d_raster_auto.png)
  set_tests_properties(cli_2d_raster_auto PROPERTIES LABELS "cli;gl"
                       PASS_REGULAR_EXPRESSION "llvmpipe[^\n]*, CPU exact rasteriser.*rasteriser: auto: ")
  add_test(NAME cli_2d_raster_gl COMMAND ${cli} --2d ${d}/lm2d/shadow.txt --size 64x64 --raster gl
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_2d_raster_gl.png)
  set_tests_properties(cli_2d_raster_gl PROPERTIES LABELS "cli;gl"
                       PASS_REGULAR_EXPRESSION "GL lines.*rasteriser: GL lines requested")
  foreach(bad "--passes|abc" "--bounces|-1" "--format|foo" "--blend|mix" "--threshold|300" "--gamma|0" "--raster|gpu")
    string(MAKE_C_IDENTIFIER "cli_2d_bad_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--2d|${d}/lm2d/shadow.txt|${bad}|-o|x.png"
             -DCODE=2 "-DERR=snell-render --2d: " -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()

# snell-bench reports the llvmpipe threads it ran with (issue 10, item 5): the
# table line here; the JSON header and the CSV column come from the same code.
if(TARGET snell-bench)
  add_test(NAME bench_llvmpipe_threads COMMAND $<TARGET_FILE:snell-bench> -b single:scene=sphere:size=32x32 --frames 1
           --warmup 0 --no-cache -q -o ${CMAKE_CURRENT_BINARY_DIR}/bench_lp)
  set_tests_properties(bench_llvmpipe_threads PROPERTIES LABELS "cli;gl" ENVIRONMENT "LP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "llvmpipe threads: 1 \\(LP_NUM_THREADS=1\\)")
endif()
