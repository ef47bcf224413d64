# SPDX-License-Identifier: Apache-2.0
# modcp — ARM MPS2 AN385 (Cortex-M3, CMSDK UART + timer). Included by boards/CMakeLists.txt
# for MODCP_BOARD=mps2-an385 or MODCP_BOARD_DIR=<this folder>: the image modcp-<board>.elf
# from the common application, this folder's board.c and linker script, and the CMSDK HAL.
include(${MODCP_ROOT}/hal/cmsdk/CMakeLists.txt)
modcp_firmware(${MODCP_BOARD} ${MODCP_BOARD_DIR}/mps2-an385.ld modcp_hal_cmsdk
  ${MODCP_BOARD_DIR}/board.c)
