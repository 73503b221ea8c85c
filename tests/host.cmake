# SPDX-License-Identifier: MIT
# The library in a careless or hostile host's hands (issue 14): contexts,
# host GL state (EXTERNAL), pixel buffers, destroy order, NULL/NaN lookups,
# camera and model values; the CLI's --env pattern; and the long run (flat
# RSS and GL object counts over 2,000 varied frames and 500 create/destroy
# cycles), labelled "longrun" only so that the sanitizer legs skip it.
snell_add_test(test_host SOURCES test_host.c LABELS "unit;gl")
target_link_libraries(test_host PRIVATE snell_dep::egl snell_dep::gles m)

snell_add_test(test_longrun SOURCES test_longrun.c LABELS "longrun" TIMEOUT 600)
target_link_libraries(test_longrun PRIVATE snell_dep::gles m)

if(TARGET snell-render)
  # --env is a file name, never a printf format: %s is the face, %% a percent
  # sign, anything else after a % a usage error (exit 2), not a write through %n.
  foreach(bad "%s_%n" "%n" "sky%d.png" "a%" "%s%s%x")
    string(MAKE_C_IDENTIFIER "cli_env_format_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>" "-DARGS=--env|${bad}|--size|8x8"
             -DCODE=2 "-DERR=snell-render: --env '.*': .*only %s" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  add_test(NAME cli_env_format_bench COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-bench>"
           "-DARGS=--env|%s_%n|-b|single" -DCODE=2 "-DERR=snell-bench: --env '%s_%n': " -P
           ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(cli_env_format_bench PROPERTIES LABELS "cli")
  # Each %s is a face name, %% one '%', as the message's file name shows.
  add_test(NAME cli_env_format_expand COMMAND $<TARGET_FILE:snell-render> --env /nonexistent/%s_%%_%s.png --size 8x8
           -o ${CMAKE_CURRENT_BINARY_DIR}/x.png)
  set_tests_properties(cli_env_format_expand PROPERTIES LABELS "cli"
                       PASS_REGULAR_EXPRESSION "cannot open image \"/nonexistent/px_%_px.png\"")
endif()

# Glass in a host's world: its off-axis camera as matrices, its depth kept and
# tested, its depth given back (NO_WRITE); orbit and matrices byte-identical.
snell_add_test(test_host_world SOURCES test_host_world.c LABELS "render;gl")
target_link_libraries(test_host_world PRIVATE PkgConfig::EGL PkgConfig::GLES m)

# snell-render --view/--projection: a host's off-axis camera and an
# orthographic one render; a projection neither perspective nor orthographic
# is refused (exit 1, naming the field); --view alone or with --camera is a
# usage error (exit 2).
if(TARGET snell-render)
  set(view "0.866,-0.117,0.486,0,0,0.972,0.234,0,-0.5,-0.203,0.842,0,0,0,-3.5,1")
  add_test(NAME cli_camera_matrices COMMAND snell-render --view ${view}
           --projection 2.414,0,0,0,0,2.414,0,0,0.3,0.2,-1.002,-1,0,0,-0.07,0 --size 32x24
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_camera_matrices.png)
  add_test(NAME cli_camera_ortho COMMAND snell-render --view ${view} --projection 0.7,0,0,0,0,0.7,0,0,0,0,-0.2,0,0,0,-1.01,1
           --mesh torus --size 32x32 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_camera_ortho.png)
  set_tests_properties(cli_camera_matrices cli_camera_ortho PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION "wrote .*32x")
  add_test(NAME cli_camera_projective COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--view|${view}|--projection|2.4,0,0,0.2,0,2.4,0,0,0,0,-1,-1,0,0,-0.07,0|--size|8x8" -DCODE=1
           "-DERR=snell-render: render: snell_render: camera.projection's bottom row" -P
           ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  add_test(NAME cli_camera_view_alone COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-render>"
           "-DARGS=--view|${view}|--size|8x8" -DCODE=2 "-DERR=snell-render: --view and --projection go together" -P
           ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(cli_camera_projective cli_camera_view_alone PROPERTIES LABELS "cli")
  # snell-bench takes the same matrices: every scene's frame and reference through them
  add_test(NAME bench_camera_matrices COMMAND snell-bench --view ${view}
           --projection 2.414,0,0,0,0,2.414,0,0,0.3,0.2,-1.002,-1,0,0,-0.07,0 -b single --scenes sphere --sizes 32x32
           --frames 1 --warmup 0 --no-cache -q -o ${CMAKE_CURRENT_BINARY_DIR}/bench_camera_matrices)
  set_tests_properties(bench_camera_matrices PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "wrote .*bench_camera_matrices.json")
  add_test(NAME bench_camera_view_alone COMMAND ${CMAKE_COMMAND} "-DEXE=$<TARGET_FILE:snell-bench>"
           "-DARGS=--view|${view}|-b|single" -DCODE=2 "-DERR=snell-bench: --view and --projection go together" -P
           ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(bench_camera_view_alone PROPERTIES LABELS "cli")
endif()

# The cameras engines use (issue 48): reversed-Z, infinite far, oblique near,
# mirrored and scaled views as matrices, each the image of its standard
# equivalent in every method and the reference; bad ones refused by name.
snell_add_test(test_camera_engines SOURCES test_camera_engines.c LABELS "render;gl")
target_link_libraries(test_camera_engines PRIVATE PkgConfig::GLES m)

# The host's scene behind the glass (snell_frame_desc.backdrop): a host's
# frame and depth as textures or copied from its framebuffer, searched by
# every glass's exit rays; against the reference with the same backdrop.
snell_add_test(test_backdrop SOURCES test_backdrop.c LABELS "render;gl" TIMEOUT 600)
target_link_libraries(test_backdrop PRIVATE PkgConfig::EGL PkgConfig::GLES m)

# The host's sky (issue 48): rays that meet nothing take the host's colour
# where their direction vanishes over its far plane, standard and reversed-Z,
# every method against the reference. `test_backdrop_sky PATH` also draws
# docs/host_sky.png (the app's sky cube as SNELL_ENV_GL_TEXTURE).
snell_add_test(test_backdrop_sky SOURCES test_backdrop_sky.c LABELS "render;gl")
target_link_libraries(test_backdrop_sky PRIVATE PkgConfig::GLES m)

# The host's cube map as the environment (SNELL_ENV_GL_TEXTURE): borrowed, not copied.
snell_add_test(test_env_gl SOURCES test_env_gl.c LABELS "render;gl")
target_link_libraries(test_env_gl PRIVATE PkgConfig::GLES)

# Premultiplied alpha over a transparent target: the composite over a colour
# is the frame drawn in a world of that colour, every method.
snell_add_test(test_premultiplied SOURCES test_premultiplied.c LABELS "render;gl" TIMEOUT 600)
target_link_libraries(test_premultiplied PRIVATE PkgConfig::GLES)

# examples/host_scene.c: an app with its own context, shaders and a walking
# first-person camera puts a glass bunny and a sphere into its scene (its
# matrices, its depth tested, its frame copied and refracted). Built and run;
# exit 0 when the glass was drawn into the app's frame searched against its depth.
add_executable(host_scene ${PROJECT_SOURCE_DIR}/examples/host_scene.c)
target_link_libraries(host_scene PRIVATE snell_static PkgConfig::EGL PkgConfig::GLES m)
add_test(NAME example_host_scene COMMAND host_scene ${CMAKE_CURRENT_BINARY_DIR}/host_scene.png)
set_tests_properties(example_host_scene PROPERTIES LABELS "render;gl" SKIP_RETURN_CODE 77
                     PASS_REGULAR_EXPRESSION "searched against the app's depth")
# test_resolve_order: a frame's and a material's descriptions resolved once, then the resolved copy
# validated (sokol_gfx's order): refusals name the resolved value and never re-encode a default.
snell_add_test(test_resolve_order SOURCES test_resolve_order.c LABELS "unit;gl")
target_link_libraries(test_resolve_order PRIVATE snell_dep::gles)

# Glass panels (issue 51): the stage against snell_ref_panels over an app's
# texture: glass PSNR of a clear, a frosted, a dispersive and a merged panel.
snell_add_test(test_panels_ref SOURCES test_panels_ref.c LABELS "render;gl")
target_link_libraries(test_panels_ref PRIVATE PkgConfig::GLES m)
