# SPDX-License-Identifier: MIT
# snell-bench: a tiny interleaved sweep and its outputs; bad specs.
if(TARGET snell-bench)
  set(bench $<TARGET_FILE:snell-bench>)
  add_test(NAME bench_sweep COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_sweep"
           -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench.cmake)
  set_tests_properties(bench_sweep PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  if(SNELL_WITH_MESHOPT)
    add_test(NAME bench_lod COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DOUT_DIR=${CMAKE_CURRENT_BINARY_DIR}/bench_lod"
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_bench_lod.cmake)
    set_tests_properties(bench_lod PROPERTIES LABELS "cli;gl" TIMEOUT 300)
  endif()
  # bench/band_check.sh (issue 25's two speed-against-error criteria) runs on this build and gives
  # both verdicts; at 48x48 without antialiasing (about 6 s) the verdicts themselves mean nothing
  set(band_methods oliveira layered peel exact)
  set(band_ok ${SNELL_WITH_REF})
  foreach(m ${band_methods})
    if(NOT "${m}" IN_LIST SNELL_METHODS_ON)
      set(band_ok FALSE)
    endif()
  endforeach()
  if(band_ok)
    add_test(NAME bench_band_check COMMAND ${CMAKE_COMMAND} -E env SIZE=48x48 AA=1 FRAMES=2 WARMUP=1
             OUT=${CMAKE_CURRENT_BINARY_DIR}/band_check CACHE=${CMAKE_CURRENT_BINARY_DIR}/band_check/cache
             sh ${PROJECT_SOURCE_DIR}/bench/band_check.sh ${PROJECT_BINARY_DIR})
    # the rows read the CSV's columns (a layered sphere above 10 dB), then both verdicts
    set_tests_properties(bench_band_check PROPERTIES LABELS "cli;gl" TIMEOUT 300 PASS_REGULAR_EXPRESSION
      "(PASS|FAIL) bunny >= 26 dB at <= 3x single: .*  layered:scene=sphere:size=48x48 +[0-9.]+x +[1-9][0-9][.][0-9]+ dB.*(PASS|FAIL) sphere >= 40 dB at <= 2x single: ")
  endif()
  # --env-lookup: both look-ups timed and probed (64x64, 3 rounds: ~3 s); that it runs and prints both tables
  add_test(NAME bench_env_lookup COMMAND ${bench} --env-lookup --frames 3 --sizes 64x64)
  set_tests_properties(bench_env_lookup PROPERTIES LABELS "cli;gl" TIMEOUT 120
    PASS_REGULAR_EXPRESSION "cubemap, dynamic env .*within 1 deg of the rim, smooth")
  add_test(NAME bench_env_lookup_bad COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=--env-lookup|--frames|1" -DCODE=2
           "-DERR=snell-bench --env-lookup: " -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
  set_tests_properties(bench_env_lookup_bad PROPERTIES LABELS "cli")
  foreach(bad "-b|nosuch" "-b|cubemap:iterations=0" "-b|cubemap:face_size=99999" "--frames|0"
              "-b|single:iterations=4" "-b|cubemap:encoding=rgb" "-b|cubemap:scene=pair:attenuation=2/1/1/1"
              "-b|single:lod=0" "-b|single:lod=1.5" "-b|single:lod=nan" "-b|single:dispersion=-1"
              "-b|single:dispersion=21" "-b|single:dispersion_model=spectral"
              "-b|single:methods=nosuch" "-b|single:methods=peel//single"
              # 0 means the default (8, 10) to the library: refused, not run as the default (issue 25)
              "-b|oliveira:linear_steps=0" "-b|wyman:guard_band=0"
              # the frame's scene layers are scene_layers=; layers= is peel's own (2..8)
              "-b|single:layers=2" "-b|peel:layers=1")
    string(MAKE_C_IDENTIFIER "bench_bad_${bad}" name)
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=${bad}" -DCODE=2 "-DERR=snell-bench: "
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  # Flags read by getopt_long in every mode: one message per error, naming the option
  # and where to look (NAME|EXIT|stderr regex|ARGS)
  foreach(case
      "bench_opt_unknown|2|^snell-bench: unknown option '--frobnicate'. see --help$|--frobnicate"
      "bench_opt_no_value|2|^snell-bench: --frames needs a value. see --help$|-q|--frames"
      "bench_opt_short|2|^snell-bench: unknown option '-x'. see --help$|-x"
      "bench_opt_key_of_other_method|2|^snell-bench: method single has no key 'face_size' \\(see --list\\)$|-b|single:face_size=64"
      "bench_budget_sizes|2|^snell-bench --budget: --sizes 64: want one size WxH within 16..2048$|--budget|5|--sizes|64"
      "bench_budget_old_size|2|^snell-bench --budget: --sizes 64: want one size WxH within 16..2048$|--budget|5|--size|64"
      "bench_budget_value|2|^snell-bench --budget 0: want a budget in ms \\(e.g. 40\\) or times single's frame \\(e.g. 4x\\)$|--budget|0"
      "bench_water_sizes|2|^snell-bench --water: --sizes 64x32: want a square size SxS$|--water|--sizes|64x32"
      "bench_env_lookup_unknown|2|^snell-bench --env-lookup: unknown option '--bogus'. see --env-lookup --help$|--env-lookup|--bogus"
      "bench_2d_no_value|2|^snell-bench --2d: --rays needs a value. see --2d --help$|--2d|--rays"
      "bench_compare_one|2|^snell-bench --compare: wants two JSON files, A.json B.json$|--compare|a.json"
      "bench_compare_missing|1|^snell-bench --compare: cannot read '/nonexistent/a.json': No such file or directory$|--compare|/nonexistent/a.json|/nonexistent/b.json"
      "bench_compare_not_bench|1|^snell-bench --compare: '.*nodes.gltf' is not a snell-bench JSON \\(no \"results\" array\\)$|--compare|${CMAKE_CURRENT_SOURCE_DIR}/data/nodes.gltf|${CMAKE_CURRENT_SOURCE_DIR}/data/nodes.gltf")
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 name)
    list(GET parts 1 code)
    list(GET parts 2 err)
    list(SUBLIST parts 3 -1 args)
    string(REPLACE ";" "|" args "${args}")
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DEXE=${bench}" "-DARGS=${args}" -DCODE=${code} "-DERR=${err}"
             -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_one_error.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endforeach()
  # --compare on hostile JSON (issue 49 item 3): linear, numbers only, bounded
  # columns, control bytes scrubbed, loads and devices shown and warned about
  find_program(SNELL_PYTHON3 python3)
  if(SNELL_PYTHON3)
    add_test(NAME bench_compare_hostile COMMAND ${SNELL_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_compare.py
             ${bench} ${CMAKE_CURRENT_BINARY_DIR}/compare_hostile)
    set_tests_properties(bench_compare_hostile PROPERTIES LABELS "cli" TIMEOUT 60)
  endif()
  # --help lists every mode and option of the tool
  add_test(NAME bench_help_complete COMMAND ${bench} --help)
  set_tests_properties(bench_help_complete PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION
    "--compare A.json B.json.*--budget MS\\|Nx.*--water.*--env-lookup.*--2d.*--version")
  add_test(NAME bench_version COMMAND ${bench} --version)
  set_tests_properties(bench_version PROPERTIES LABELS "cli" PASS_REGULAR_EXPRESSION
    "^snell-bench [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit ([0-9a-f]+(-dirty)?|unknown)\\)\n$")
endif()

# bench_floor: issue 10's frame floor (G-buffer pass + kernel at full blocks +
# background, each timed alone) against the screen-space frame. A tool, not a
# test (bench/BENCHMARKS.md); built with the tests because it uses internals.
add_executable(bench_floor bench_floor.c ${PROJECT_SOURCE_DIR}/ports/cli/cli_time.c)
target_link_libraries(bench_floor PRIVATE snell_static)
target_include_directories(bench_floor PRIVATE ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/ports/cli ${CGLM_INCLUDE_DIR})
target_compile_options(bench_floor PRIVATE ${SNELL_WARNINGS})
# that it runs (two rounds on a sphere), not how fast
add_test(NAME bench_floor_runs COMMAND bench_floor sphere cubemap 64 3)
set_tests_properties(bench_floor_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "frame / floor")

# snell-bench's errors per object class (issue 13 item 5): hand-placed
# differences must land in their class only. A CPU test on the bench's own code,
# which measures with the metrics (SNELL_WITH_REF).
if(TARGET snell_bench_common AND SNELL_WITH_REF)
  snell_add_test(test_bench_classes SOURCES test_bench_classes.c LABELS "unit;cli")
  target_link_libraries(test_bench_classes PRIVATE snell_bench_common)
  target_include_directories(test_bench_classes PRIVATE ${PROJECT_SOURCE_DIR}/ports/cli)
endif()

# Every key the bench's spec parser accepts (its common keys and every method
# parameter of the registry) changes the configuration field it names and no
# other (issue 25 item 4). A CPU test of bench_spec.c.
if(TARGET snell_bench_common)
  snell_add_test(test_bench_keys SOURCES test_bench_keys.c LABELS "unit;cli")
  target_link_libraries(test_bench_keys PRIVATE snell_bench_common)
  target_include_directories(test_bench_keys PRIVATE ${PROJECT_SOURCE_DIR}/ports/cli)
endif()

# bench_panels: issue 51's cost of N glass panels against a plain full-screen copy, configurations
# taking turns (a tool, not a test; figures in bench/BENCHMARKS.md "Panels"); that it runs, small.
if(SNELL_WITH_PANELS)
  add_executable(bench_panels bench_panels.c ${PROJECT_SOURCE_DIR}/ports/cli/cli_time.c)
  target_link_libraries(bench_panels PRIVATE snell_static PkgConfig::GLES)
  target_include_directories(bench_panels PRIVATE ${PROJECT_SOURCE_DIR}/ports/cli)
  target_compile_options(bench_panels PRIVATE ${SNELL_WARNINGS})
  add_test(NAME bench_panels_runs COMMAND bench_panels 128x72 2)
  set_tests_properties(bench_panels_runs PROPERTIES LABELS "cli;gl" PASS_REGULAR_EXPRESSION "TARGET\\) \\| 64 clear \\| [0-9.]+ \\|")
endif()
