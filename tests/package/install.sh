#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# modcp as an installed package (cmake/install.cmake): `cmake --install` into a staging
# prefix, then outside projects that know nothing but that prefix:
#   - CMake: tests/package/outside with find_package(modcp 0.2 CONFIG REQUIRED) (run on
#     the host: the manual's FC03 example through the public API); the compile definitions
#     modcp::core gives it are the -D switches of `pkg-config --cflags modcp`;
#     find_package(modcp 1.0) is refused (SameMajorVersion), and so is the host package
#     in a Cortex-M3 build (pointer size);
#   - Make: tests/package/make/Makefile with `pkg-config --cflags --libs modcp` (run on
#     the host);
#   - the same two for Cortex-M3 against a cross build of modcp (MODCP_BOARD=core, with
#     a ring depth of 8 and no ASCII, which must reach both) installed into its own
#     prefix (a static library / a linked ELF, not run).
#   tests/package/install.sh ROOT BUILD_DIR HOST_BUILD_DIR
set -euo pipefail
ROOT=$1
B=$2/package-install
HOST_BUILD=$3
rm -rf "$B"
mkdir -p "$B"
fail() { echo "FAIL: $*"; exit 1; }

# defs_equal OUTSIDE_BUILD PC_PATH: modcp::core's compile definitions == pkg-config's -D
defs_equal() {
  local cm pc
  cm=$(sort "$1/modcp_core_defs.txt" | sed '/^$/d')
  pc=$(PKG_CONFIG_PATH="$2" pkg-config --cflags modcp | tr ' ' '\n' | sed -n 's/^-D//p' | sort)
  [ -n "$cm" ] && [ "$cm" = "$pc" ] ||
    fail "modcp::core's definitions ($(echo $cm)) != pkg-config --cflags modcp ($(echo $pc))"
  echo "  modcp::core and pkg-config --cflags modcp: the same definitions ($(echo $pc))"
}

echo "== host: cmake --install $HOST_BUILD --prefix $B/stage-host"
cmake --install "$HOST_BUILD" --prefix "$B/stage-host" >/dev/null
PC_HOST=$B/stage-host/lib/pkgconfig
[ "$(PKG_CONFIG_PATH=$PC_HOST pkg-config --modversion modcp)" = "$(sed -n 's/^#define MODCP_VERSION "\(.*\)"$/\1/p' "$B/stage-host/include/modcp/version.h")" ] ||
  fail "modcp.pc's version is not modcp/version.h's"
cmake -S "$ROOT/tests/package/outside" -B "$B/host" -G Ninja \
      -DCMAKE_PREFIX_PATH="$B/stage-host" >"$B/host.log" || { cat "$B/host.log"; fail "host configure"; }
grep "^-- modcp " "$B/host.log"
cmake --build "$B/host" >/dev/null
"$B/host/outside_app" || fail "host (find_package): the FC03 reply is not the manual's"
echo "host (find_package): the outside application's FC03 reply is the manual's"
defs_equal "$B/host" "$PC_HOST"
if cmake -S "$ROOT/tests/package/outside" -B "$B/host-v1" -G Ninja -DMODCP_WANT_VERSION=1.0 \
         -DCMAKE_PREFIX_PATH="$B/stage-host" >"$B/host-v1.log" 2>&1; then
  fail "find_package(modcp 1.0) accepted modcp $(PKG_CONFIG_PATH=$PC_HOST pkg-config --modversion modcp)"
fi
grep -q "requested version \"1.0\"" "$B/host-v1.log" ||
  { cat "$B/host-v1.log"; fail "find_package(modcp 1.0): not refused by the version check"; }
echo "host: find_package(modcp 1.0) refused (SameMajorVersion)"
mkdir -p "$B/make-host"
PKG_CONFIG_PATH=$PC_HOST make -s -f "$ROOT/tests/package/make/Makefile" OUT="$B/make-host" >/dev/null
"$B/make-host/outside_app" || fail "host (pkg-config, make): the FC03 reply is not the manual's"
echo "host (pkg-config, make): the outside application's FC03 reply is the manual's"

command -v arm-none-eabi-gcc >/dev/null ||
  fail "arm-none-eabi-gcc missing (Debian: gcc-arm-none-eabi): Cortex-M part not built"
echo "== cortex-m3: modcp built with MODCP_BOARD=core, MODCP_BP_DEPTH=8, MODCP_WITH_ASCII=OFF, installed into $B/stage-m3"
TC=$ROOT/cmake/arm-none-eabi.cmake
cmake -S "$ROOT" -B "$B/modcp-m3" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$TC" -DMODCP_ARM_CPU=cortex-m3 \
      -DMODCP_BOARD=core -DCMAKE_BUILD_TYPE=MinSizeRel -DMODCP_BP_DEPTH=8 -DMODCP_WITH_ASCII=OFF >/dev/null
cmake --build "$B/modcp-m3" >/dev/null
cmake --install "$B/modcp-m3" --prefix "$B/stage-m3" >/dev/null
cmake -S "$ROOT/tests/package/outside" -B "$B/arm" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$TC" \
      -DMODCP_ARM_CPU=cortex-m3 -DCMAKE_PREFIX_PATH="$B/stage-m3" >"$B/arm.log" || { cat "$B/arm.log"; fail "cortex-m3 configure"; }
grep "^-- modcp " "$B/arm.log"
cmake --build "$B/arm" >/dev/null
ls "$B/arm/liboutside_app.a" >/dev/null
echo "cortex-m3 (find_package): outside application built against modcp::core and modcp::hal_cmsdk"
if cmake -S "$ROOT/tests/package/outside" -B "$B/arm-host-pkg" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$TC" \
         -DMODCP_ARM_CPU=cortex-m3 -DCMAKE_PREFIX_PATH="$B/stage-host" >"$B/arm-host-pkg.log" 2>&1; then
  fail "a Cortex-M3 build accepted the host package"
fi
grep -q "version: [0-9.]* ([0-9]*bit)" "$B/arm-host-pkg.log" ||
  { cat "$B/arm-host-pkg.log"; fail "the host package was not refused by its version file"; }
echo "cortex-m3: the host package is refused (pointer size, modcpConfigVersion.cmake)"
defs_equal "$B/arm" "$B/stage-m3/lib/pkgconfig"
for d in MODCP_BP_DEPTH=8u MODCP_WITH_ASCII=0; do
  grep -qx "$d" "$B/arm/modcp_core_defs.txt" || fail "cortex-m3: the build's $d did not reach modcp::core"
done
mkdir -p "$B/make-arm"
PKG_CONFIG_PATH=$B/stage-m3/lib/pkgconfig make -s -f "$ROOT/tests/package/make/Makefile" \
  OUT="$B/make-arm" arm >/dev/null 2>"$B/make-arm.log" || { cat "$B/make-arm.log"; fail "cortex-m3 make"; }
syms=$(arm-none-eabi-nm "$B/make-arm/outside_app.elf")
grep -q " T modcp_cp_init$" <<<"$syms" ||
  fail "cortex-m3 (pkg-config, make): modcp_cp_init not linked"
echo "cortex-m3 (pkg-config, make): outside_app.elf linked with modcp's core"
