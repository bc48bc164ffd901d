# SPDX-License-Identifier: MIT
# Rewind in the browser (REWIND_BUILD_VIEWER): wasm/ compiled with
# Emscripten as an external project of its own, and gathered with its pages
# into two folders of this build:
#   REWIND_VIEWER_WEB_DIR  the replay and live viewer (viewer/web), where
#                          `rewind-replay view` and the live endpoint serve it
#                          (target rewind_viewer);
#   REWIND_CLIENT_WEB_DIR  the client SDK for browser players as an npm
#                          folder (client_sdk/web: rewind-client.js, its
#                          TypeScript declarations, the module)
#                          (target rewind_browser_client);
#   wasm/stage             the libraries, headers and package config a game's
#                          own browser module is built with
#                          (rewind_add_browser_client, wasm/RewindBrowserClient.cmake),
#                          installed under share/rewind/wasm.
# Neither is built by every build: a few minutes each time the engine
# changes; the browser tests' fixture or a request builds them.
option(REWIND_BUILD_VIEWER "Add the browser viewer and the browser client SDK (targets rewind_viewer, rewind_browser_client) and their browser tests (needs emscripten, node and Chromium: scripts/setup.sh --viewer)" OFF)
set(REWIND_CLIENT_WEB_DIR ${CMAKE_BINARY_DIR}/client_web)
if(NOT REWIND_BUILD_VIEWER)
  return()
endif()
find_program(REWIND_EMCMAKE emcmake)
if(NOT REWIND_EMCMAKE)
  message(FATAL_ERROR "REWIND_BUILD_VIEWER needs Emscripten's emcmake: install the Debian "
                      "package emscripten (bash scripts/setup.sh --viewer)")
endif()
include(ExternalProject)
# Emscripten's JavaScript tools need Debian's node modules (acorn).
set(emscripten_env ${CMAKE_COMMAND} -E env NODE_PATH=/usr/share/nodejs)
set(REWIND_WASM_DIR ${CMAKE_BINARY_DIR}/wasm)
set(wasm_deps ${CMAKE_BINARY_DIR}/wasm-deps)
# Under a lock: scripts/test.sh runs the same commands in the background
# while the real-time tests leave the CPU idle, and whichever comes second
# finds the work done. The client's libraries (libsodium, protobuf-lite)
# are built from Debian's sources first; when they cannot be fetched the
# viewer is still built, and the client's absence is told in wasm-deps.log.
set(wasm_lock flock ${REWIND_WASM_DIR}.lock)
ExternalProject_Add(rewind_wasm
  SOURCE_DIR ${PROJECT_SOURCE_DIR}/wasm
  BINARY_DIR ${REWIND_WASM_DIR}
  CONFIGURE_COMMAND ${wasm_lock} ${emscripten_env} bash ${PROJECT_SOURCE_DIR}/wasm/configure.sh
                    ${PROJECT_SOURCE_DIR} <BINARY_DIR> ${wasm_deps}
  BUILD_COMMAND ${wasm_lock} ${emscripten_env} ${CMAKE_COMMAND} --build <BINARY_DIR>
  # What a game's own browser module builds on (RewindBrowserConfig.cmake),
  # staged for cmake --install (share/rewind/wasm).
  INSTALL_COMMAND ${wasm_lock} ${CMAKE_COMMAND} --install <BINARY_DIR> --prefix <BINARY_DIR>/stage
  # The sub-build's ninja knows what changed; ask it every time.
  BUILD_ALWAYS ON
  EXCLUDE_FROM_ALL ON
  USES_TERMINAL_BUILD ON)

file(GLOB viewer_files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/viewer/web/*)
add_custom_target(rewind_viewer
  COMMAND ${CMAKE_COMMAND} -E make_directory ${REWIND_VIEWER_WEB_DIR}
  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${viewer_files} ${REWIND_WASM_DIR}/rewind_viewer.js
          ${REWIND_WASM_DIR}/rewind_viewer.wasm ${REWIND_VIEWER_WEB_DIR}
  DEPENDS rewind_wasm ${viewer_files}
  COMMENT "Gathering the browser viewer in ${REWIND_VIEWER_WEB_DIR}")

file(GLOB client_files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/client_sdk/web/*)
add_custom_target(rewind_browser_client
  COMMAND ${CMAKE_COMMAND} -E make_directory ${REWIND_CLIENT_WEB_DIR}
  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${client_files} ${REWIND_WASM_DIR}/rewind_client.js
          ${REWIND_CLIENT_WEB_DIR}
  DEPENDS rewind_wasm ${client_files}
  COMMENT "Gathering the browser client SDK in ${REWIND_CLIENT_WEB_DIR}")
