# SPDX-License-Identifier: MIT
# The package steps of CI and the README's commands (scripts/apt.sh) against a
# fake apt-get: a mirror mid-sync must not stop an install.
add_test(NAME test_apt COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/test_apt.sh)
set_tests_properties(test_apt PROPERTIES LABELS "unit" TIMEOUT 60)
# Every source file names its licence (LICENSE, MIT) by its SPDX tag.
add_test(NAME source_spdx COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
         -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_spdx.cmake)
set_tests_properties(source_spdx PROPERTIES LABELS "unit")
# Comments in src/ and shaders_es/ say why; measurements, dates, loads, commit
# hashes, issue numbers and history live in bench/notes/ and commit messages.
add_test(NAME source_comments COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_comments.sh ${PROJECT_SOURCE_DIR})
set_tests_properties(source_comments PROPERTIES LABELS "unit")
