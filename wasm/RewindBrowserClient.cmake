# SPDX-License-Identifier: MIT
# rewind_add_browser_client(TARGET <target> SOURCES <file>... [OUTPUT_DIRECTORY <dir>])
#
# A browser client module (WebAssembly, for client_sdk/web/rewind-client.js)
# that plays the built-in games and the games SOURCES register: one of them
# defines rwd::client::register_browser_games() (rewind/client/browser_games.h).
# The game's sources are compiled with the engine's determinism flags
# (-ffp-contract=off, no fast-math), which RewindBrowser::engine carries.
#
# The module is <OUTPUT_DIRECTORY>/rewind_client.js (the WebAssembly inlined),
# the name rewind-client.js imports. With the installed package
# (find_package(RewindBrowser)), the SDK's wrapper, its TypeScript
# declarations and package.json are copied beside it: OUTPUT_DIRECTORY is
# then an npm folder a page or a bundler takes as it is.
#
# Used by Rewind's own module (wasm/CMakeLists.txt) and, installed under
# share/rewind/wasm/lib/cmake/RewindBrowser, by a game's Emscripten build.
include_guard(GLOBAL)

# Everything rewind-client.js calls (the entry points of client_api.cpp, in
# the static library RewindBrowser::client: naming them pulls them in).
set(REWIND_BROWSER_EXPORTS
    _malloc _free _rc_error _rc_input_spec _rc_create _rc_disconnect _rc_destroy _rc_connect
    _rc_receive _rc_update _rc_next_datagram _rc_set_input _rc_poll_event _rc_status _rc_draw
    _rc_warm_up)

function(rewind_add_browser_client)
  cmake_parse_arguments(arg "" "TARGET;OUTPUT_DIRECTORY" "SOURCES" ${ARGN})
  if(NOT arg_TARGET OR NOT arg_SOURCES)
    message(FATAL_ERROR "rewind_add_browser_client: TARGET and SOURCES are required")
  endif()
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "rewind_add_browser_client: unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET RewindBrowser::client)
    message(FATAL_ERROR "rewind_add_browser_client: no RewindBrowser::client (find_package(RewindBrowser))")
  endif()
  set(out ${arg_OUTPUT_DIRECTORY})
  if(NOT out)
    set(out ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  add_executable(${arg_TARGET} ${arg_SOURCES})
  target_link_libraries(${arg_TARGET} PRIVATE RewindBrowser::client)
  set_target_properties(${arg_TARGET} PROPERTIES OUTPUT_NAME rewind_client SUFFIX ".js"
                        RUNTIME_OUTPUT_DIRECTORY ${out})
  list(JOIN REWIND_BROWSER_EXPORTS "," exports)
  # One file (the WebAssembly inlined): an npm folder a bundler or a plain
  # <script type="module"> takes as it is.
  target_link_options(${arg_TARGET} PRIVATE
    -sMODULARIZE=1 -sEXPORT_ES6=1 -sEXPORT_NAME=RewindClientModule -sSINGLE_FILE=1
    -sALLOW_MEMORY_GROWTH=1 -sTOTAL_STACK=1MB -sENVIRONMENT=web,worker
    -sEXPORTED_FUNCTIONS=${exports} -sEXPORTED_RUNTIME_METHODS=ccall,UTF8ToString,HEAPU8,HEAPF32)
  if(REWIND_BROWSER_WEB_DIR)
    add_custom_command(TARGET ${arg_TARGET} POST_BUILD
      COMMAND ${CMAKE_COMMAND} -E copy_if_different ${REWIND_BROWSER_WEB_DIR}/rewind-client.js
              ${REWIND_BROWSER_WEB_DIR}/rewind-client.d.ts ${REWIND_BROWSER_WEB_DIR}/package.json
              ${REWIND_BROWSER_WEB_DIR}/README.md ${out}
      COMMENT "The client SDK beside ${arg_TARGET}'s module in ${out}")
  endif()
endfunction()
