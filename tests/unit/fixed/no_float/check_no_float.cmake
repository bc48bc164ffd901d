# SPDX-License-Identifier: MIT
# Proves that files use no floating point, in two independent ways:
#  1. every file (header or source) is compiled with -fsyntax-only after
#     poison.h, which makes the words float and double name nothing: any use
#     of a floating-point type in the file's own text fails;
#  2. every source is compiled to an object by REGS_CXX (GCC) with REGS_FLAG
#     (-mgeneral-regs-only on x86-64 and aarch64), which forbids the
#     compiler any floating-point or SIMD register: a floating-point literal,
#     a call to a function that returns double, or code the compiler chose to
#     vectorize fails, even when no floating-point type is named.
# The tests fixed_no_float_detects_keyword and fixed_no_float_detects_codegen
# run this script on files that break each rule and require it to fail.
#
# cmake -DCXX=<compiler> -DFILES=<a;b;...> -DINCLUDES=<dir;dir> -DPOISON=<poison.h>
#       [-DREGS_FLAG=-mgeneral-regs-only -DREGS_CXX=<g++>] -P check_no_float.cmake
foreach(var CXX FILES POISON)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "check_no_float: ${var} is required")
  endif()
endforeach()

set(include_flags "")
foreach(dir IN LISTS INCLUDES)
  list(APPEND include_flags "-I${dir}")
endforeach()

set(failures "")
set(checked 0)
foreach(file IN LISTS FILES)
  math(EXPR checked "${checked} + 1")
  get_filename_component(name "${file}" NAME)
  execute_process(
    COMMAND ${CXX} -std=c++20 -fsyntax-only -x c++ ${include_flags} -include ${POISON} ${file}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    if(out MATCHES "rwd_fixed_forbids_(float|double)")
      string(APPEND failures "${name} names a floating-point type:\n${out}\n")
    else()
      string(APPEND failures "${name} does not compile under poison.h:\n${out}\n")
    endif()
    continue()
  endif()
  if(REGS_FLAG AND REGS_CXX AND file MATCHES "\\.cpp$")
    execute_process(
      COMMAND ${REGS_CXX} -std=c++20 -O2 ${REGS_FLAG} ${include_flags} -c ${file} -o /dev/null
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    if(NOT rc EQUAL 0)
      string(APPEND failures "${name} generates floating-point code (${REGS_FLAG}):\n${out}\n")
    endif()
  endif()
endforeach()

if(failures)
  message(FATAL_ERROR "floating point found:\n${failures}")
endif()
if(REGS_FLAG AND REGS_CXX)
  message(STATUS "${checked} files free of floating point (keyword and ${REGS_FLAG} checks)")
else()
  message(STATUS "${checked} files free of floating point (keyword check only: no GCC "
                 "with -mgeneral-regs-only for this target)")
endif()
