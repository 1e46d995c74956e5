# ctest script: configures, builds and links the bare-metal example examples/cortex-m4 (-Os,
# -Werror) with arm-none-eabi-gcc and prints its footprint (examples/cortex-m4/footprint.py):
# the core's flash after --gc-sections file by file, and the RAM of the node beside its
# dictionary's variables and the SDO buffer.
#   cmake -DSOURCE_DIR=<repo> -DBINARY_DIR=<dir> -DPYTHON=<python3> -P cmake/cortex_m_example.cmake
set(example ${SOURCE_DIR}/examples/cortex-m4)
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${example} -B ${BINARY_DIR} -DCMAKE_BUILD_TYPE=MinSizeRel
          -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/cmake/arm-none-eabi.cmake -DCO_CORTEX_CPU=cortex-m4
          -DPython3_EXECUTABLE=${PYTHON}
  RESULT_VARIABLE configured)
if(NOT configured EQUAL 0)
  message(FATAL_ERROR "configuring the Cortex-M4 example failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} RESULT_VARIABLE built)
if(NOT built EQUAL 0)
  message(FATAL_ERROR "the Cortex-M4 example does not build or link")
endif()
execute_process(COMMAND arm-none-eabi-size ${BINARY_DIR}/blinky.elf)
execute_process(COMMAND ${PYTHON} ${example}/footprint.py ${BINARY_DIR}/blinky.map
                        ${BINARY_DIR}/blinky.elf RESULT_VARIABLE printed)
if(NOT printed EQUAL 0)
  message(FATAL_ERROR "footprint.py failed")
endif()
