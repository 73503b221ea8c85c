# SPDX-License-Identifier: MIT
# The CLI ports with a scene (issue 9): repeated --mesh with per-object options and
# --opaque objects, per-object statistics (each object's method and why), methods and
# parameters from the library's registry, --trace-pixel through a scene, and
# snell-bench on multi-object scenes. Usage errors exit 2 with "PROG: " messages.
if(TARGET snell-render)
  set(cli $<TARGET_FILE:snell-render>)
  set(d ${CMAKE_CURRENT_SOURCE_DIR}/data)
  set(expect ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  # Every model of glmark2-data (Debian's package; in the quick start's list): .3ds, .obj, .jobj.
  if(EXISTS /usr/share/glmark2/models)
    add_test(NAME cli_glmark2_models COMMAND ${CMAKE_COMMAND} -DEXE=${cli} -DMODELS=/usr/share/glmark2/models
             -DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/glmark2_models -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/render_glmark2.cmake)
    set_tests_properties(cli_glmark2_models PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  endif()
  # Glass options before the first --mesh are every object's defaults; after a --mesh, its own.
  add_test(NAME cli_scene_objects COMMAND ${cli} --ior 1.2 --mesh sphere --place -1,0,0,0.5 --mesh goblet
           --place 1,0,0,0.5 --ior 2 --mesh shape:cube --place 0,1,0,0.4 --method single --opaque torus
           --place 0,-1,0,0.5 --color 0.2,0.6,0.9 --stats --size 32x32 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_scene.png)
  set_tests_properties(cli_scene_objects PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "glass 3, opaque drawn 1.*glass 0 \\(sphere, ior 1.2\\): method layered, warning 0.*reason: auto.*glass 1 \\(goblet, ior 2\\): method peel, warning 0.*reason: auto: closed, depth complexity.*glass 2 \\(cube, ior 1.2\\): method single.*reason: requested.*wrote .*cli_scene.png")
  # -v: the same statistics on stderr
  add_test(NAME cli_scene_verbose COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}"
           "-DARGS=--mesh|sphere|--place|-1,0,0,0.5|--mesh|cube|--place|1,0,0,0.5|-v|--size|16x16|-o|${CMAKE_CURRENT_BINARY_DIR}/cli_verbose.png"
           -DCODE=0 "-DERR=stats: glass 1 \\(cube, ior 1.5\\): method layered" -P ${expect})
  set_tests_properties(cli_scene_verbose PROPERTIES LABELS "cli;gl")
  # An open mesh: AUTO never picks cubemap; an explicit cubemap renders but warns.
  add_test(NAME cli_open_auto COMMAND ${cli} --mesh ${d}/quad_ngon.obj --method auto --stats --size 32x32
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_open.png)
  set_tests_properties(cli_open_auto PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "quad_ngon.obj, ior 1.5\\): method single, warning 0.*reason: auto fallback.*closed mesh.*boundary")
  add_test(NAME cli_open_cubemap_warns COMMAND ${cli} --mesh ${d}/quad_ngon.obj --method cubemap --stats --size 32x32
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_open_cubemap.png)
  set_tests_properties(cli_open_cubemap_warns PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "quad_ngon.obj, ior 1.5\\): method cubemap, warning 1.*reason: requested, but")
  # Registry names: a clear message listing the methods; parameters by name.
  add_test(NAME cli_unknown_method COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--mesh|sphere|--method|nosuch" -DCODE=2
           "-DERR=snell-render: unknown method 'nosuch'; methods: auto, single, layered, cubemap, wyman, oliveira, peel" -P ${expect})
  set_tests_properties(cli_unknown_method PROPERTIES LABELS "cli")
  add_test(NAME cli_param COMMAND ${cli} --mesh sphere --method cubemap --param cubemap.iterations=3 --param encoding=oct
           --linear_steps 2 --stats --size 16x16 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_param.png)
  set_tests_properties(cli_param PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "\\(sphere, ior 1.5\\): method cubemap")
  # A parameter only other methods have is refused for --method M, not ignored (AUTO takes any)
  set(one_error ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_one_error.cmake)
  add_test(NAME cli_key_of_other_method COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--method|single|--face_size|64" -DCODE=2
           "-DERR=^snell-render: --face_size is a parameter of [a-z, ]*cubemap[a-z, ]*, not of --method single \\(the default sphere\\). see --help$"
           -P ${one_error})
  add_test(NAME cli_qualified_key_of_other_method COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}"
           "-DARGS=--mesh|sphere|--param|cubemap.face_size=64|--method|single" -DCODE=2
           "-DERR=^snell-render: --face_size is a parameter of cubemap, not of --method single \\(--mesh sphere\\). see --help$"
           -P ${one_error})
  add_test(NAME cli_key_auto COMMAND ${cli} --face_size 64 --size 16x16 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_key_auto.png)
  # getopt_long: one message per error
  add_test(NAME cli_unexpected_argument COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--size|16x16|stray" -DCODE=2
           "-DERR=^snell-render: unexpected argument 'stray'. see --help$" -P ${one_error})
  add_test(NAME cli_no_value COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--mesh|sphere|--ior" -DCODE=2
           "-DERR=^snell-render: --ior needs a value. see --help$" -P ${one_error})
  add_test(NAME cli_version COMMAND ${cli} --version)
  set_tests_properties(cli_version PROPERTIES PASS_REGULAR_EXPRESSION
    "^snell-render [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit ([0-9a-f]+(-dirty)?|unknown)\\)\n$")
  add_test(NAME cli_2d_opt_unknown COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--2d|--bogus" -DCODE=2
           "-DERR=^snell-render --2d: unknown option '--bogus'. see --2d --help$" -P ${one_error})
  add_test(NAME cli_water_opt_unexpected COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--water|stray" -DCODE=2
           "-DERR=^snell-render --water: unexpected argument 'stray'. see --water --help$" -P ${one_error})
  set_tests_properties(cli_key_of_other_method cli_qualified_key_of_other_method cli_unexpected_argument cli_no_value
                       cli_version cli_2d_opt_unknown cli_water_opt_unexpected PROPERTIES LABELS "cli")
  set_tests_properties(cli_key_auto PROPERTIES LABELS "cli;gl")
  add_test(NAME cli_help_registry COMMAND ${cli} --help)
  set_tests_properties(cli_help_registry PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION
    "method cubemap: .*--iterations V +1\\.\\.32 \\(default 6\\).*--encoding V +default\\|plain\\|oct \\(default plain\\)")
  # --env-lookup: the stats say which look-up each object used
  add_test(NAME cli_env_lookup COMMAND ${cli} --mesh sphere --opaque cube --place 0,0,-2,0.5 --env-lookup paraboloid-direct
           --stats --size 32x32 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_env_lookup.png)
  set_tests_properties(cli_env_lookup PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "glass 0 \\(sphere, ior 1.5\\): method layered.*env dual-paraboloid.*wrote .*cli_env_lookup.png")
  add_test(NAME cli_env_lookup_bad COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=--env-lookup|sphere" -DCODE=2
           "-DERR=snell-render: --env-lookup: unknown look-up 'sphere' \\(auto, cube, paraboloid, paraboloid-direct\\)"
           -P ${expect})
  set_tests_properties(cli_env_lookup_bad PROPERTIES LABELS "cli")
  foreach(bad "--color|1,1,1" "--place|1,0,0|--mesh|cube" "--mesh|cube|--place|1,2" "--mesh|cube|--place|0,0,0,0"
              "--param|nosuch=1" "--param|cubemap.iterations=99" "--param|iterations" "--attenuation|1,1,1"
              "--mesh|cube|--thickness|-1" "--opaque|shape:blob" "--opaque|65" "--mesh|cube|--encoding|rgb")
    string(MAKE_C_IDENTIFIER "cli_scene_bad_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${cli}" "-DARGS=${bad}" -DCODE=2 "-DERR=snell-render: "
             -P ${expect})
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  # --trace-pixel through a scene of two glass spheres and an opaque cube.
  add_test(NAME cli_trace_scene COMMAND ${cli} --mesh sphere --place -0.7,0,0,0.6 --mesh sphere --place 0.7,0,0,0.6
           --opaque cube --place 0,0,-2,0.5 --camera 0,0,4 --size 32x32 --trace-pixel 10,16 --trace-pixel 16,2
           -o ${CMAKE_CURRENT_BINARY_DIR}/cli_trace.png)
  set_tests_properties(cli_trace_scene PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION
    "pixel 10,16: FULL [1-9][0-9]* interface\\(s\\).*first hit glass 0.*wrote .*cli_trace_trace.json.*wrote .*cli_trace_trace.png")
