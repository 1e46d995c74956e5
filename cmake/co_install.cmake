# SPDX-License-Identifier: Apache-2.0
# What `cmake --install` puts where (GNUInstallDirs; relative to the prefix, /usr/local by default,
# /usr in the Debian package), and the Debian package itself (`cpack -G DEB`). README.md, Install.
#
#   include/co/, co_linux/, drive/, dn/    the public headers of the libraries
#   lib/libcanopen.a                       canopen::core, the portable core
#   lib/libco_linux.a                      canopen::linux, the Linux runtime (links canopen::core)
#   lib/libco_drive.a                      canopen::drive, the generic CiA 402 velocity drive
#                                          (portable; links canopen::core)
#   lib/libdevicenet.a                     canopen::devicenet, the portable DeviceNet slave
#   lib/libdnscanner.a                     canopen::dnscanner, the DeviceNet scanner (links
#                                          canopen::devicenet)
#   lib/libdrive_devicenet.a               canopen::drive_devicenet, the drive behind the
#                                          DeviceNet slave (links canopen::drive, canopen::devicenet)
#   lib/cmake/canopen/                     find_package(canopen): those targets and co_generate_od()
#   lib/pkgconfig/canopen.pc               pkg-config: the core (variables edstool and edsdir)
#   lib/pkgconfig/canopen-linux.pc         pkg-config: the Linux runtime (requires canopen)
#   lib/pkgconfig/canopen-drive.pc         pkg-config: the drive (requires canopen)
#   lib/pkgconfig/devicenet.pc             pkg-config: the DeviceNet slave and scanner
#   lib/pkgconfig/devicenet-drive.pc       pkg-config: the drive on DeviceNet (requires
#                                          canopen-drive, devicenet)
#   bin/atv312d, bin/cotrace, bin/comaster, bin/dnscan, bin/co-edstool, bin/vcan-run
#                                          the daemon, the trace decoder, the master tool,
#                                          tools/edstool.py, tools/vcan-run
#   share/man/man1/<program>.1             their man pages, written from their --help text
#   share/canopen-atv312/eds/*.eds         the EDS files of eds/
#   share/doc/canopen-atv312/              README.md, docs/*.md, examples/atv312d.service, LICENSE
#                                          (Apache-2.0) and copyright (Debian's machine-readable
#                                          form, cmake/copyright; the package's copyright file)

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The libraries of an instrumented build need the instrumentation's runtime in every consumer.
if(CO_SANITIZE OR CO_COVERAGE)
  install(CODE "message(WARNING \"installing a build made with CO_SANITIZE or CO_COVERAGE: \
programs using its libraries must link the same runtime (-fsanitize=..., --coverage)\")")
endif()

set(CO_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/canopen)
set(CO_INSTALL_EDSDIR ${CMAKE_INSTALL_DATADIR}/${PROJECT_NAME}/eds)

# Libraries and their headers. The models' headers (src/drive/models/<model>/<model>.h) are the
# daemon's: their libraries are not installed, so neither are their headers.
set(CO_INSTALL_HEADER_DIRS co co_linux drive dn)
set_target_properties(canopen PROPERTIES EXPORT_NAME core)
set_target_properties(co_linux PROPERTIES EXPORT_NAME linux)
set_target_properties(co_drive PROPERTIES EXPORT_NAME drive)
install(TARGETS canopen co_linux co_drive devicenet dnscanner drive_devicenet EXPORT canopenTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(dir ${CO_INSTALL_HEADER_DIRS})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.h")
endforeach()

# The CMake package: the exported targets, co_generate_od() running the installed co-edstool.
install(EXPORT canopenTargets NAMESPACE canopen:: DESTINATION ${CO_INSTALL_CMAKEDIR})
set(CO_EDSTOOL_INSTALL ${CMAKE_INSTALL_BINDIR}/co-edstool)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/canopenConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/canopenConfig.cmake
                              INSTALL_DESTINATION ${CO_INSTALL_CMAKEDIR}
                              PATH_VARS CO_EDSTOOL_INSTALL)
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/canopenConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/canopenConfig.cmake
              ${PROJECT_BINARY_DIR}/canopenConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/co_od.cmake
        DESTINATION ${CO_INSTALL_CMAKEDIR})

# The daemon and the tools.
install(TARGETS atv312d cotrace comaster dnscan RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(PROGRAMS ${CO_EDSTOOL} DESTINATION ${CMAKE_INSTALL_BINDIR} RENAME co-edstool)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/tools/vcan-run DESTINATION ${CMAKE_INSTALL_BINDIR})
# vcan-run's helpers, which it finds as ../libexec/vcan-run/ from its own place (tools/vcan-run).
install(PROGRAMS ${PROJECT_SOURCE_DIR}/tools/vcan-run-relay.py
        DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/vcan-run)
if(TARGET uml_xstate)
  install(TARGETS uml_xstate LIBRARY DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/vcan-run)
