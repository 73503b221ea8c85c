# SPDX-License-Identifier: MIT
# snell-bench on glTF scene files (issue 13 item 5), in OUT_DIR; SCENES is
# tests/data/scenes. Checks what follows from the scenes and the references:
#  - exit 0, the per-class table printed (method, alone, ref-alone rows, pixel counts);
#  - the file's objects: three_glass_two_opaque 3 glass + 2 opaque, glass_box 1 + 1;
#  - the classes of the reference's first hit partition the image, none empty;
#  - the method's frame and the objects drawn alone and composed cover >= 90% of the
#    reference's glass pixels (their exit directions are compared there);
#  - the method's background (the skybox, the reference's env lookup) within 1/255
#    RMSE, single's glass pixels far worse: classes not swapped;
#  - the scene layers on by default there (the comparisons with isolate_glass = 0), off
#    with scene_layers=-1, and then the objects drawn alone match the frame (within 0.5 dB);
#  - the isolated reference differs from the whole-scene one only where the view ray
#    meets glass first (an opaque or background pixel's path never meets glass), and
#    on three_glass_two_opaque it does differ there (glass seen through glass);
#  - with one glass object (glass_box) "alone" is the method's frame and the isolated
#    reference is the whole-scene one;
#  - glass seen through glass (whole-scene and isolated references differ) on part of
#    three_glass_two_opaque's glass pixels, nowhere on glass_box;
#  - methods=peel/single: objects 0 and 1 drawn so, object 2 with the spec's cubemap;
#  - --baseline-scene: overlap_1 is its own baseline (vs_scene 1), overlap_2 has a ratio;
#  - spin=: the frame after warm-up peels its scene layers again (a still one reuses them).
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
set(three ${SCENES}/three_glass_two_opaque.gltf)
set(box ${SCENES}/glass_box.gltf)
execute_process(COMMAND ${EXE} -b single:scene=${three}:size=48x48 -b cubemap:scene=${three}:size=48x48
                        -b single:scene=${box}:size=48x48 -b cubemap:scene=${three}:size=48x48:methods=peel/single
                        -b cubemap:scene=${three}:size=48x48:scene_layers=-1
                        --frames 1 --warmup 0 --no-cache -q -o ${OUT_DIR}/bench
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "snell-bench exit ${rc}: ${err}")
endif()
if(NOT out MATCHES "whole scene against FULL with glass seen through glass" OR NOT out MATCHES " method  "
   OR NOT out MATCHES " alone  " OR NOT out MATCHES " ref-alone " OR NOT out MATCHES " pixels  ")
  message(FATAL_ERROR "no per-class table in:\n${out}")
endif()
file(READ "${OUT_DIR}/bench.json" json)
string(JSON n LENGTH "${json}" results)
if(NOT n EQUAL 5)
  message(FATAL_ERROR "expected 5 results, got ${n}")
endif()
# the scene layers: on by default for 3 glass + 2 opaque objects (the MATCHED/FULL comparisons then
# see glass through glass too), off with scene_layers=-1 (the isolated references)
string(JSON iso1 GET "${json}" results 1 reference_isolate_glass)
string(JSON iso4 GET "${json}" results 4 reference_isolate_glass)
string(JSON lay4 GET "${json}" results 4 scene_layers)
if(iso1 OR NOT iso4 OR NOT lay4 EQUAL -1)
  message(FATAL_ERROR "reference_isolate_glass: ${iso1} with the layers (want false), ${iso4} with scene_layers=${lay4} (want true)")
endif()
# each object drawn alone and composed: with the layers off that is what the renderer draws
# (CMake's math is integer: dB in tenths)
function(tenths value out)
  if(NOT value MATCHES "^([0-9]+)(\\.([0-9]))?")
    message(FATAL_ERROR "not a finite PSNR: ${value}")
  endif()
  set(d "${CMAKE_MATCH_3}")
  if(d STREQUAL "")
    set(d 0)
  endif()
  math(EXPR t "${CMAKE_MATCH_1} * 10 + ${d}")
  set(${out} ${t} PARENT_SCOPE)
endfunction()
string(JSON m4 GET "${json}" results 4 whole_scene method glass psnr_db)
string(JSON a4 GET "${json}" results 4 whole_scene alone glass psnr_db)
tenths(${m4} mt)
tenths(${a4} at)
math(EXPR diff "${mt} - ${at}")
if(diff GREATER 5 OR diff LESS -5)
  message(FATAL_ERROR "scene_layers=-1: the frame's glass ${m4} dB, the objects alone ${a4} dB")
endif()
# methods=: objects 0 and 1 by the list, object 2 by the spec's method
foreach(k 0 1 2)
  string(JSON used GET "${json}" results 3 methods_used ${k})
  list(APPEND used_list ${used})
endforeach()
if(NOT used_list STREQUAL "peel;single;cubemap")
  message(FATAL_ERROR "methods=peel/single on cubemap: drawn with ${used_list}")