endif()

if(TARGET snell-bench)
  set(bench $<TARGET_FILE:snell-bench>)
  add_test(NAME bench_scenes COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_scenes"
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench_scenes.cmake)
  set_tests_properties(bench_scenes PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  # glTF scene files: per-class errors against the whole-scene reference (issue 13 item 5)
  add_test(NAME bench_scene_file COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DSCENES=${d}/scenes"
           "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_scene_file" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench_scene_file.cmake)
  set_tests_properties(bench_scene_file PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  add_test(NAME bench_scene_file_material COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}"
           "-DARGS=-b|single:scene=${d}/scenes/glass_box.gltf:ior=1.3" -DCODE=2
           "-DERR=snell-bench: ior=: scene=.*glass_box.gltf brings its own materials" -P ${expect})
  set_tests_properties(bench_scene_file_material PROPERTIES LABELS "cli")
  add_test(NAME bench_scene_file_missing COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}"
           "-DARGS=-b|single:size=8x8|--scene|${CMAKE_CURRENT_BINARY_DIR}/no_such_scene.gltf|--no-cache" -DCODE=1
           "-DERR=snell-bench: scene .*no_such_scene.gltf: " -P ${expect})
  set_tests_properties(bench_scene_file_missing PROPERTIES LABELS "cli;gl")
  add_test(NAME bench_list_registry COMMAND ${bench} --list)
  set_tests_properties(bench_list_registry PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION
    "pair .*many .*method cubemap: .*iterations +1\\.\\.32 \\(default 6\\)")
  add_test(NAME bench_unknown_method COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=-b|nosuch:scene=pair" -DCODE=2
           "-DERR=snell-bench: unknown method 'nosuch' in 'nosuch:scene=pair'; methods: auto, single, layered, cubemap, wyman, oliveira, peel"
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(bench_unknown_method PROPERTIES LABELS "cli")
endif()
