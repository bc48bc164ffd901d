# SPDX-License-Identifier: MIT
# Proves that files use no floating point, in two independent ways:
#  1. every file (header or source) is compiled with -fsyntax-only after
#     poison.h, which makes the words float and double name nothing: any use
#     of a floating-point type in the file's own text fails;
#  2. the file's text, stripped of comments, strings and _fx literals, must
#     hold no floating-point literal (1.5, .5, 2e3, 0x1p4): a literal the
#     compiler folds into an integer constant leaves no floating-point code
#     behind for rule 3 to see, yet it is floating point all the same;
#  3. every source is compiled to an object by REGS_CXX (GCC) with REGS_FLAG
#     (-mgeneral-regs-only on x86-64 and aarch64), which forbids the
#     compiler any floating-point or SIMD register: a floating-point literal,
#     a call to a function that returns double, or code the compiler chose to
#     vectorize fails, even when no floating-point type is named.
# The tests fixed_no_float_detects_keyword, _detects_literal and
# _detects_codegen run this script on files that break each rule and
# require it to fail.
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
  # A source is compiled once for rules 1 and 3 together (poison.h first,
  # then to an object without floating-point registers): parsing it twice
  # was half the cost. A header, and a source without the GCC check, gets
  # rule 1 alone.
  set(object_check OFF)
  if(REGS_FLAG AND REGS_CXX AND file MATCHES "\\.cpp$")
    set(object_check ON)
    execute_process(
      COMMAND ${REGS_CXX} -std=c++20 -O2 ${REGS_FLAG} -x c++ ${include_flags} -include ${POISON}
              -c ${file} -o /dev/null
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  else()
    execute_process(
      COMMAND ${CXX} -std=c++20 -fsyntax-only -x c++ ${include_flags} -include ${POISON} ${file}
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  endif()
  if(NOT rc EQUAL 0)
    if(out MATCHES "rwd_fixed_forbids_(float|double)")
      string(APPEND failures "${name} names a floating-point type:\n${out}\n")
    elseif(object_check)
      string(APPEND failures "${name} generates floating-point code (${REGS_FLAG}) or does not "
                             "compile under poison.h:\n${out}\n")
    else()
      string(APPEND failures "${name} does not compile under poison.h:\n${out}\n")
    endif()
    continue()
  endif()
  file(READ "${file}" text)
  string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" " " text "${text}")
  string(REGEX REPLACE "//[^\n]*" " " text "${text}")
  string(REGEX REPLACE "\"([^\"\\\\\n]|\\\\.)*\"" "\"\"" text "${text}")
  string(REGEX REPLACE "[0-9][0-9']*(\\.[0-9']*)?_fx" "0" text "${text}")
  set(literal "")
  if(text MATCHES "0[xX][0-9a-fA-F'.]*[pP][-+]?[0-9]*")
    set(literal "${CMAKE_MATCH_0}")
  else()
    string(REGEX REPLACE "0[xX][0-9a-fA-F']+" "0" text "${text}")
    foreach(pattern "[0-9][0-9']*\\.[0-9]*" "\\.[0-9]+" "[0-9]+[eE][-+]?[0-9]+")
      # Only where a number can start: not inside a name or after a member dot.
      if(text MATCHES "(^|[^]A-Za-z0-9_.)])(${pattern})")
        set(literal "${CMAKE_MATCH_2}")
        break()
      endif()
    endforeach()
  endif()
  if(literal)
    string(APPEND failures "${name} holds a floating-point literal (${literal})\n")
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
