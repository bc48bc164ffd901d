# SPDX-License-Identifier: MIT
# Compiles FILE and fails if it compiles; otherwise prints the compiler's
# diagnostics, which the test's PASS_REGULAR_EXPRESSION then checks for the
# expected message (so a file that fails for another reason fails the test).
#
# cmake -DCXX=<compiler> -DFILE=<file.cpp> -DINCLUDES=<dir;dir> -P expect_compile_error.cmake
set(include_flags "")
foreach(dir IN LISTS INCLUDES)
  list(APPEND include_flags "-I${dir}")
endforeach()
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only ${include_flags} ${FILE}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "${FILE} compiled, but must not")
endif()
message(STATUS "refused as expected:\n${out}")
