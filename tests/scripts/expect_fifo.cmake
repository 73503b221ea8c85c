# SPDX-License-Identifier: MIT
# Issue 49 item 1: a FIFO handed to a tool as an input file. Makes the FIFO
# FIFO (no writer ever comes), runs EXE with ARGS (separated by |) under a
# 10 s bound, and requires exit CODE and stderr matching ERR: a tool that
# blocks in open() runs into the bound and fails.
execute_process(COMMAND rm -f "${FIFO}")
execute_process(COMMAND mkfifo "${FIFO}" RESULT_VARIABLE made)
if(NOT made STREQUAL "0")
  message(FATAL_ERROR "mkfifo ${FIFO}: ${made}")
endif()
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err TIMEOUT 10)
file(REMOVE "${FIFO}")
if(NOT rc STREQUAL "${CODE}")
  message(FATAL_ERROR "expected exit ${CODE}, got '${rc}' (a timeout: blocked on the FIFO); stderr: ${err}")
endif()
if(NOT err MATCHES "${ERR}")
  message(FATAL_ERROR "stderr does not match '${ERR}': ${err}")
endif()
