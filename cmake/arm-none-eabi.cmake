# SPDX-License-Identifier: Apache-2.0
# Toolchain file for building the portable core for a Cortex-M with Debian's gcc-arm-none-eabi:
#   cmake -S . -B build-m4 -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake -DCO_CORE_ONLY=ON
# CO_CORTEX_CPU picks the core (a -mcpu value): cortex-m4 by default, cortex-m0 for the smallest
# Thumb instruction set CI builds.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
# A bare-metal toolchain cannot link a test executable without a board's startup code.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
if(NOT CO_CORTEX_CPU)
  set(CO_CORTEX_CPU cortex-m4)
endif()
# try_compile projects read this file again: they must see the same CPU.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES CO_CORTEX_CPU)
set(CMAKE_C_FLAGS_INIT "-mcpu=${CO_CORTEX_CPU} -mthumb")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os")