endif()

file(GLOB CO_INSTALL_EDS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/eds/*.eds)
install(FILES ${CO_INSTALL_EDS} DESTINATION ${CO_INSTALL_EDSDIR})
install(FILES ${PROJECT_SOURCE_DIR}/eds/00F3000218090100.EDS DESTINATION ${CO_INSTALL_EDSDIR})
file(GLOB CO_INSTALL_DOCS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${CO_INSTALL_DOCS}
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The licence: its text, and the copyright file Debian's policy wants in /usr/share/doc/<package>/
# (the same in both installations, so that the package holds the files `cmake --install` does).
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/cmake/copyright
        DESTINATION ${CMAKE_INSTALL_DOCDIR})

# co_install_configured(<template> <destination>): installs <template> without its .in into
# <destination>, configured (@ONLY) when installing, so that the paths it names are those of this
# installation (cmake --install --prefix, cpack's /usr), not the prefix configured: @CO_PREFIX@,
# @CO_BINDIR@, @CO_LIBDIR@, @CO_INCLUDEDIR@, @CO_EDSDIR@, @CO_DOCDIR@ (absolute) and
# @PROJECT_VERSION@.
function(co_install_configured template destination)
  get_filename_component(name ${template} NAME)
  string(REGEX REPLACE "[.]in$" "" name ${name})
  set(output ${PROJECT_BINARY_DIR}/install-time/${name})
  set(code "set(CO_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")\n")
  foreach(dir BINDIR LIBDIR INCLUDEDIR EDSDIR DOCDIR)
    if(dir STREQUAL "EDSDIR")
      set(path ${CO_INSTALL_EDSDIR})
    else()
      set(path ${CMAKE_INSTALL_${dir}})
    endif()
    if(IS_ABSOLUTE ${path})
      string(APPEND code "set(CO_${dir} \"${path}\")\n")
    else()
      string(APPEND code "set(CO_${dir} \"\${CMAKE_INSTALL_PREFIX}/${path}\")\n")
    endif()
  endforeach()
  string(APPEND code "set(PROJECT_VERSION \"${PROJECT_VERSION}\")\n"
                     "configure_file(\"${template}\" \"${output}\" @ONLY)\n")
  install(CODE "${code}")
  install(FILES ${output} DESTINATION ${destination})
endfunction()

co_install_configured(${PROJECT_SOURCE_DIR}/cmake/canopen.pc.in
                      ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
co_install_configured(${PROJECT_SOURCE_DIR}/cmake/canopen-linux.pc.in
                      ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
co_install_configured(${PROJECT_SOURCE_DIR}/cmake/canopen-drive.pc.in
                      ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
co_install_configured(${PROJECT_SOURCE_DIR}/cmake/devicenet.pc.in
                      ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
co_install_configured(${PROJECT_SOURCE_DIR}/cmake/devicenet-drive.pc.in
                      ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
co_install_configured(${PROJECT_SOURCE_DIR}/tools/atv312d.service.in
                      ${CMAKE_INSTALL_DOCDIR}/examples)

# Man pages, written at build time from each program's --help (tools/man-from-help.py), so that
# the options are written once, in the program.
# co_man_page(<name> SUMMARY <line> SEE_ALSO <text> [SUBCOMMANDS <sub>...] COMMAND <argv>...
#             DEPENDS <file or target>...)
set(CO_MAN_PAGES)
# Ninja creates the directory of an output, the Makefile generators do not.
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/man)
function(co_man_page name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "SUMMARY;SEE_ALSO" "SUBCOMMANDS;COMMAND;DEPENDS")
  set(page ${PROJECT_BINARY_DIR}/man/${name}.1)
  set(subcommands)
  foreach(sub ${ARG_SUBCOMMANDS})
    list(APPEND subcommands --subcommand ${sub})
  endforeach()
  set(generator ${PROJECT_SOURCE_DIR}/tools/man-from-help.py)
  add_custom_command(
    OUTPUT ${page}
    COMMAND ${Python3_EXECUTABLE} ${generator} --name ${name} --summary ${ARG_SUMMARY}
            --version "${PROJECT_NAME} ${PROJECT_VERSION}" --see-also ${ARG_SEE_ALSO}
            ${subcommands} --output ${page} -- ${ARG_COMMAND}
    DEPENDS ${generator} ${ARG_DEPENDS}
    COMMENT "Writing the man page ${name}(1) from its --help"
    VERBATIM)
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
  set(CO_MAN_PAGES ${CO_MAN_PAGES} ${page} PARENT_SCOPE)
endfunction()

set(CO_DOCS_INSTALLED "${CMAKE_INSTALL_DOCDIR} under the installation prefix (docs/ in the source)")
co_man_page(atv312d
  SUMMARY "emulated Schneider Altivar drives (ATV312, ATV31 and ATV58, CANopen, CiA 402) on SocketCAN"
  SEE_ALSO "co-edstool(1), vcan-run(1), candump(1), cansend(1). The full documentation (every \
log message, the storage file, the systemd unit) is atv312d.md in ${CO_DOCS_INSTALLED}, the \
example unit examples/atv312d.service there."
  COMMAND $<TARGET_FILE:atv312d>
  DEPENDS atv312d)
co_man_page(cotrace
  SUMMARY "say what every CANopen frame of a candump -L log or a SocketCAN interface means"
  SEE_ALSO "atv312d(1), candump(1). The output format and examples are cotrace.md in \
${CO_DOCS_INSTALLED}. The EDS files of the package, for --eds, are in ${CO_INSTALL_EDSDIR} under \
the installation prefix."
  COMMAND $<TARGET_FILE:cotrace>
  DEPENDS cotrace)
co_man_page(comaster
  SUMMARY "a CANopen master on SocketCAN: SDO read and write, NMT, scan, monitor, CiA 402 drives"
  SEE_ALSO "atv312d(1), cotrace(1), candump(1). Every command with examples, the JSON fields and \
the exit codes: comaster.md in ${CO_DOCS_INSTALLED}. The EDS files of the package, found by the \
node's identity or given with --eds, are in ${CO_INSTALL_EDSDIR} under the installation prefix."
  SUBCOMMANDS ${COMASTER_COMMANDS}
  COMMAND $<TARGET_FILE:comaster>
  DEPENDS comaster)
co_man_page(dnscan
  SUMMARY "a DeviceNet scanner on SocketCAN: scan, allocate, get and set attributes, poll I/O"
  SEE_ALSO "cotrace(1), comaster(1), candump(1). Every command with examples, the JSON fields and \
the exit codes: dnscan.md in ${CO_DOCS_INSTALLED}."
  COMMAND $<TARGET_FILE:dnscan>
  DEPENDS dnscan)
co_man_page(co-edstool
  SUMMARY "generate the CANopen core's object dictionary from an EDS or DCF, check EDS files"
  SEE_ALSO "atv312d(1). eds-generator.md in ${CO_DOCS_INSTALLED}. The CMake package canopen runs \
it at build time: co_generate_od(<target> EDS <file>|DCF <file> PREFIX <name> [HOOKS <file>]). \
The EDS files of the package are in ${CO_INSTALL_EDSDIR} under the installation prefix."
  SUBCOMMANDS generate check dump
  COMMAND ${CO_EDSTOOL_COMMAND}
  DEPENDS ${CO_EDSTOOL})
co_man_page(vcan-run
  SUMMARY "run a command where a virtual CAN interface vcan0 is up, in User-Mode Linux if need be"
  SEE_ALSO "atv312d(1), candump(1), cansend(1). It needs Debian's user-mode-linux, kmod and \
iproute2 packages when the host has no vcan."
  COMMAND ${PROJECT_SOURCE_DIR}/tools/vcan-run
  DEPENDS ${PROJECT_SOURCE_DIR}/tools/vcan-run)
add_custom_target(man ALL DEPENDS ${CO_MAN_PAGES})

# The Debian package (cpack -G DEB in the build directory): everything above, in /usr. Only for
# the top-level project: CPack's configuration is the whole build's.
if(NOT CO_TOP_LEVEL)
  return()
endif()
set(CPACK_PACKAGE_NAME ${PROJECT_NAME})
set(CPACK_PACKAGE_CONTACT "canopen-atv312 maintainers <maintainers@canopen-atv312.invalid>"
    CACHE STRING "Maintainer field of the Debian package")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "CANopen (CiA 301) stack in C and emulated Altivar drives on SocketCAN")
set(CPACK_PACKAGE_DESCRIPTION "The portable CANopen core (libcanopen.a) and its Linux runtime
(libco_linux.a) with their headers, CMake package (find_package(canopen)) and pkg-config files;
co-edstool, which generates a dictionary from an EDS; atv312d, a daemon putting emulated
Schneider Altivar drives (ATV312, ATV31 and ATV58, CiA 402) on a SocketCAN interface; cotrace,
which says what every frame of a candump -L log or a live interface means; comaster, a master
command-line tool (SDO, NMT, scan, monitor, CiA 402 drives); vcan-run, which runs it
where the kernel has no vcan.")
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION devel)
# libc from the daemon's own dependencies (dpkg-shlibdeps); python3 for co-edstool.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3")
# libmicrohttpd for atv312d --http: loaded only then, so dpkg-shlibdeps does not see it, and a
# recommendation, not a dependency, since the daemon runs without it (apps/atv312d/CMakeLists.txt
# names its package).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "can-utils, ${ATV312D_MHD_PACKAGE}")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "cmake, pkg-config, user-mode-linux, kmod, iproute2")
# The licence, for the generators that show or record one (the Debian package has no licence
# field: its copyright file is installed above). RPM's field, FreeBSD's falls back to it.
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_RPM_PACKAGE_LICENSE "Apache-2.0")
include(CPack)
