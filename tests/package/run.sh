#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# modcp as a CMake package: an outside project (tests/package/outside) adds the modcp
# tree with add_subdirectory() and links modcp::core. Built for the host and run (the
# manual's FC03 example through the public API), then built for Cortex-M3.
#   tests/package/run.sh ROOT BUILD_DIR
set -euo pipefail
ROOT=$1
B=$2/package
rm -rf "$B"
echo "== host"
cmake -S "$ROOT/tests/package/outside" -B "$B/host" -G Ninja -DMODCP_DIR="$ROOT" >/dev/null
cmake --build "$B/host" >/dev/null
"$B/host/outside_app" && echo "host: the outside application's FC03 reply is the manual's"
if command -v arm-none-eabi-gcc >/dev/null; then
  echo "== cortex-m3"
  cmake -S "$ROOT/tests/package/outside" -B "$B/arm" -G Ninja -DMODCP_DIR="$ROOT" \
        -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/arm-none-eabi.cmake" -DMODCP_ARM_CPU=cortex-m3 >/dev/null
  cmake --build "$B/arm" >/dev/null
  ls "$B/arm/liboutside_app.a" "$B/arm/modcp/firmware/libmodcp_core.a" >/dev/null
  echo "cortex-m3: outside application and modcp::core built"
else
  echo "arm-none-eabi-gcc missing (Debian: gcc-arm-none-eabi): Cortex-M part not built"
  exit 1
fi
