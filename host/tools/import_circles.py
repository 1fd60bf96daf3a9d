#!/usr/bin/env python3
"""Import circles of the host crate, from its own `use crate::` lines (and `crate::x::` paths).

usage: python3 host/tools/import_circles.py [host/src]
Prints the circles between top-level modules (folders and files under src/), then between files.
A file's module is its path; `crate::a::b::c` names file a/b.rs or a/b/mod.rs (or a.rs) whichever exists.
Tests (files named tests.rs, and `mod tests` blocks) are left out: they may reach anywhere.
Exits with 1 when it finds a circle (CI runs it: .ci/run), 0 when there is none.
"""
import os, re, sys
import networkx as nx

root = sys.argv[1] if len(sys.argv) > 1 else "host/src"

def module_file(parts):
    """The file that the longest prefix of `parts` names."""
    for n in range(len(parts), 0, -1):
        base = os.path.join(root, *parts[:n])
        for f in (base + ".rs", os.path.join(base, "mod.rs")):
            if os.path.exists(f):
                return os.path.relpath(f, root)
    return None

def paths_in(text):
    """Every crate path a file uses: `use crate::{a::b, c}` expanded, and inline `crate::a::b`."""
    text = re.sub(r"#\[cfg\(test\)\]\s*mod tests \{.*", "", text, flags=re.S)
    found = []
    for m in re.finditer(r"use crate::\{([^;]*)\};", text, flags=re.S):
        for item in re.split(r",\s*(?![^{]*\})", m.group(1)):
            found.append(item.strip())
    for m in re.finditer(r"crate::([A-Za-z_][A-Za-z0-9_:]*)", text):
        found.append(m.group(1))
    return [re.split(r"::\{|\s", f)[0].split("::") for f in found if f]

files = {}
for d, _, names in os.walk(root):
    for n in names:
        if n.endswith(".rs") and n != "tests.rs":
            p = os.path.relpath(os.path.join(d, n), root)
            files[p] = open(os.path.join(d, n)).read()

def top(path):
    first = path.split(os.sep)[0]
    return first[:-3] if first.endswith(".rs") else first

by_file, by_top = nx.DiGraph(), nx.DiGraph()
for p, text in files.items():
    for parts in paths_in(text):
        target = module_file([x for x in parts if x not in ("self",)])
        if target and target != p:
            by_file.add_edge(p, target)
            if top(p) != top(target):
                by_top.add_edge(top(p), top(target))

found = 0
for title, graph in (("across folders (top-level modules)", by_top), ("between files", by_file)):
    cycles = sorted(sorted(c) for c in nx.simple_cycles(graph))
    found += len(cycles)
    print(f"{len(cycles)} circles {title}:")
    for c in cycles:
        print("  " + " <-> ".join(c))
sys.exit(1 if found else 0)
