# 2D lightmap (lm2d) tests: unit (geometry, scene files, tracer, contour) and
# render (GL lines vs the exact rasteriser, showcase scenes) on llvmpipe.
foreach(t geom scene trace contour)
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
  foreach(bad "--passes|abc" "--bounces|-1" "--format|foo" "--blend|mix" "--threshold|300" "--gamma|0")
    string(MAKE_C_IDENTIFIER "cli_2d_bad_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--2d|${d}/lm2d/shadow.txt|${bad}|-o|x.png"
             -DCODE=2 "-DERR=snell-render --2d: " -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
endif()
