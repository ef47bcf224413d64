# SPDX-License-Identifier: Apache-2.0
# modcp as an installed package (included by the top-level CMakeLists.txt with
# MODCP_INSTALL, ON when modcp is the top-level project):
#
#   cmake --install <build> --prefix <prefix>
#     <prefix>/include/modcp/*.h          the public API: core, HAL interface, console,
#                                         the HAL ports' headers, the generated version.h
#     <prefix>/lib/libmodcp_*.a           modcp::core, ::core_manual, ::console, ::hal_<impl>
#     <prefix>/lib/cmake/modcp/           modcpConfig.cmake, modcpConfigVersion.cmake
#                                         (SameMajorVersion), modcpTargets.cmake
#     <prefix>/lib/pkgconfig/modcp*.pc    the same libraries for Make-based builds
#
# find_package(modcp 0.2 CONFIG REQUIRED) gives the targets of add_subdirectory() with the
# same usage requirements: the feature switches and the ring depth are PUBLIC compile
# definitions of the core (firmware/CMakeLists.txt) and reach the consumer from the
# exported targets; the .pc files are generated from the same target properties, so
# `pkg-config --cflags modcp` carries the same -D switches.
#
# One prefix per target: a host build installs the core, the console and hal_posix; a
# cross build installs the core and the console for its Cortex-M profile and the HAL
# ports that build has: its board's, or with MODCP_BOARD=core (the core-<profile>
# presets) every port in MODCP_CROSS_HAL_PORTS.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MODCP_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/modcp CACHE STRING
    "Where modcpConfig.cmake is installed, relative to the prefix")

if(CMAKE_CROSSCOMPILING)
  if(MODCP_BOARD STREQUAL "core")
    foreach(impl ${MODCP_CROSS_HAL_PORTS})
      if(NOT TARGET modcp_hal_${impl})
        include(${PROJECT_SOURCE_DIR}/hal/${impl}/CMakeLists.txt)
      endif()
    endforeach()
  endif()
  set(_ports ${MODCP_CROSS_HAL_PORTS})
  set(_target "${MODCP_ARM_CPU}")
else()
  set(_ports posix)
  set(_target "host")
endif()

set(_libs modcp_version modcp_core modcp_core_manual modcp_console)
set(_pc_hals "")
foreach(impl ${_ports})
  if(TARGET modcp_hal_${impl})
    list(APPEND _libs modcp_hal_${impl})
    list(APPEND _pc_hals ${impl})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/hal/${impl}/include/modcp
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
  endif()
endforeach()

# Exported names: modcp_core -> modcp::core, modcp_hal_posix -> modcp::hal_posix, ...
# The build-tree include folders are the build's own; an installed target has
# <prefix>/include, where every public header is.
foreach(lib ${_libs})
  string(REGEX REPLACE "^modcp_" "" _name ${lib})
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${_name})
  get_target_property(_dirs ${lib} INTERFACE_INCLUDE_DIRECTORIES)
  set(_wrapped "")
  foreach(d ${_dirs})
    if(d MATCHES "^\\$<")
      list(APPEND _wrapped "${d}")
    else()
      list(APPEND _wrapped "$<BUILD_INTERFACE:${d}>")
    endif()
  endforeach()
  list(APPEND _wrapped "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  set_target_properties(${lib} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_wrapped}")
endforeach()

install(TARGETS ${_libs} EXPORT modcpTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(dir ${PROJECT_SOURCE_DIR}/firmware/include/modcp ${PROJECT_SOURCE_DIR}/hal/include/modcp
            ${PROJECT_SOURCE_DIR}/firmware/console/include/modcp
            ${PROJECT_BINARY_DIR}/firmware/include/modcp)
  install(DIRECTORY ${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/modcp)

install(EXPORT modcpTargets NAMESPACE modcp:: DESTINATION ${MODCP_INSTALL_CMAKEDIR})
set(MODCP_PACKAGE_TARGET "${_target}")
set(MODCP_PACKAGE_HALS "${_pc_hals}")
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/modcpConfig.cmake.in
  ${PROJECT_BINARY_DIR}/modcpConfig.cmake INSTALL_DESTINATION ${MODCP_INSTALL_CMAKEDIR})
# SameMajorVersion: 0.2 accepts 0.2.x and later 0.x; the pointer size of the consumer must
# match (a host package is not found by a Cortex-M build, nor the other way round)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/modcpConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/modcpConfig.cmake ${PROJECT_BINARY_DIR}/modcpConfigVersion.cmake
        DESTINATION ${MODCP_INSTALL_CMAKEDIR})

# ---- pkg-config ----------------------------------------------------------------------------
# modcp_pc(<file> <target> <description> <requires> <extra libs>): <file>.pc for one
# library; its -D switches are the target's INTERFACE_COMPILE_DEFINITIONS (with those of
# the libraries it links), evaluated at generation time. The prefix is found from the
# .pc file's place (${pcfiledir}), so a staged or moved install stays usable.
function(modcp_pc file target description requires extra)
  set(_defs "$<TARGET_PROPERTY:${target},INTERFACE_COMPILE_DEFINITIONS>")
  if(requires)
    set(_req "Requires: ${requires}\n")
    set(_cflags "")
  else()
    set(_req "")
    set(_cflags " -I\${includedir}$<$<BOOL:${_defs}>: -D$<JOIN:${_defs}, -D>>")
  endif()
  string(REPLACE "/" ";" _up "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
  set(_rel "\${pcfiledir}")
  foreach(x ${_up})
    string(APPEND _rel "/..")
  endforeach()
  file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/pkgconfig/${file}.pc CONTENT
"# SPDX-License-Identifier: Apache-2.0
# generated by modcp's cmake/install.cmake for ${MODCP_PACKAGE_TARGET}
prefix=${_rel}
includedir=\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}
libdir=\${prefix}/${CMAKE_INSTALL_LIBDIR}

Name: ${file}
Description: ${description} (${MODCP_PACKAGE_TARGET})
Version: ${PROJECT_VERSION}
${_req}Cflags:${_cflags}
Libs: -L\${libdir} -l$<TARGET_FILE_BASE_NAME:${target}>${extra}
")
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/${file}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()

modcp_pc(modcp modcp_core "modcp Modbus slave communication processor core, every feature" "" "")
modcp_pc(modcp-manual modcp_core_manual
  "modcp core with the manual's function set only (RTU, cp341, no RS232 signals); instead of modcp"
  "" "")
modcp_pc(modcp-console modcp_console "modcp monitor console (S7 operands)" "modcp" "")
foreach(impl ${_pc_hals})
  if(impl STREQUAL "posix")
    set(_extra " -pthread")
  else()
    set(_extra "")
  endif()
  modcp_pc(modcp-hal-${impl} modcp_hal_${impl} "modcp HAL port ${impl}" "modcp" "${_extra}")
endforeach()
