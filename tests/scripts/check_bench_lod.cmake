# SPDX-License-Identifier: MIT
# snell-bench lod=: the glass mesh is simplified before timing and the
# references keep the original, so the error includes the simplification:
# at lod=0.25 the error against MATCHED (single-surface: its own model, ~0 at
# lod=1) must be well above lod=1's; stderr reports the triangle counts.
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
execute_process(COMMAND ${EXE} -b single:scene=sphere:size=64x64:lod=1,0.25 --frames 3 --warmup 1 --no-cache
                        -o ${OUT_DIR}/bench
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "snell-bench exit ${rc}: ${err}")
endif()
if(NOT err MATCHES "lod=0.25: [0-9]+ -> [0-9]+ triangles")
  message(FATAL_ERROR "no simplification reported on stderr: ${err}")
endif()
file(READ "${OUT_DIR}/bench.json" json)
string(JSON n LENGTH "${json}" results)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "expected 2 results, got ${n}")
endif()
foreach(i 0 1)
  string(JSON spec${i} GET "${json}" results ${i} spec)
  string(JSON ok GET "${json}" results ${i} ok)
  string(JSON e${i} GET "${json}" results ${i} vs_matched mean_deg)
  if(NOT ok STREQUAL "ON" AND NOT ok STREQUAL "true")
    message(FATAL_ERROR "${spec${i}} not ok")
  endif()
endforeach()
if(NOT spec0 MATCHES "lod=1$" OR NOT spec1 MATCHES "lod=0.25$")
  message(FATAL_ERROR "specs ${spec0}, ${spec1}")
endif()
if(NOT e1 GREATER 0.05 OR NOT e0 LESS 0.01)
  message(FATAL_ERROR "vs MATCHED: lod=1 ${e0} deg, lod=0.25 ${e1} deg (want < 0.01 and > 0.05: the reference "
                      "must keep the original mesh)")
endif()
message(STATUS "lod: vs MATCHED ${e0} deg at lod=1, ${e1} deg at lod=0.25")
