# Foundation tests: context, shaders, optics twin, single-surface render, CLI, install.
snell_add_test(test_ctx SOURCES test_ctx.c LABELS "unit;gl")
target_link_libraries(test_ctx PRIVATE PkgConfig::EGL PkgConfig::GLES)
snell_add_test(test_shader SOURCES test_shader.c LABELS "unit;gl")
target_link_libraries(test_shader PRIVATE PkgConfig::GLES)
snell_add_test(test_optics_twin SOURCES test_optics_twin.c LABELS "unit;gl")
target_link_libraries(test_optics_twin PRIVATE PkgConfig::GLES m)
snell_add_test(test_render_single SOURCES test_render_single.c LABELS "render;gl")
target_link_libraries(test_render_single PRIVATE m)
