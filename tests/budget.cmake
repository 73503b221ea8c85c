# SPDX-License-Identifier: MIT
# AUTO by frame budget (issue 25 item 3; src/render/budget.c, budget_stage.c):
# the controller against synthetic devices (no GL), and the renderer's budget
# stage on real frames (its stats, the rung drawn, the refusals).
snell_add_test(test_budget SOURCES test_budget.c LABELS "unit")
target_link_libraries(test_budget PRIVATE m)
snell_add_test(test_budget_render SOURCES test_budget_render.c LABELS "render;gl")
target_link_libraries(test_budget_render PRIVATE m)
# snell-bench --budget: AUTO by budget beside the rung table's fixed
# configurations on a moving camera, measured against FULL at the samples.
if(TARGET snell-bench)
  add_test(NAME cli_bench_budget COMMAND $<TARGET_FILE:snell-bench> --budget 10000 --scene sphere --sizes 32x32
           --frames 12 --samples 1 --fixed-every 4 --threads 2 --cache ${CMAKE_CURRENT_BINARY_DIR}/bench-budget-cache
           -o ${CMAKE_CURRENT_BINARY_DIR}/bench-budget)
  set_tests_properties(cli_bench_budget PROPERTIES LABELS "cli"
    PASS_REGULAR_EXPRESSION "the rung table.*AUTO warmed \\(snell_renderer_warm\\): [0-9]+ frames.*[1-9][0-9]* rungs timed.*\\| auto, budget \\|.*\\| peel \\|.*AUTO: [0-9]+ plan changes.*frame 6: layered.*best fixed configuration within the budget \\(p95\\): .*wrote .*bench-budget.json, .*bench-budget.csv")
endif()
