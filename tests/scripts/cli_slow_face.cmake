# SPDX-License-Identifier: MIT
# Issue 26 item 1 through the CLI: one OBJ face of 120,000 corners on 3
# vertices (119,998 triangles, 40,000 of them the same one) rendered by
# snell-render. Its vertex-cache reorder took 66 s here; now the upload skips
# it for the linear FIFO order and says so at WARN, with the work estimate
# against its bound: that line is the deterministic check. The wall-clock
# bound (20 s x SNELL_TEST_TIME_SCALE; 1.5 s here, the default sphere 1.3 s) only
# catches a stage gone quadratic again; execute_process's TIMEOUT ends a run
# past it. Usage: cmake -DEXE=snell-render -DOUT=dir -P cli_slow_face.cmake
string(REPEAT " 1 2 3" 40000 corners)
file(WRITE "${OUT}/slow_face.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf${corners}\n")
set(scale 1)
if(DEFINED ENV{SNELL_TEST_TIME_SCALE})
  set(scale $ENV{SNELL_TEST_TIME_SCALE})
endif()
math(EXPR limit "20 * ${scale}")
string(TIMESTAMP t0 "%s")
execute_process(COMMAND ${EXE} --mesh "${OUT}/slow_face.obj" --size 128x128 --stats -o "${OUT}/slow_face.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT ${limit})
string(TIMESTAMP t1 "%s")
math(EXPR dt "${t1} - ${t0}")
message(STATUS "snell-render on the 120,000-corner face: exit ${rc}, ${dt} s (bound ${limit} s)")
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "snell-render exit '${rc}' (bound ${limit} s); stderr: ${err}")
endif()
if(NOT err MATCHES "vertex-cache reorder skipped for the linear FIFO order: work 5\\.28e\\+10 over its bound 5\\.66e\\+07 \\(199996 corners on one vertex\\); 39999 copies of triangles not drawn")
  message(FATAL_ERROR "no warning that the reorder was skipped, with its work and bound; stderr: ${err}")
endif()
if(NOT out MATCHES "glass 0 \\(.*slow_face.obj, ior 1.5\\): method single")
  message(FATAL_ERROR "stats: ${out}")
endif()
