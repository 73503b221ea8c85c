# SPDX-License-Identifier: MIT
# cli_panels.cmake — snell-render --panels end to end (tests/panels_ports.cmake):
# the default scene's frame, the same frame with a panels file over it, and
# the panels over that frame given as --under's picture (and, with REFERENCE,
# snell_ref_panels' images of both beside them): each must differ from the plain frame
# inside the panel's box and equal it away from it (panels_diff).
# With KIOSK: snell-kiosk --preview the same way, over its scene and over a
# --slide of its plain frame.
# Run: cmake -DEXE=snell-render [-DREFERENCE=1] | -DKIOSK=snell-kiosk
#      -DDIFF=panels_diff -DPANELS=file -DBOX=x0,y0,x1,y1 -DOUT_DIR=dir -P cli_panels.cmake
file(MAKE_DIRECTORY ${OUT_DIR})
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${what}: ${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: exit ${rc}")
  endif()
  set(last_out "${out}" PARENT_SCOPE)
endfunction()
if(KIOSK)
  set(spec -b single:scene=sphere --mode 96x64)
  run("kiosk: plain" ${KIOSK} ${spec} --preview ${OUT_DIR}/kiosk_plain.png)
  run("kiosk: panels over the scene" ${KIOSK} ${spec} --panels ${PANELS} --preview ${OUT_DIR}/kiosk_scene.png)
  if(NOT last_out MATCHES "1 panels from .*: 1 drawn")
    message(FATAL_ERROR "the kiosk does not say one panel was drawn")
  endif()
  run("kiosk scene: pixels" ${DIFF} ${OUT_DIR}/kiosk_plain.png ${OUT_DIR}/kiosk_scene.png ${BOX} 2)
  run("kiosk: panels over a slide" ${KIOSK} ${spec} --panels ${PANELS} --slide ${OUT_DIR}/kiosk_plain.png
      --preview ${OUT_DIR}/kiosk_slide.png)
  run("kiosk slide: pixels" ${DIFF} ${OUT_DIR}/kiosk_plain.png ${OUT_DIR}/kiosk_slide.png ${BOX} 2)
  return()
endif()
run("plain frame" ${EXE} --size 96x64 -o ${OUT_DIR}/plain.png)
set(ref "")
if(REFERENCE)
  set(ref --reference)
endif()
run("panels over the scene" ${EXE} --size 96x64 --panels ${PANELS} --stats ${ref} -o ${OUT_DIR}/scene.png)
if(NOT last_out MATCHES "stats: panels: 1 drawn")
  message(FATAL_ERROR "the stats do not say one panel was drawn")
endif()
run("scene: pixels" ${DIFF} ${OUT_DIR}/plain.png ${OUT_DIR}/scene.png ${BOX} 2)
run("panels over --under" ${EXE} --panels ${PANELS} --under ${OUT_DIR}/plain.png ${ref} -o ${OUT_DIR}/under.png)
if(NOT last_out MATCHES "wrote .*under.png \\(96x64\\)")
  message(FATAL_ERROR "--under did not give the frame the picture's size")
endif()
run("under: pixels" ${DIFF} ${OUT_DIR}/plain.png ${OUT_DIR}/under.png ${BOX} 2)
if(REFERENCE)
  run("reference over the scene: pixels" ${DIFF} ${OUT_DIR}/plain.png ${OUT_DIR}/scene_reference.png ${BOX} 2)
  run("reference over --under: pixels" ${DIFF} ${OUT_DIR}/plain.png ${OUT_DIR}/under_reference.png ${BOX} 2)
endif()
