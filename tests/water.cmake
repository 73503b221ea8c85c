# Water (snell_water_*, src/water/, ref/ref_water.c; issue 17).
# test_water_sim: the CPU simulation, no GL (100,000 steps of 64^2 twice; ~3 s).
snell_add_test(test_water_sim SOURCES test_water_sim.c LABELS "unit")
target_link_libraries(test_water_sim PRIVATE m)
# test_water_gl: GPU simulation against the CPU one, its settle check, and the
# still and rippled water frames against snell_ref_water_render (~10 s).
snell_add_test(test_water_gl SOURCES test_water_gl.c LABELS "render;gl")
target_link_libraries(test_water_gl PRIVATE m)
