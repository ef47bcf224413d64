# SPDX-License-Identifier: Apache-2.0
# modcp — STM32F405 (Cortex-M4F; QEMU netduinoplus2): USART + TIM + GPIO. Included by
# boards/CMakeLists.txt for MODCP_BOARD=stm32f405 or MODCP_BOARD_DIR=<this folder>.
include(${MODCP_ROOT}/hal/stm32f4/CMakeLists.txt)
modcp_firmware(${MODCP_BOARD} ${MODCP_BOARD_DIR}/stm32f405.ld modcp_hal_stm32f4
  ${MODCP_BOARD_DIR}/board.c)
