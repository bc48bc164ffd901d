# SPDX-License-Identifier: MIT
# Fails when any header in HEADERS (a ;-list), compiled alone as a
# consumer would with INCLUDES and DEFINES, pulls in asio or a generated
# protobuf header, directly or through another library's headers. Run as
#   cmake -DCXX=... -DHEADERS=... -DINCLUDES=... -DDEFINES=... -P check_public_headers.cmake
set(flags -std=c++20 -M -x c++)
foreach(dir ${INCLUDES})
  list(APPEND flags -I${dir})
endforeach()
foreach(def ${DEFINES})
  list(APPEND flags -D${def})
endforeach()
if(NOT HEADERS)
  message(FATAL_ERROR "no headers to check")
endif()
set(failures "")
foreach(header ${HEADERS})
  execute_process(COMMAND ${CXX} ${flags} ${header}
    OUTPUT_VARIABLE deps ERROR_VARIABLE errors RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(APPEND failures "${header} does not compile alone:\n${errors}\n")
    continue()
  endif()
  # -M lists every file the header reads, one path per token. Only asio's
  # own headers count (a checkout under a directory named asio is fine).
  string(REGEX MATCHALL
         "[^ \t\r\n\\\\]*(/asio\\.hpp|/asio/[^ \t\r\n\\\\]*\\.[hi]pp|\\.pb\\.h)"
         leaks "${deps}")
  if(leaks)
    list(REMOVE_DUPLICATES leaks)
    list(JOIN leaks "\n  " leak_lines)
    string(APPEND failures "${header} includes:\n  ${leak_lines}\n")
  else()
    message(STATUS "clean: ${header}")
  endif()
endforeach()
if(failures)
  # Printed as is: an error message is word-wrapped, which splits a long
  # path from the "includes:" after it (tests match on that line).
  message(NOTICE "${failures}")
  message(FATAL_ERROR "public headers must not include asio or generated protobuf headers (above)")
endif()
