# SPDX-License-Identifier: Apache-2.0
# modcp — BBC micro:bit (nRF51822, Cortex-M0). Included by boards/CMakeLists.txt with
# MODCP_BOARD=microbit (preset microbit, MODCP_ARM_CPU=cortex-m0) or
# MODCP_BOARD_DIR=<this folder>.
#
# The image is linked with link-time optimisation of its own sources (app.c, board.c):
# the board's console functions do nothing (no second UART), so the application's
# console code and its buffers (2 KB), the console library and the C library's float
# formatting drop out, which the 16 KB of RAM needs. The libraries (core, HAL,
# configuration) are the same objects as without LTO.
include(${MODCP_ROOT}/hal/nrf51/CMakeLists.txt)
set(_variants modcp-${MODCP_BOARD}:modcp_cfg)
if(MODCP_QEMU_CFG_C)
  list(APPEND _variants modcp-${MODCP_BOARD}-qemu:modcp_cfg_qemu)
endif()
foreach(v ${_variants})
  string(REPLACE ":" ";" v ${v})
  list(GET v 0 _name)
  list(GET v 1 _cfg)
  modcp_image(${_name} ${MODCP_BOARD_DIR}/microbit.ld
    ${BOARDS_DIR}/common/app.c ${MODCP_BOARD_DIR}/board.c)
  target_link_libraries(${_name} PRIVATE modcp_hal_nrf51 ${_cfg} modcp_console modcp_core)
  set_target_properties(${_name} PROPERTIES INTERPROCEDURAL_OPTIMIZATION ON)
endforeach()
