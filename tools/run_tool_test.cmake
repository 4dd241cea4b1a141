# SPDX-License-Identifier: MIT
# Runs TOOL with ARGS ('|'-separated) and checks its exit code (EXPECT_CODE) and,
# if EXPECT_OUTPUT is not empty, that its standard output matches that regex.
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${TOOL} ${args} RESULT_VARIABLE code OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
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
