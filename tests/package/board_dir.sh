#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A board in one folder, out of the tree: a copy of boards/mps2-an385 under another name
# and path is built with -DMODCP_BOARD_DIR (Cortex-M3); the image is named after the
# folder. Nothing of modcp's tree is edited for it.
#   tests/package/board_dir.sh ROOT BUILD_DIR MODCP_CONF
set -euo pipefail
ROOT=$1
B=$2/board_dir
CONF=$3
command -v arm-none-eabi-gcc >/dev/null || {
  echo "arm-none-eabi-gcc missing (Debian: gcc-arm-none-eabi libnewlib-arm-none-eabi)"; exit 1; }
rm -rf "$B"
mkdir -p "$B/elsewhere"
cp -r "$ROOT/boards/mps2-an385" "$B/elsewhere/acme-board"
cmake -S "$ROOT" -B "$B/build" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" \
      -DMODCP_ARM_CPU=cortex-m3 -DMODCP_BOARD_DIR="$B/elsewhere/acme-board" \
      -DMODCP_CONF_TOOL="$CONF" -DCMAKE_BUILD_TYPE=MinSizeRel >/dev/null
cmake --build "$B/build" --target modcp-acme-board >/dev/null
text=$(arm-none-eabi-size "$B/build/modcp-acme-board.elf" | awk 'NR == 2 { print $1 }')
[ "${text:-0}" -gt 10000 ] || { echo "modcp-acme-board.elf: text $text bytes?"; exit 1; }
echo "out-of-tree board $B/elsewhere/acme-board -> modcp-acme-board.elf, $text bytes of text"
