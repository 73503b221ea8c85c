# The scene and the method seam (issue 9: src/render/scene.c, renderer.c,
# prepared.c, env_dynamic.c, composite.c, methods/registry.c): registry and
# material resolve, AUTO's per-object choice, order, skips, 8 glass + 4
# opaque objects against the reference tracer.
snell_add_test(test_scene SOURCES test_scene.c LABELS "render;gl" SHADINGS forward screen)
target_link_libraries(test_scene PRIVATE m)
