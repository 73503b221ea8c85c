# Dispersion (material.dispersion, core/optics.h, common/dispersion.glsl, ref/ref_trace.c):
# the channels' IORs, the reference's per-channel traces, and every kernel in both
# variants on a prism and a sphere against the per-channel reference.
snell_add_test(test_dispersion SOURCES test_dispersion.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_dispersion PRIVATE m)