endif()
math(EXPR last "${n} - 1")
foreach(i RANGE ${last})
  string(JSON spec GET "${json}" results ${i} spec)
  string(JSON ok GET "${json}" results ${i} ok)
  if(NOT ok STREQUAL "ON" AND NOT ok STREQUAL "true")
    string(JSON error ERROR_VARIABLE e GET "${json}" results ${i} error)
    message(FATAL_ERROR "${spec} not ok: ${error}")
  endif()
  string(JSON glass GET "${json}" results ${i} glass_objects)
  string(JSON opaque GET "${json}" results ${i} opaque_objects)
  if(spec MATCHES "three_glass_two_opaque" AND NOT (glass EQUAL 3 AND opaque EQUAL 2))
    message(FATAL_ERROR "${spec}: ${glass} glass, ${opaque} opaque objects")
  endif()
  if(spec MATCHES "glass_box" AND NOT (glass EQUAL 1 AND opaque EQUAL 1))
    message(FATAL_ERROR "${spec}: ${glass} glass, ${opaque} opaque objects")
  endif()
  set(sum 0)
  foreach(cls glass opaque background)
    string(JSON px GET "${json}" results ${i} whole_scene method ${cls} pixels)
    if(NOT px GREATER 0)
      message(FATAL_ERROR "${spec}: no ${cls} pixel")
    endif()
    math(EXPR sum "${sum} + ${px}")
  endforeach()
  string(JSON all GET "${json}" results ${i} whole_scene method all pixels)
  # the method's frame and the composed objects alone cover the glass pixels (exit directions compared)
  foreach(img method alone)
    string(JSON cmp GET "${json}" results ${i} whole_scene ${img} exit_dir_glass compared)
    string(JSON gpx GET "${json}" results ${i} whole_scene ${img} glass pixels)
    math(EXPR want "${gpx} * 9 / 10")
    if(NOT cmp GREATER_EQUAL want)
      message(FATAL_ERROR "${spec}: ${img}: ${cmp} of ${gpx} glass pixels compared")
    endif()
  endforeach()
  if(NOT sum EQUAL 2304 OR NOT all EQUAL 2304)
    message(FATAL_ERROR "${spec}: classes sum to ${sum}, all ${all}, image 2304")
  endif()
  string(JSON bg GET "${json}" results ${i} whole_scene method background rmse)
  string(JSON gl GET "${json}" results ${i} whole_scene method glass rmse)
  # single refracts once only: its glass is far off FULL, classes swapped would show
  if(NOT bg LESS 1.0 OR (spec MATCHES "^single" AND NOT gl GREATER 10.0))
    message(FATAL_ERROR "${spec}: background rmse ${bg} (want < 1), glass ${gl} (single: want > 10)")
  endif()
  foreach(cls opaque background)
    string(JSON r GET "${json}" results ${i} whole_scene reference_isolated ${cls} rmse)
    if(NOT r EQUAL 0)
      message(FATAL_ERROR "${spec}: isolated reference differs on ${cls} pixels (rmse ${r})")
    endif()
  endforeach()
  # glass seen through glass: a part of the glass pixels on three_glass_two_opaque, none with one glass object
  string(JSON thr GET "${json}" results ${i} whole_scene method glass_through_glass pixels)
  string(JSON gpx GET "${json}" results ${i} whole_scene method glass pixels)
  if(spec MATCHES "three_glass_two_opaque" AND NOT (thr GREATER 0 AND thr LESS gpx))
    message(FATAL_ERROR "${spec}: ${thr} of ${gpx} glass pixels see other glass")
  endif()
  if(spec MATCHES "glass_box" AND NOT thr EQUAL 0)
    message(FATAL_ERROR "${spec}: one glass object, yet ${thr} pixels see other glass")
  endif()
  string(JSON r GET "${json}" results ${i} whole_scene reference_isolated glass rmse)
  if(spec MATCHES "three_glass_two_opaque" AND NOT r GREATER 1.0)
    message(FATAL_ERROR "${spec}: isolated reference equals the whole scene on glass (rmse ${r})")
  endif()
  if(spec MATCHES "glass_box")
    if(NOT r EQUAL 0)
      message(FATAL_ERROR "${spec}: one glass object, yet isolation changed its pixels (rmse ${r})")
    endif()
    foreach(cls glass opaque background all)
      string(JSON m GET "${json}" results ${i} whole_scene method ${cls} rmse)
      string(JSON a GET "${json}" results ${i} whole_scene alone ${cls} rmse)
      if(NOT m STREQUAL a)
        message(FATAL_ERROR "${spec}: one glass object, yet alone (${a}) differs from the frame (${m}) on ${cls}")
      endif()
    endforeach()
  endif()
endforeach()

execute_process(COMMAND ${EXE} -b single:scene=${SCENES}/overlap_1.gltf:size=32x32
                        -b single:scene=${SCENES}/overlap_2.gltf:size=32x32
                        -b single:scene=${SCENES}/overlap_2.gltf:size=32x32:spin=2 --baseline-scene ${SCENES}/overlap_1.gltf
                        --frames 3 --warmup 1 --no-cache -q -o ${OUT_DIR}/overlap
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "snell-bench --baseline-scene exit ${rc}: ${err}")
endif()
file(READ "${OUT_DIR}/overlap.json" json)
string(JSON r1 GET "${json}" results 0 vs_scene)
string(JSON r2 GET "${json}" results 1 vs_scene)
string(JSON g2 GET "${json}" results 1 glass_objects)
if(NOT r1 EQUAL 1 OR NOT r2 GREATER 0 OR NOT g2 EQUAL 2 OR NOT out MATCHES "xscene")
  message(FATAL_ERROR "--baseline-scene: vs_scene ${r1} (want 1), ${r2} (want > 0), ${g2} glass objects:\n${out}")
endif()
# a still scene's frame after warm-up reuses its scene layers; spin=2 turns the camera, so they are peeled again
string(JSON still GET "${json}" results 1 scene_layer_passes)
string(JSON moving GET "${json}" results 2 scene_layer_passes)
if(NOT still EQUAL 0 OR NOT moving GREATER 0)
  message(FATAL_ERROR "scene-layer peels after warm-up: ${still} still (want 0), ${moving} with spin=2 (want > 0)")
endif()
message(STATUS "snell-bench on scene files: ${n} configurations ok, vs_scene ${r2}")
