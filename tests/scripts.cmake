# SPDX-License-Identifier: MIT
# The package steps of CI and the README's commands (scripts/apt.sh) against a
# fake apt-get: a mirror mid-sync must not stop an install.
add_test(NAME test_apt COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/test_apt.sh)
set_tests_properties(test_apt PROPERTIES LABELS "unit" TIMEOUT 60)
# Every source file names its licence (LICENSE, MIT) by its SPDX tag.
add_test(NAME source_spdx COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
         -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_spdx.cmake)
set_tests_properties(source_spdx PROPERTIES LABELS "unit")
# Comments in src/, include/ and shaders_es/ say why; measurements, dates, loads, commit
# hashes, issue numbers and history live in bench/notes/ and commit messages.
add_test(NAME source_comments COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_comments.sh ${PROJECT_SOURCE_DIR})
set_tests_properties(source_comments PROPERTIES LABELS "unit")
# and the check fails where it should: tests/data/comments plants seven bad
# comments (a percentage, degrees of error, "was" history) and an eleven-line
# file header beside good ones
add_test(NAME source_comments_fail COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_comments.sh
         ${CMAKE_CURRENT_SOURCE_DIR}/data/comments)
set_tests_properties(source_comments_fail PROPERTIES LABELS "unit" PASS_REGULAR_EXPRESSION
  "include/planted.h:2: history.*shaders_es/planted.glsl:3: degrees result.*src/long_header.c:2: header over 10 lines.*src/planted.c:4: percent result.*src/planted.c:5: degrees result.*src/planted.c:6: history.*src/planted.c:7: percent result.*src/planted.c:8: history.*: 8 comment line")
