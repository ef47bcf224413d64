# SPDX-License-Identifier: Apache-2.0
# modcp — TI Stellaris LM3S6965 evaluation board (Cortex-M3; QEMU lm3s6965evb): PL011
# UART + GPTM timers + SysTick. Included by boards/CMakeLists.txt for
# MODCP_BOARD=lm3s6965evb or MODCP_BOARD_DIR=<this folder>; board.env beside it names the
# core and the QEMU machine.
include(${MODCP_ROOT}/hal/lm3s/CMakeLists.txt)
modcp_firmware(${MODCP_BOARD} ${MODCP_BOARD_DIR}/lm3s6965evb.ld modcp_hal_lm3s
  ${MODCP_BOARD_DIR}/board.c)
