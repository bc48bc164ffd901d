# SPDX-License-Identifier: MIT
# Rewind as an installed package: `cmake --install` puts the public headers,
# the static libraries, the tools, a CMake package (find_package(Rewind
# CONFIG), targets Rewind::*) and pkg-config files under the prefix; `cpack
# -G DEB` wraps the same files in a Debian package. docs/package.md lists
# the targets and what each needs.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# rewind_public_headers(TARGET DIR...): the target's public headers live
# under each DIR (DIR/rewind/...). While building they are found there;
# installed, under include/ (every installed target gets that directory).
function(rewind_public_headers target)
  foreach(dir ${ARGN})
    get_filename_component(abs ${dir} ABSOLUTE)
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${abs}>)
    set_property(GLOBAL APPEND PROPERTY REWIND_PACKAGE_HEADER_DIRS ${abs})
  endforeach()
endfunction()

# rewind_package_library(TARGET NAME): the library is installed and
# exported as Rewind::NAME.
function(rewind_package_library target name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  set_property(GLOBAL APPEND PROPERTY REWIND_PACKAGE_TARGETS ${target})
endfunction()

# rewind_package_program(TARGET): the executable is installed in bin/.
function(rewind_package_program target)
  set_property(GLOBAL APPEND PROPERTY REWIND_PACKAGE_PROGRAMS ${target})
endfunction()

# Writes a pkg-config file NAME.pc for libraries LIBS (link order, most
# dependent first) needing pkg-config modules REQUIRES.
function(rewind_pkg_config name description requires)
  set(libs "")
  foreach(lib ${ARGN})
    string(APPEND libs " -l${lib}")
  endforeach()
  set(pc ${CMAKE_BINARY_DIR}/pkgconfig/${name}.pc)
  file(WRITE ${pc}.in "prefix=@CMAKE_INSTALL_PREFIX@
libdir=\${prefix}/${CMAKE_INSTALL_LIBDIR}
includedir=\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}

Name: ${name}
Description: ${description}
Version: ${PROJECT_VERSION}
Requires: ${requires}
Cflags: -std=c++20 -ffp-contract=off -fno-fast-math -I\${includedir}
Libs: -L\${libdir}${libs} -pthread
")
  # The prefix is the one given at install time (cmake --install --prefix).
  install(CODE "set(CMAKE_INSTALL_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
    configure_file(\"${pc}.in\" \"${pc}\" @ONLY)")
  install(FILES ${pc} DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()

function(rewind_install_package)
  get_property(targets GLOBAL PROPERTY REWIND_PACKAGE_TARGETS)
  get_property(header_dirs GLOBAL PROPERTY REWIND_PACKAGE_HEADER_DIRS)
  get_property(programs GLOBAL PROPERTY REWIND_PACKAGE_PROGRAMS)
  list(REMOVE_DUPLICATES header_dirs)

  set_target_properties(rewind_determinism PROPERTIES EXPORT_NAME determinism)
  install(TARGETS rewind_determinism ${targets} EXPORT RewindTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  foreach(dir ${header_dirs})
    install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
      FILES_MATCHING PATTERN "*.h")
  endforeach()
  if(programs)
    install(TARGETS ${programs} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
  # The browser viewer, when this build gathered it (rewind-server
  # --live-viewer-dir and rewind-replay view find it next to their binary).
  install(DIRECTORY ${REWIND_VIEWER_WEB_DIR}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rewind/viewer
    OPTIONAL)
  # The browser client SDK's npm folder, when this build gathered it: a web
  # game copies or `npm install`s it from there.
  install(DIRECTORY ${CMAKE_BINARY_DIR}/client_web/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rewind/client
    OPTIONAL)
  # And what a game's own browser module is built with (find_package(
  # RewindBrowser) in an Emscripten build; docs/writing-a-game.md).
  install(DIRECTORY ${CMAKE_BINARY_DIR}/wasm/stage/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rewind/wasm
    OPTIONAL)

  set(cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/Rewind)
  install(EXPORT RewindTargets NAMESPACE Rewind:: DESTINATION ${cmake_dir})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/RewindConfig.cmake.in
    ${CMAKE_BINARY_DIR}/RewindConfig.cmake INSTALL_DESTINATION ${cmake_dir})
  # Before 1.0 every minor version may change the API and the ABI.
  write_basic_package_version_file(${CMAKE_BINARY_DIR}/RewindConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${CMAKE_BINARY_DIR}/RewindConfig.cmake ${CMAKE_BINARY_DIR}/RewindConfigVersion.cmake
    DESTINATION ${cmake_dir})

  set(engine_libs rewind_game rewind_sim2d rewind_fixed rewind_sim rewind_core)
  rewind_pkg_config(rewind-engine "Rewind's deterministic engine: both physics lanes and the game seam"
    "libxxhash" ${engine_libs})
  if(REWIND_WITH_SERVER)
    rewind_pkg_config(rewind "Rewind: the engine, the server core, the client SDK and the tools' run loops"
      "libxxhash protobuf-lite libsodium openssl"
      rewind_server_main rewind_bots_main rewind_synctest_main rewind_agones rewind_server_core
      rewind_http rewind_client rewind_client_websocket rewind_bot_script rewind_replay rewind_view rewind_replay_io
      rewind_rollback rewind_transport rewind_secure rewind_wire rewind_proto rewind_cli
      ${engine_libs})
  endif()

  set(CPACK_PACKAGE_NAME rewind)
  set(CPACK_PACKAGE_VENDOR "Rewind")
  set(CPACK_PACKAGE_CONTACT "Rewind maintainers <rewind@localhost>")
  set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Authoritative rollback simulation server and deterministic physics engine")
  set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
  set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
  set(CPACK_DEBIAN_PACKAGE_SECTION devel)
  set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
  # What a program built against the package needs at build time, and the
  # tools at run time (Debian 12 package names).
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libxxhash-dev, libprotobuf-dev, protobuf-compiler, libsodium-dev, libasio-dev, libboost-dev, nlohmann-json3-dev, libssl-dev")
  include(CPack)
endfunction()
