# ctest script: configures and builds the portable core with arm-none-eabi-gcc for a Cortex-M4
# (-Os, -Wall -Wextra -pedantic and, whatever the calling build's CO_WERROR, -Werror) and prints its
# size. Fails when the toolchain is missing.
#   cmake -DSOURCE_DIR=<repo> -DBINARY_DIR=<dir> -P cmake/cortex_m_build.cmake
find_program(ARM_GCC arm-none-eabi-gcc)
if(NOT ARM_GCC)
  message(FATAL_ERROR "arm-none-eabi-gcc not found: install Debian's gcc-arm-none-eabi (tools/setup)")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -DCO_CORE_ONLY=ON -DCO_WERROR=ON
          -DCMAKE_BUILD_TYPE=MinSizeRel -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/cmake/arm-none-eabi.cmake
  RESULT_VARIABLE configured)
if(NOT configured EQUAL 0)
  message(FATAL_ERROR "configuring the Cortex-M4 build failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} RESULT_VARIABLE built)
if(NOT built EQUAL 0)
  message(FATAL_ERROR "the core does not build for Cortex-M4")
endif()
execute_process(COMMAND arm-none-eabi-size -t ${BINARY_DIR}/libcanopen.a)
