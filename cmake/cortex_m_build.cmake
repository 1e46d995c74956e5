# SPDX-License-Identifier: Apache-2.0
# ctest script: configures and builds the portable core, the DeviceNet slave and scanner with
# arm-none-eabi-gcc for one Cortex-M (-Os, -Wall -Wextra -pedantic and, whatever the calling
# build's CO_WERROR, -Werror) and prints their size: text / data / bss of each module, then the
# RAM of one CANopen node in the default configuration (include/co/co_config.h), of one
# DeviceNet slave and of a scanner, as the target's compiler lays them out. Fails when the toolchain is missing.
#   cmake -DSOURCE_DIR=<repo> -DBINARY_DIR=<dir> -DCPU=cortex-m0 -P cmake/cortex_m_build.cmake
find_program(ARM_GCC arm-none-eabi-gcc)
find_program(ARM_NM arm-none-eabi-nm)
if(NOT ARM_GCC OR NOT ARM_NM)
  message(FATAL_ERROR "arm-none-eabi-gcc not found: install Debian's gcc-arm-none-eabi (scripts/setup)")
endif()
if(NOT CPU)
  set(CPU cortex-m4)
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -DCO_CORE_ONLY=ON -DCO_WERROR=ON
          -DCMAKE_BUILD_TYPE=MinSizeRel -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/cmake/arm-none-eabi.cmake
          -DCO_CORTEX_CPU=${CPU}
  RESULT_VARIABLE configured)
if(NOT configured EQUAL 0)
  message(FATAL_ERROR "configuring the ${CPU} build failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} RESULT_VARIABLE built)
if(NOT built EQUAL 0)
  message(FATAL_ERROR "the core does not build for ${CPU}")
endif()
execute_process(COMMAND arm-none-eabi-size -t ${BINARY_DIR}/libcanopen.a)
# The DeviceNet slave library and the scanner, built by the same configuration
# (docs/footprint.md).
execute_process(COMMAND arm-none-eabi-size -t ${BINARY_DIR}/libdevicenet.a)
execute_process(COMMAND arm-none-eabi-size -t ${BINARY_DIR}/libdnscanner.a)

# sizeof(co_node_t) for this CPU, without running anything on it: the size of a variable of that
# type in an object file.
file(WRITE ${BINARY_DIR}/node_size.c "#include \"co/co_node.h\"\nco_node_t co_node_size;\n")
execute_process(
  COMMAND ${ARM_GCC} -mcpu=${CPU} -mthumb -Os -std=c11 -fno-common -I${SOURCE_DIR}/include -c
          ${BINARY_DIR}/node_size.c -o ${BINARY_DIR}/node_size.o RESULT_VARIABLE compiled)
execute_process(COMMAND ${ARM_NM} -S -t d ${BINARY_DIR}/node_size.o OUTPUT_VARIABLE symbols)
if(NOT compiled EQUAL 0 OR NOT symbols MATCHES "[0-9]+ 0*([0-9]+) B co_node_size")
  message(FATAL_ERROR "could not measure sizeof(co_node_t) for ${CPU}")
endif()
message("${CPU}: sizeof(co_node_t) = ${CMAKE_MATCH_1} bytes (default co_config.h)")

# sizeof(dn_node_t), the RAM of one DeviceNet slave, the same way.
file(WRITE ${BINARY_DIR}/dn_node_size.c "#include \"dn/dn_node.h\"\ndn_node_t dn_node_size;\n")
execute_process(
  COMMAND ${ARM_GCC} -mcpu=${CPU} -mthumb -Os -std=c11 -fno-common -I${SOURCE_DIR}/include -c
          ${BINARY_DIR}/dn_node_size.c -o ${BINARY_DIR}/dn_node_size.o RESULT_VARIABLE compiled)
execute_process(COMMAND ${ARM_NM} -S -t d ${BINARY_DIR}/dn_node_size.o OUTPUT_VARIABLE symbols)
if(NOT compiled EQUAL 0 OR NOT symbols MATCHES "[0-9]+ 0*([0-9]+) B dn_node_size")
  message(FATAL_ERROR "could not measure sizeof(dn_node_t) for ${CPU}")
endif()
message("${CPU}: sizeof(dn_node_t) = ${CMAKE_MATCH_1} bytes")

# sizeof(dn_scanner_t), the RAM of a scanner without its slaves, and sizeof(dn_slave_t), each
# slave's (the application allocates one per slave it talks to).
file(WRITE ${BINARY_DIR}/dn_scanner_size.c
     "#include \"dn/dn_scanner.h\"\ndn_scanner_t dn_scanner_size;\ndn_slave_t dn_slave_size;\n")
execute_process(
  COMMAND ${ARM_GCC} -mcpu=${CPU} -mthumb -Os -std=c11 -fno-common -I${SOURCE_DIR}/include -c
          ${BINARY_DIR}/dn_scanner_size.c -o ${BINARY_DIR}/dn_scanner_size.o
  RESULT_VARIABLE compiled)
execute_process(COMMAND ${ARM_NM} -S -t d ${BINARY_DIR}/dn_scanner_size.o OUTPUT_VARIABLE symbols)
if(NOT compiled EQUAL 0 OR NOT symbols MATCHES "[0-9]+ 0*([0-9]+) B dn_scanner_size")
  message(FATAL_ERROR "could not measure sizeof(dn_scanner_t) for ${CPU}")
endif()
set(scanner_size ${CMAKE_MATCH_1})
if(NOT symbols MATCHES "[0-9]+ 0*([0-9]+) B dn_slave_size")
  message(FATAL_ERROR "could not measure sizeof(dn_slave_t) for ${CPU}")
endif()
message("${CPU}: sizeof(dn_scanner_t) = ${scanner_size} bytes, sizeof(dn_slave_t) = ${CMAKE_MATCH_1} bytes")
