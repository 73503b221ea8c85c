# SPDX-License-Identifier: MIT
# Reference tracer (snell_ref_*, src/ref/*.c): BVH (one or several parts),
# analytic checks (sphere, slab, TIR prism; scenes of several glass objects,
# thin walls, opaque objects), image-level properties of single objects and
# scenes (determinism, energy, object ids, separation, isolate_glass) and
# renders of a sphere, the bunny and a scene.
snell_add_test(test_ref_bvh SOURCES test_ref_bvh.c LABELS "unit")
target_link_libraries(test_ref_bvh PRIVATE m)
snell_add_test(test_ref_analytic SOURCES test_ref_analytic.c LABELS "unit")
target_link_libraries(test_ref_analytic PRIVATE m)
# FULL where smooth normals and the triangles' planes disagree (issue 15's
# bunny base): a smooth-shaded cube's grazing rays and every path's sides.
snell_add_test(test_ref_shading_normals SOURCES test_ref_shading_normals.c LABELS "unit")
target_link_libraries(test_ref_shading_normals PRIVATE m)
# snell_ref_params.progress: called, never decreasing, rate-limited, ends at 1.0 (issue 28 item 7).
snell_add_test(test_ref_progress SOURCES test_ref_progress.c LABELS "unit")
target_link_libraries(test_ref_progress PRIVATE m)
snell_add_test(test_ref_render SOURCES test_ref_render.c LABELS "render")
target_link_libraries(test_ref_render PRIVATE m)
snell_add_test(test_ref_gpu_single SOURCES test_ref_gpu_single.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_ref_gpu_single PRIVATE m)
# Supersampling (snell_renderer_desc.ssaa, render/ssaa.c): the resolved frame
# against the block means of the large one; refused settings.
snell_add_test(test_ssaa SOURCES test_ssaa.c LABELS "render;gl" SHADINGS forward screen)
# Glass panels' reference (snell_ref_panels, src/ref/ref_panels.c) against
# values derived from snell_panels.h's model; hostile input (issue 51).
snell_add_test(test_ref_panels SOURCES test_ref_panels.c LABELS "unit")
target_link_libraries(test_ref_panels PRIVATE m)
