#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A board in one folder, out of the tree (docs/porting.md §6): a copy of
# boards/mps2-an385 under another name and path is built with the documented command
#     tools/build-board <folder> --build-dir <dir>
# (the image and its QEMU twin are named after the folder), then, when QEMU is there,
# tools/run-qemu <folder> names it in its banner and the smoke suite runs against it
# (tests/qemu/qemu_test.py --board <folder>). Nothing of modcp's tree is edited for it.
#   tests/package/board_dir.sh ROOT BUILD_DIR
set -euo pipefail
ROOT=$1
B=$2/board_dir
command -v arm-none-eabi-gcc >/dev/null || {
  echo "arm-none-eabi-gcc missing (Debian: gcc-arm-none-eabi libnewlib-arm-none-eabi)"; exit 1; }
rm -rf "$B"
mkdir -p "$B/elsewhere"
board=$B/elsewhere/acme-board
cp -r "$ROOT/boards/mps2-an385" "$board"
"$ROOT/tools/build-board" "$board" --build-dir "$B/build"
for f in modcp-acme-board.elf modcp-acme-board.bin modcp-acme-board-qemu.elf; do
  [ -f "$B/build/$f" ] || { echo "tools/build-board made no $B/build/$f"; exit 1; }
done
text=$(arm-none-eabi-size "$B/build/modcp-acme-board.elf" | awk 'NR == 2 { print $1 }')
[ "${text:-0}" -gt 10000 ] || { echo "modcp-acme-board.elf: text $text bytes?"; exit 1; }
echo "out-of-tree board $board -> modcp-acme-board.elf, $text bytes of text"

if ! command -v qemu-system-arm >/dev/null; then
  echo "qemu-system-arm missing: the QEMU part is not run"
  exit 0
fi
timeout -s TERM 5 "$ROOT/tools/run-qemu" "$board" --elf "$B/build/modcp-acme-board.elf" \
  >"$B/run-qemu.log" 2>&1 || true
grep -q "^modcp acme-board in QEMU mps2-an385 (modcp-acme-board.elf)" "$B/run-qemu.log" ||
  { echo "tools/run-qemu banner:"; cat "$B/run-qemu.log"; exit 1; }
head -1 "$B/run-qemu.log"
/usr/bin/python3 "$ROOT/tests/qemu/qemu_test.py" --root "$ROOT" --board "$board" --suite smoke \
  --elf "$B/build/modcp-acme-board.elf"
