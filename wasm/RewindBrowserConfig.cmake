# SPDX-License-Identifier: MIT
# Rewind's browser client for a game's own Emscripten build:
#   emcmake cmake -S browser -B build-web -DCMAKE_PREFIX_PATH=<Rewind's prefix>/share/rewind/wasm
#   find_package(RewindBrowser CONFIG REQUIRED NO_CMAKE_FIND_ROOT_PATH)
#     (Emscripten's toolchain otherwise searches its sysroot only)
#   rewind_add_browser_client(TARGET my_client SOURCES my_game.cpp my_browser_games.cpp
#                             OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/web)
# Targets: RewindBrowser::engine (the engine, both lanes, the game seam, the
# built-in games), RewindBrowser::client (the client SDK's protocol and its
# JavaScript entry points, libsodium and protobuf-lite); the function is in
# RewindBrowserClient.cmake. Everything here was compiled with Emscripten
# by the same Rewind build as the native package beside it.
if(NOT EMSCRIPTEN)
  message(FATAL_ERROR "RewindBrowser is for Emscripten builds (emcmake cmake ...)")
endif()
get_filename_component(_rewind_browser_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
set(_rewind_browser_lib ${_rewind_browser_prefix}/lib)

if(NOT TARGET RewindBrowser::engine)
  add_library(RewindBrowser::engine STATIC IMPORTED)
  set_target_properties(RewindBrowser::engine PROPERTIES
    IMPORTED_LOCATION ${_rewind_browser_lib}/librewind_engine.a
    INTERFACE_INCLUDE_DIRECTORIES ${_rewind_browser_prefix}/include
    INTERFACE_COMPILE_OPTIONS "-ffp-contract=off;-fno-fast-math"
    INTERFACE_COMPILE_FEATURES cxx_std_20)
  add_library(RewindBrowser::client STATIC IMPORTED)
  set_target_properties(RewindBrowser::client PROPERTIES
    IMPORTED_LOCATION ${_rewind_browser_lib}/librewind_client_core.a
    INTERFACE_LINK_LIBRARIES
      "RewindBrowser::engine;${_rewind_browser_lib}/libsodium.a;${_rewind_browser_lib}/libprotobuf-lite.a")
endif()
set(REWIND_BROWSER_WEB_DIR ${_rewind_browser_prefix}/web)
include(${CMAKE_CURRENT_LIST_DIR}/RewindBrowserClient.cmake)
set(RewindBrowser_FOUND TRUE)
