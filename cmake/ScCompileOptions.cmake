# SPDX-License-Identifier: MIT
# Warnings and sanitizer flags for the project's own targets.

option(SC_SANITIZE_THREAD "Build with ThreadSanitizer (exclusive with SC_SANITIZE)" OFF)
option(SC_BUILD_FUZZERS "Build the libFuzzer targets of tests/fuzz (clang only)" OFF)

function(sc_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                                           -Wnon-virtual-dtor -Wconversion-null)
  if(SC_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(SC_SANITIZE AND SC_SANITIZE_THREAD)
  message(FATAL_ERROR "SC_SANITIZE (ASan+UBSan) and SC_SANITIZE_THREAD cannot be combined")
endif()

if(SC_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

if(SC_SANITIZE_THREAD)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()

# The fuzz targets come from the same build as the sanitized tests: everything is
# compiled with libFuzzer's coverage instrumentation, and only tests/fuzz links the
# fuzzer runtime (its main).
if(SC_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "SC_BUILD_FUZZERS needs clang (libFuzzer); CXX is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
  add_link_options(-fsanitize=fuzzer-no-link)
endif()
