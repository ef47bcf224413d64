#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What a new user does, checked in CI: a fresh `git clone` of this tree into an empty
# temporary folder (nothing beside it, no build folder), then the first
# steps of `tools/test --quick` there: install-deps --host-tests (a no-op when everything
# is installed), check-deps, the host preset's configure and the simulator's and
# modcp-conf's build. Then the same check-deps from a source tarball (`git archive`,
# no .git). Only committed files are cloned: commit before running it by hand.
#   tests/package/clean_clone.sh ROOT
# Exit 77 (skipped) when ROOT is not a git work tree (an unpacked tarball).
set -euo pipefail
ROOT=$1
if ! git -C "$ROOT" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "clean_clone: $ROOT is not a git work tree: nothing to clone (skipped)"
  exit 77
fi
T=$(mktemp -d /tmp/modcp-clean-clone.XXXXXX)
trap 'rm -rf "$T"' EXIT
mkdir "$T/clone" "$T/tarball"
git clone -q "$ROOT" "$T/clone/modcp"
cd "$T/clone/modcp"
echo "== clone: $(git log -1 --format='%h %s' | cut -c1-72)"
echo "== clone: tools/install-deps --host-tests"
tools/install-deps --host-tests
echo "== clone: tools/check-deps"
tools/check-deps
echo "== clone: cmake --preset host, build modcp-sim and modcp-conf"
cmake --preset host >/dev/null
cmake --build --preset host -j "$(nproc 2>/dev/null || echo 2)" --target modcp-sim modcp-conf >/dev/null
ls build/host/tools/sim/modcp-sim build/host/tools/conf/modcp-conf >/dev/null
echo "== tarball (git archive HEAD, no .git): tools/check-deps"
git -C "$ROOT" archive HEAD | tar -x -C "$T/tarball"
[ ! -e "$T/tarball/.git" ]
"$T/tarball/tools/check-deps"
echo "clean_clone: a fresh clone and a source tarball pass the first steps of tools/test --quick"
