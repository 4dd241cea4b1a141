# SPDX-License-Identifier: MIT
# Runs TOOL with ARGS ('|'-separated) and checks its exit code (EXPECT_CODE) and,
# if EXPECT_OUTPUT is not empty, that its standard output matches that regex. With
# EXPECT_ERROR, its standard error must hold one line matching that regex besides the
# progress lines ("sc-preprocess:  40% stage, 1.2 s", written when not a terminal). MKFIFO names
# a FIFO made before the run (non-regular files must be refused, not read). A run
# over 20 s fails (a hang).
string(REPLACE "|" ";" args "${ARGS}")
if(MKFIFO)
  file(REMOVE ${MKFIFO})
  execute_process(COMMAND mkfifo ${MKFIFO} RESULT_VARIABLE made)
  if(NOT made EQUAL 0)
    message(FATAL_ERROR "mkfifo ${MKFIFO} failed")
  endif()
endif()
execute_process(COMMAND ${TOOL} ${args} RESULT_VARIABLE code OUTPUT_VARIABLE out
                ERROR_VARIABLE err TIMEOUT 20)
if(MKFIFO)
  file(REMOVE ${MKFIFO})
endif()
message(STATUS "exit code ${code}\n--- stdout\n${out}--- stderr\n${err}")
if(NOT code EQUAL EXPECT_CODE)
  message(FATAL_ERROR "expected exit code ${EXPECT_CODE}, got ${code}")
endif()
if(NOT EXPECT_OUTPUT STREQUAL "")
  string(REPLACE "\n" " " flat "${out}")
  if(NOT flat MATCHES "${EXPECT_OUTPUT}")
    message(FATAL_ERROR "output does not match '${EXPECT_OUTPUT}'")
  endif()
endif()
if(NOT EXPECT_ERROR STREQUAL "")
  string(REGEX REPLACE "sc-preprocess: +[0-9]+% [^\n]*\n" "" line "${err}")
  string(REGEX REPLACE "\n$" "" line "${line}")
  if(line MATCHES "\n" OR NOT line MATCHES "${EXPECT_ERROR}")
    message(FATAL_ERROR "standard error is not one line matching '${EXPECT_ERROR}'")
  endif()
endif()
