# SPDX-License-Identifier: Apache-2.0
# ctest script: configures, builds and links the bare-metal example examples/cortex-m4 (-Os,
# -Werror) with arm-none-eabi-gcc and prints its footprint (examples/cortex-m4/footprint.py):
# the core's flash after --gc-sections file by file, and the RAM of the node beside its
# dictionary's variables and the SDO buffer; twice: blinky.eds whole (SYNC producer linked), then
# without 1006h (BLINKY_OMIT=0x1006, in BINARY_DIR/no-producer: no SYNC producer); and the firmware
# that runs, for the mps2-an386 board that QEMU emulates (BINARY_DIR/mps2-an386/blinky.elf, which
# the integration test firmware_socketcan boots: tests/integration/CMakeLists.txt).
#   cmake -DSOURCE_DIR=<repo> -DBINARY_DIR=<dir> -DPYTHON=<python3> -P cmake/cortex_m_example.cmake
set(example ${SOURCE_DIR}/examples/cortex-m4)
function(build_and_measure dir title omit board)
  message("${title}")
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${example} -B ${dir} -DCMAKE_BUILD_TYPE=MinSizeRel
            -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/cmake/arm-none-eabi.cmake -DCO_CORTEX_CPU=cortex-m4
            -DPython3_EXECUTABLE=${PYTHON} -DBLINKY_OMIT=${omit} -DBLINKY_BOARD=${board}
    RESULT_VARIABLE configured)
  if(NOT configured EQUAL 0)
    message(FATAL_ERROR "configuring the Cortex-M4 example failed")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${dir} RESULT_VARIABLE built)
  if(NOT built EQUAL 0)
    message(FATAL_ERROR "the Cortex-M4 example does not build or link")
  endif()
  execute_process(COMMAND arm-none-eabi-size ${dir}/blinky.elf)
  execute_process(COMMAND ${PYTHON} ${example}/footprint.py ${dir}/blinky.map ${dir}/blinky.elf
                  RESULT_VARIABLE printed)
  if(NOT printed EQUAL 0)
    message(FATAL_ERROR "footprint.py failed")
  endif()
endfunction()
build_and_measure(${BINARY_DIR} "blinky.eds (with 1006h: SYNC producer linked)" "" stub)
build_and_measure(${BINARY_DIR}/no-producer "blinky.eds without 1006h (no SYNC producer)" 0x1006 stub)
build_and_measure(${BINARY_DIR}/mps2-an386 "the firmware that runs: mps2-an386 board, slcan over UART0" ""
                  mps2-an386)
