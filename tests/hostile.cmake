# SPDX-License-Identifier: MIT
# Hostile files (issue 14): glTF URIs leaving the model's folder, coordinates at
# the float range, coincident triangles, the memory budget and the messages of
# refused files. Inputs under tests/data/hostile (make_hostile.py), bigger ones
# made at run time. The budget cases need a context (memory_budget): label gl.
snell_add_test(test_hostile_files SOURCES test_hostile_files.c LABELS "unit")
target_link_libraries(test_hostile_files PRIVATE m)
snell_add_test(test_hostile_files_ctx SOURCES test_hostile_files.c LABELS "unit;gl" ARGS ctx)
target_link_libraries(test_hostile_files_ctx PRIVATE m)
# Hostile input, fourth round (issue 40): one function per item of the issue.
snell_add_test(test_hostile_inputs4 SOURCES test_hostile_inputs4.c LABELS "unit")
target_link_libraries(test_hostile_inputs4 PRIVATE m)
snell_add_test(test_hostile_inputs4_ctx SOURCES test_hostile_inputs4.c LABELS "unit;gl" ARGS ctx)
target_link_libraries(test_hostile_inputs4_ctx PRIVATE m)
# Hostile input, fifth round (issue 49): one function per finding.
snell_add_test(test_hostile_inputs5 SOURCES test_hostile_inputs5.c LABELS "unit")
snell_add_test(test_hostile_inputs5_ctx SOURCES test_hostile_inputs5.c LABELS "unit;gl" ARGS ctx)
# Issue 49 item 1 through the tools: every path that reads a mesh, a JSON or a
# configuration, handed a FIFO (NAME|FIFO|EXIT|stderr regex|ARGS, @F@ = the FIFO).
set(fifo_dir ${CMAKE_CURRENT_BINARY_DIR}/hostile5_fifo)
file(MAKE_DIRECTORY ${fifo_dir})
set(fifo_cases)
if(TARGET snell-render)
  set(r $<TARGET_FILE:snell-render>)
  list(APPEND fifo_cases
    "fifo_render_mesh_3ds|m.3ds|1|'.*m.3ds' is not a regular file|${r}|--mesh|@F@|--size|8x8|-o|${fifo_dir}/x.png"
    "fifo_render_opaque_jobj|o.jobj|1|'.*o.jobj' is not a regular file|${r}|--opaque|@F@|--size|8x8|-o|${fifo_dir}/x.png"
    "fifo_render_water_glass|w.3ds|2|'.*w.3ds' is not a regular file|${r}|--water|--glass|@F@:0,0,0,1|--size|8x8|-o|${fifo_dir}/x.png")
endif()
if(TARGET snell-bench)
  set(b $<TARGET_FILE:snell-bench>)
  list(APPEND fifo_cases
    "fifo_bench_scene|s.jobj|1|'.*s.jobj' is not a regular file|${b}|-b|single:scene=@F@|--frames|1|--no-cache|-o|${fifo_dir}/bench"
    "fifo_bench_compare|c.json|1|^snell-bench --compare: cannot read '.*c.json': not a regular file|${b}|--compare|@F@|@F@")
endif()
if(TARGET snell-kiosk)
  set(k $<TARGET_FILE:snell-kiosk>)
  list(APPEND fifo_cases
    "fifo_kiosk_config|k.conf|2|^snell-kiosk: --config .*k.conf: not a regular file|${k}|--config|@F@"
    "fifo_kiosk_scene|k.3ds|1|'.*k.3ds' is not a regular file|${k}|-b|single:scene=@F@|--preview|${fifo_dir}/k.png|--mode|16x16")
endif()
foreach(case IN LISTS fifo_cases)
  string(REPLACE "|" ";" f "${case}")
  list(POP_FRONT f name fifo code err exe)
  string(REPLACE ";" "|" args "${f}")
  string(REPLACE "@F@" "${fifo_dir}/${fifo}" args "${args}")
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${exe}" "-DARGS=${args}" "-DFIFO=${fifo_dir}/${fifo}"
           -DCODE=${code} "-DERR=${err}" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_fifo.cmake)
  set_tests_properties(${name} PROPERTIES LABELS "cli;gl" TIMEOUT 30)
endforeach()
