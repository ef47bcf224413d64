#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""diff.mutant: tools/diffcore notices a wrong line of code, and only then.

    tests/diff/mutant.py ROOT SCRATCH [--work-bin EXE] [--inputs N]

Copies the core's tree (CMakeLists.txt, cmake/, firmware/, hal/ of ROOT, uncommitted
changes included; only changed files are rewritten, so the copy's build stays
incremental) to SCRATCH/mutant-tree and runs tools/diffcore against it:
  - for each mutation below that applies to the copy (its pattern found exactly once in
    firmware/src): with it, diffcore must report differences (exit 1, D > 0);
  - without any: 0 differences (exit 0) — the harness is deterministic and the
    differences came from the mutation.
At least one mutation must apply (firmware/src is reshaped from time to time: when none
does, this test fails and asks for a new pattern).
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys

# (what, file glob under firmware/src, pattern, replacement)
MUTATIONS = (
    ("exceptions counted as NAKs (only the serial-line counters and FC08 replies change)",
     "*.c", r"(modcp_diag_count_error\([^,()]+, )MODCP_CNT_EXCEPTION\)", r"\1MODCP_CNT_NAK)"),
    ("the RS485 turnaround 1 us shorter (only timer arms change)",
     "link.c", r"link_arm\(l, l->turnaround_us\)", r"link_arm(l, l->turnaround_us - 1u)"),
    ("the write limit's last byte not writable (one operator: <= -> <)",
     "map*", r"(\w+) <= (\w+)->max\b", r"\1 < \2->max"),
)
TREE = ("CMakeLists.txt", "cmake", "firmware", "hal")


def sync(root, dest):
    """dest := root's tree (the files git lists under TREE), touching only what differs."""
    listed = subprocess.run(["git", "-C", root, "ls-files", "-co", "--exclude-standard", "--"] +
                            list(TREE), capture_output=True, text=True, check=True).stdout.split("\n")
    want = {rel for rel in listed if rel and os.path.isfile(os.path.join(root, rel))}
    for rel in want:
        src, dst = os.path.join(root, rel), os.path.join(dest, rel)
        with open(src, "rb") as f:
            data = f.read()
        if os.path.exists(dst):
            with open(dst, "rb") as f:
                if f.read() == data:
                    continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(src, dst)
    for top in TREE:
        for path in glob.glob(os.path.join(dest, top, "**"), recursive=True):
            rel = os.path.relpath(path, dest)
            if os.path.isfile(path) and rel not in want:
                os.remove(path)


def diffcore(root, tree, args):
    cmd = [os.path.join(root, "tools", "diffcore"), tree, "--inputs", str(args.inputs),
           "--scratch", args.scratch, "--show", "1"]
    if args.work_bin:
        cmd += ["--work-bin", args.work_bin]
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(p.stdout + p.stderr, end="")
    return p.returncode


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("root")
    ap.add_argument("scratch")
    ap.add_argument("--work-bin")
    ap.add_argument("--inputs", type=int, default=1000)
    args = ap.parse_args()
    tree = os.path.join(args.scratch, "mutant-tree")
    os.makedirs(tree, exist_ok=True)
    sync(args.root, tree)
    applied, failures = 0, []
    for what, pattern, rx, repl in MUTATIONS:
        hits = []
        for path in sorted(glob.glob(os.path.join(tree, "firmware", "src", pattern))):
            with open(path, encoding="utf-8") as f:
                text = f.read()
            hits += [(path, text, m) for m in re.finditer(rx, text)]
        if len(hits) != 1:
            print(f"mutant: '{what}' does not apply ({len(hits)} sites)")
            continue
        path, text, m = hits[0]
        line = text.count("\n", 0, m.start()) + 1
        print(f"mutant: {os.path.relpath(path, tree)}:{line}: {what}")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text[:m.start()] + m.expand(repl) + text[m.end():])
        try:
            rc = diffcore(args.root, tree, args)
        finally:
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        applied += 1
        if rc != 1:
            failures.append(f"'{what}' gave exit {rc}, not 1 (differences)")
    print("mutant: the unchanged copy")
    rc = diffcore(args.root, tree, args)
    if rc != 0:
        failures.append(f"the unchanged copy gave exit {rc}, not 0")
    if applied == 0:
        failures.append("no mutation applies to firmware/src any more: give MUTATIONS a new pattern")
    for f in failures:
        print("mutant: FAILED: " + f)
    print(f"mutant: {applied} mutations applied, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
