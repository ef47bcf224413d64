# SPDX-License-Identifier: Apache-2.0
# modcp — CMake toolchain file for Debian's arm-none-eabi-gcc (newlib, newlib-nano).
#
#   cmake -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake -DMODCP_ARM_CPU=cortex-m3 ...
#
# MODCP_ARM_CPU selects the core (cmake/cortex-m-profiles.cmake): cortex-m0, cortex-m0plus,
# cortex-m3 (soft float), cortex-m4 (FPv4-SP), cortex-m7 (FPv5 double precision),
# cortex-m33 (FPv5-SP, ARMv8-M mainline without TrustZone code); hard float ABI where
# there is an FPU. Everything (core library, HAL, boards) is compiled -Os with function and
# data sections; executables are linked with --gc-sections against newlib-nano and no
# host start files (each board brings its own startup code and linker script). The core
# library is also compiled for link-time optimisation (MODCP_LTO, firmware/CMakeLists.txt;
# boards/ links the images with -flto). Keep -mcpu/-mthumb in the link flags: a
# CMAKE_EXE_LINKER_FLAGS given on the command line replaces the _INIT value below, and
# the LTO code generation at link time then targets the wrong core.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

include(${CMAKE_CURRENT_LIST_DIR}/cortex-m-profiles.cmake)
set(MODCP_ARM_CPU "cortex-m3" CACHE STRING "Cortex-M core: ${MODCP_ARM_CPUS}")
set_property(CACHE MODCP_ARM_CPU PROPERTY STRINGS ${MODCP_ARM_CPUS})
# try_compile() projects see the same core.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES MODCP_ARM_CPU)

set(_prefix arm-none-eabi-)
find_program(CMAKE_C_COMPILER ${_prefix}gcc REQUIRED)
find_program(CMAKE_ASM_COMPILER ${_prefix}gcc)
find_program(CMAKE_OBJCOPY ${_prefix}objcopy REQUIRED)
find_program(CMAKE_SIZE ${_prefix}size)
find_program(CMAKE_NM ${_prefix}nm)
set(CMAKE_AR ${_prefix}ar CACHE FILEPATH "archiver")
set(CMAKE_RANLIB ${_prefix}ranlib CACHE FILEPATH "ranlib")

# No host executables can run: test the compiler with a static library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

modcp_cortex_m_flags(${MODCP_ARM_CPU} _cpu)

set(CMAKE_C_FLAGS_INIT "${_cpu} -ffunction-sections -fdata-sections -fno-common")
set(CMAKE_ASM_FLAGS_INIT "${_cpu}")
# -Os for every build type: the size report is made on this image.
set(CMAKE_C_FLAGS_DEBUG_INIT "-Os -g3")
set(CMAKE_C_FLAGS_RELEASE_INIT "-Os -DNDEBUG")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os -DNDEBUG")
set(CMAKE_C_FLAGS_RELWITHDEBINFO_INIT "-Os -g -DNDEBUG")
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "${_cpu} -specs=nano.specs -nostartfiles -Wl,--gc-sections -Wl,--print-memory-usage")

set(CMAKE_EXECUTABLE_SUFFIX_C .elf)
set(CMAKE_EXECUTABLE_SUFFIX .elf)

# Look for libraries and headers only in the toolchain's sysroot.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
