#!/usr/bin/env python3
"""The core stays free of I/O (issue 36): no file, port, clock, thread or process control in its
source, and none of the host's I/O crates in its dependency tree.

usage: python3 host/tools/core_io_free.py [core/src]
Prints each forbidden use (file:line: what) and each forbidden crate, and exits 1 when it finds one.
The wasm32 build of the core (.ci/run) checks the rest: what does not build there is no core code.
"""
import os
import re
import subprocess
import sys

# What reads the outside world or the clock, or controls threads and processes: each with its reason.
FORBIDDEN = [
    (re.compile(r"\bstd::fs\b|\buse std::\{[^}]*\bfs\b"), "std::fs (files are the host's)"),
    (re.compile(r"\bInstant\b"), "Instant (the host reads the clock and feeds the time)"),
    (re.compile(r"\bSystemTime\b|\bstd::time::UNIX_EPOCH\b"), "SystemTime (the host reads the clock and feeds the time)"),
    (re.compile(r"\bthread\b(?!-)"), "thread (the core runs in one; a browser has none)"),
    (re.compile(r"\bstd::process\b"), "std::process (process control is the host's)"),
    (re.compile(r"\bstd::net\b"), "std::net (ports and sockets are the host's)"),
    (re.compile(r"\bstd::io::std(in|out|err)\b"), "the terminal (the core returns what to tell the person)"),
]
# The host's I/O crates: none may be in the core's dependency tree.
CRATES = ["serialport", "rusqlite", "ctrlc", "nix", "clap", "indicatif"]


def code_lines(path):
    """The lines of a Rust file with their numbers, comments left out (a doc may name what it avoids)."""
    with open(path) as f:
        for number, line in enumerate(f, 1):
            yield number, line.split("//", 1)[0]


def forbidden_uses(root):
    """(file, line, what) of every forbidden use under `root`."""
    found = []
    for folder, _, files in os.walk(root):
        for name in sorted(f for f in files if f.endswith(".rs")):
            path = os.path.join(folder, name)
            for number, code in code_lines(path):
                found += [(os.path.relpath(path, root), number, why) for pattern, why in FORBIDDEN if pattern.search(code)]
    return found


def forbidden_crates(package, features):
    """The forbidden crates in `package`'s normal and build dependency tree with `features`."""
    command = ["cargo", "tree", "-p", package, "-e", "normal,build", "--prefix", "none", "--format", "{p}"]
    command += ["--features", features] if features else []
    tree = subprocess.run(command, capture_output=True, text=True, check=True).stdout
    names = {line.split()[0] for line in tree.splitlines() if line.strip()}
    return sorted(names & set(CRATES))


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "core/src"
    uses = forbidden_uses(root)
    for path, number, why in uses:
        print(f"{path}:{number}: {why}")
    crates = [(f or "default features", c) for f in ["", "sim"] for c in forbidden_crates("accelcal-core", f)]
    for features, crate in crates:
        print(f"accelcal-core ({features}) depends on {crate}")
    print(f"{len(uses)} forbidden uses in {root}, {len(crates)} forbidden crates in accelcal-core's tree")
    sys.exit(1 if uses or crates else 0)


if __name__ == "__main__":
    main()
