# AUTO by frame budget (issue 25 item 3; src/render/budget.c, budget_stage.c):
# the controller against synthetic devices (no GL), and the renderer's budget
# stage on real frames (its stats, the rung drawn, the refusals).
snell_add_test(test_budget SOURCES test_budget.c LABELS "unit")
target_link_libraries(test_budget PRIVATE m)
snell_add_test(test_budget_render SOURCES test_budget_render.c LABELS "render;gl")
target_link_libraries(test_budget_render PRIVATE m)
