# SPDX-License-Identifier: Apache-2.0
# libFuzzer build (-DMODCP_FUZZ=ON with CC=clang; tools/fuzz configures build/fuzz).
# Every library of the build -- the core (firmware/), the console, the config reader
# (tools/conf) -- is compiled with coverage instrumentation and ASan + UBSan, so that
# the fuzzer is guided by the code under test, not only by its harness. The fuzz
# targets themselves (tests/fuzz/, modcp_fuzz_target) link libFuzzer's main.
option(MODCP_FUZZ "Build the libFuzzer targets (clang; instruments the whole build)" OFF)
if(MODCP_FUZZ)
  if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "MODCP_FUZZ needs clang (configure with CC=clang)")
  endif()
  set(MODCP_FUZZ_SANITIZERS address,undefined)
  add_compile_options(-fsanitize=fuzzer-no-link,${MODCP_FUZZ_SANITIZERS}
                      -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${MODCP_FUZZ_SANITIZERS})
  # clang's -Wconversion includes implicit enum -> uint8_t conversions gcc accepts
  # (tools/conf/conf_keys.c); the gcc builds keep them errors, here they stay warnings.
endif()

# modcp_fuzz_target(<name> SOURCES <src...> LIBS <lib...> [DEFS <def...>]):
# a libFuzzer executable (only in the MODCP_FUZZ build).
function(modcp_fuzz_target name)
  cmake_parse_arguments(F "" "" "SOURCES;LIBS;DEFS" ${ARGN})
  if(NOT MODCP_FUZZ)
    return()
  endif()
  add_executable(${name} ${F_SOURCES})
  target_compile_definitions(${name} PRIVATE MODCP_LIBFUZZER ${F_DEFS})
  target_compile_options(${name} PRIVATE -fsanitize=fuzzer,${MODCP_FUZZ_SANITIZERS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer,${MODCP_FUZZ_SANITIZERS})
  target_link_libraries(${name} PRIVATE ${F_LIBS})
  target_compile_options(${name} PRIVATE -Wall -Wextra -Werror)
endfunction()
