# SPDX-License-Identifier: MIT
# Glass panels where users see them (issue 51 item 4): snell-render --panels
# and --under, the kiosk's --panels and --slide (its --preview: no KMS device
# here), the panels file's errors, each with its line, and the example app
# (examples/panels_merge.c). The Android scene's panels are in test_android_scene.

# The panels file's parser alone: fields, lines and hostile text (no GL).
snell_add_test(test_cli_panels SOURCES test_cli_panels.c ${PROJECT_SOURCE_DIR}/ports/cli/cli_panels.c
               ${PROJECT_SOURCE_DIR}/ports/cli/cli_input.c LABELS "unit")
target_include_directories(test_cli_panels PRIVATE ${PROJECT_SOURCE_DIR}/ports/cli)
