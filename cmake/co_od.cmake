# SPDX-License-Identifier: Apache-2.0
# co_generate_od(<target> EDS <file>|DCF <file> PREFIX <name> [HOOKS <file>] [OMIT <index>...])
#
# Generates the object dictionary <name>_od (edstool generate) from an EDS at build time, or from
# a DCF (a configured device: its ParameterValues as the defaults, docs/eds-generator.md), without
# the objects OMIT lists (a variant of the device that lacks them), into
# ${CMAKE_CURRENT_BINARY_DIR}/<target>_gen/ and wraps it in <target>, an OBJECT library whose
# include directory (for <name>_od.h) is PUBLIC and which links canopen::core PUBLIC.
#
# Why an OBJECT library: the generated table refers to the hooks named in the hooks file, which
# the application defines. Object files are linked directly into whatever links <target> (an
# executable, or the archive of a static library), so the hooks resolve whatever the link order:
# link <target> into the library or executable that defines the hooks (or into anything linked
# together with it). Link <target> directly into one target per executable, or the table would be
# defined twice.
#
# The command reruns when the EDS (or DCF), the hooks file or the generator change.
#
# Whoever includes this file says which generator to run: CO_EDSTOOL (the script, a dependency of
# the command) and CO_EDSTOOL_COMMAND (how to run it). The source tree runs tools/edstool.py with
# its Python (CMakeLists.txt); the installed package runs the installed co-edstool
# (cmake/canopenConfig.cmake.in). Both are kept as global properties, so that co_generate_od()
# works in any directory, also outside the one that included this file (a project including this
# one with add_subdirectory(), or calling find_package() in a subdirectory).

if(NOT CO_EDSTOOL OR NOT CO_EDSTOOL_COMMAND)
  message(FATAL_ERROR "co_od.cmake: set CO_EDSTOOL and CO_EDSTOOL_COMMAND before including it")
endif()
set_property(GLOBAL PROPERTY CO_EDSTOOL ${CO_EDSTOOL})
set_property(GLOBAL PROPERTY CO_EDSTOOL_COMMAND ${CO_EDSTOOL_COMMAND})

function(co_generate_od target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "EDS;DCF;PREFIX;HOOKS" "OMIT")
  if(ARG_EDS AND ARG_DCF)
    message(FATAL_ERROR "co_generate_od(${target}): EDS and DCF exclude each other")
  endif()
  if(ARG_DCF)
    set(ARG_EDS ${ARG_DCF})
  endif()
  if(NOT ARG_EDS OR NOT ARG_PREFIX)
    message(FATAL_ERROR "co_generate_od(${target}): EDS <file> (or DCF <file>) and PREFIX <name> "
                        "are required")
  endif()
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "co_generate_od(${target}): unexpected arguments ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  get_property(edstool GLOBAL PROPERTY CO_EDSTOOL)
  get_property(edstool_command GLOBAL PROPERTY CO_EDSTOOL_COMMAND)
  get_filename_component(eds ${ARG_EDS} ABSOLUTE)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_gen)
  set(outputs ${out_dir}/${ARG_PREFIX}_od.c ${out_dir}/${ARG_PREFIX}_od.h)
  set(command ${edstool_command} generate ${eds} --prefix ${ARG_PREFIX} --out-dir ${out_dir})
  set(depends ${eds} ${edstool})
  if(ARG_HOOKS)
    get_filename_component(hooks ${ARG_HOOKS} ABSOLUTE)
    list(APPEND command --hooks ${hooks})
    list(APPEND depends ${hooks})
  endif()
  if(ARG_OMIT)
    list(APPEND command --omit ${ARG_OMIT})
  endif()
  add_custom_command(
    OUTPUT ${outputs}
    COMMAND ${command}
    DEPENDS ${depends}
    COMMENT "Generating ${ARG_PREFIX}_od from ${ARG_EDS}"
    VERBATIM)
  add_library(${target} OBJECT ${outputs})
  target_include_directories(${target} PUBLIC ${out_dir})
  target_link_libraries(${target} PUBLIC canopen::core)
  target_compile_options(${target} PRIVATE ${CO_WARNINGS})
endfunction()
