# The package steps of CI and the README's commands (scripts/apt.sh) against a
# fake apt-get: a mirror mid-sync must not stop an install.
add_test(NAME test_apt COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/test_apt.sh)
set_tests_properties(test_apt PROPERTIES LABELS "unit" TIMEOUT 60)
