# SPDX-License-Identifier: MIT
# Runs EXE with ARGS (separated by |) and requires exit code CODE and stderr matching ERR, so
# a crash (signal) or a silent failure never counts as the expected error.
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc STREQUAL "${CODE}")
  message(FATAL_ERROR "expected exit ${CODE}, got '${rc}'; stderr: ${err}")
endif()
if(NOT err MATCHES "${ERR}")
  message(FATAL_ERROR "stderr does not match '${ERR}': ${err}")
endif()
