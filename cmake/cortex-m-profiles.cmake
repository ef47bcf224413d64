# SPDX-License-Identifier: Apache-2.0
# modcp — the Cortex-M profiles the core is built for (cmake/arm-none-eabi.cmake, the
# core-<profile> presets, tools/build-arm, tools/size).
#
#   profile        core            ISA              float
#   cortex-m0      Cortex-M0       ARMv6-M          soft (no FPU)   e.g. nRF51822 (micro:bit)
#   cortex-m0plus  Cortex-M0+      ARMv6-M          soft            e.g. RP2040, STM32G0
#   cortex-m3      Cortex-M3       ARMv7-M          soft            e.g. MPS2 AN385
#   cortex-m4      Cortex-M4F      ARMv7E-M         FPv4-SP, hard   e.g. STM32F405
#   cortex-m7      Cortex-M7       ARMv7E-M         FPv5-D16, hard  e.g. STM32F7/H7
#   cortex-m33     Cortex-M33      ARMv8-M main     FPv5-SP, hard   e.g. MPS2 AN505, nRF5340
#
# ARMv6-M has no BASEPRI, no hardware divide, no unaligned access, word-only NVIC / SCB
# priority registers and no configurable fault handlers; the core uses none of them.
set(MODCP_ARM_CPUS cortex-m0 cortex-m0plus cortex-m3 cortex-m4 cortex-m7 cortex-m33)

# modcp_cortex_m_flags(<profile> <out var>): the compiler flags of one profile.
function(modcp_cortex_m_flags cpu out)
  if(cpu STREQUAL "cortex-m0" OR cpu STREQUAL "cortex-m0plus" OR cpu STREQUAL "cortex-m3")
    set(f "-mcpu=${cpu} -mthumb -mfloat-abi=soft")
  elseif(cpu STREQUAL "cortex-m4")
    set(f "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
  elseif(cpu STREQUAL "cortex-m7")
    set(f "-mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-d16")
  elseif(cpu STREQUAL "cortex-m33")
    set(f "-mcpu=cortex-m33 -mthumb -mfloat-abi=hard -mfpu=fpv5-sp-d16")
  else()
    message(FATAL_ERROR "MODCP_ARM_CPU must be one of ${MODCP_ARM_CPUS}, not '${cpu}'")
  endif()
  set(${out} "${f}" PARENT_SCOPE)
endfunction()
