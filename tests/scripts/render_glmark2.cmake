# SPDX-License-Identifier: MIT
# render_glmark2.cmake — snell-render --mesh draws every model of glmark2-data
# (.3ds, .obj, .jobj): each exits 0, writes its PNG and its stats name the
# one glass object with the method that drew it.
# Run: cmake -DEXE=<snell-render> -DMODELS=<dir> -DOUT_DIR=<scratch> -P render_glmark2.cmake
file(GLOB models ${MODELS}/*.3ds ${MODELS}/*.obj ${MODELS}/*.jobj)
if(NOT models)
  message(FATAL_ERROR "no models in ${MODELS}")
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
foreach(m IN LISTS models)
  get_filename_component(name ${m} NAME)
  set(png ${OUT_DIR}/${name}.png)
  file(REMOVE ${png})
  execute_process(COMMAND ${EXE} --mesh ${m} --size 64x64 --stats -o ${png}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "snell-render --mesh ${m}: exit ${rc}\n${err}")
  endif()
  string(FIND "${out}${err}" "glass 0 (${m}, ior 1.5): method " at)
  if(at LESS 0 OR NOT EXISTS ${png})
    message(FATAL_ERROR "snell-render --mesh ${m}: no glass object drawn or no ${png}\n${out}${err}")
  endif()
  message(STATUS "${name}: drawn, ${png}")
endforeach()
