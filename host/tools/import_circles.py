#!/usr/bin/env python3
"""Import circles of a crate's source tree: which files use each other, through any path.

usage: python3 host/tools/import_circles.py SRC_ROOT      (host/src; later core/src)

A file uses another when one of its paths names an item there: `crate::a::b`, `super::x` (and
`super::super::x`), `self::x`, or a path that starts at a module the file declares (`mod x;` then
`x::f`), in `use` lines (groups `{..}` expanded) and inline in code. A path is resolved to the file that
defines the item: the longest prefix that is a file (`a/b.rs` or `a/b/mod.rs`), then through that
file's imports and re-exports (`pub use x::Item`, `pub use x::*`) to where the item is written. A
re-export is a door, not a use: it makes no edge from the file that holds it. Comments, string
literals and test code (files named tests.rs, `#[cfg(test)] mod .. { }`) are left out: tests may
reach anywhere.

Prints every circle between files (a set of files each of which reaches every other one, with the
uses that close it) and between top-level modules (folders and files under SRC_ROOT).
Exits with 1 when it finds a circle (CI runs it: .ci/run), 0 when there is none.
"""
import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
PATH_START = r"(?<![A-Za-z0-9_:$])"


def blank(text, start, end):
    """`text` with [start, end) turned to spaces, newlines kept (so offsets stay valid)."""
    return text[:start] + re.sub(r"[^\n]", " ", text[start:end]) + text[end:]


def strip_comments_and_strings(text):
    """Comments and the insides of string and char literals blanked, everything else where it was."""
    out, i, n = [], 0, len(text)
    pattern = re.compile(r'//[^\n]*|/\*|r(#*)"|b?"|b?\'(?:\\.|[^\\\'\n])\'')
    while i < n:
        m = pattern.search(text, i)
        if not m:
            out.append(text[i:])
            break
        out.append(text[i:m.start()])
        token = m.group(0)
        if token.startswith("//"):
            end = m.end()
        elif token == "/*":
            depth, j = 1, m.end()
            while depth and j < n:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            end = j
        elif token.startswith("r"):
            close = '"' + m.group(1)
            j = text.find(close, m.end())
            end = n if j < 0 else j + len(close)
        elif token.endswith('"'):
            j = m.end()
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            end = min(j + 1, n)
        else:
            end = m.end()
        out.append(re.sub(r"[^\n]", " ", text[m.start():end]))
        i = end
    return "".join(out)


def block_end(text, open_brace):
    """The offset just past the brace that closes the one at `open_brace`."""
    depth = 0
    for j in range(open_brace, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j + 1
    return len(text)


def without_tests(text):
    """`text` with every `#[cfg(test)]` module blanked."""
    pattern = re.compile(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+" + IDENT + r"\s*(\{|;)")
    m = pattern.search(text)
    while m:
        end = block_end(text, m.start(1)) if m.group(1) == "{" else m.end()
        text = blank(text, m.start(), end)
        m = pattern.search(text)
    return text


def expand_use_tree(tree):
    """`a::{b, c::{d as e}, self}` -> [(['a','b'], 'b'), (['a','c','d'], 'e'), (['a'], 'a')]."""
    tree = re.sub(r"\s+", " ", tree).strip()
    if tree.startswith("::"):
        tree = tree[2:]
    depth, brace = 0, -1
    for k, ch in enumerate(tree):
        if ch == "{":
            if depth == 0:
                brace = k
                break
    if brace < 0:
        parts = tree.split(" as ")
        segments = [s.strip() for s in parts[0].split("::") if s.strip()]
        alias = parts[1].strip() if len(parts) > 1 else (segments[-1] if segments else "")
        return [(segments, alias)] if segments else []
    prefix = [s.strip() for s in tree[:brace].split("::") if s.strip()]
    inner = tree[brace + 1 : tree.rfind("}")]
    items, depth, current = [], 0, ""
    for ch in inner:
        if ch == "," and depth == 0:
            items.append(current)
            current = ""
            continue
        depth += ch == "{"
        depth -= ch == "}"
        current += ch
    items.append(current)
    expanded = []
    for item in (i.strip() for i in items):
        if item == "self":
            expanded.append((prefix, prefix[-1]))
        elif item:
            expanded += [(prefix + segments, alias) for segments, alias in expand_use_tree(item)]
    return expanded


class Crate:
    """The source files under one root and what each of them imports."""

    def __init__(self, root):
        self.root = root
        self.files = {}
        for d, _, names in os.walk(root):
            for n in sorted(names):
                if n.endswith(".rs") and n != "tests.rs":
                    path = os.path.relpath(os.path.join(d, n), root)
                    with open(os.path.join(d, n)) as f:
                        self.files[path] = without_tests(strip_comments_and_strings(f.read()))
        self.uses = {}
        for path in self.files:
            self.uses[path] = self.read_uses(path)

    def module_of(self, path):
        """The module path of a file: a/b.rs and a/b/mod.rs are ['a', 'b']; lib.rs and main.rs are []."""
        parts = path[:-3].split(os.sep)
        if parts[-1] in ("mod", "lib", "main"):
            parts = parts[:-1]
        return parts

    def file_of(self, module):
        """The file of module path `module`, or None."""
        if not module:
            return "lib.rs" if "lib.rs" in self.files else ("main.rs" if "main.rs" in self.files else None)
        base = os.path.join(*module)
        for f in (base + ".rs", os.path.join(base, "mod.rs")):
            if f in self.files:
                return f
        return None

    def children(self, path):
        """The modules a file declares: `mod x;` and `mod x { .. }`."""
        return set(re.findall(r"\bmod\s+(" + IDENT + r")\s*[;{]", self.files[path]))

    def absolute(self, path, segments):
        """`segments` as written in file `path`, made absolute from the crate root, or None (another crate)."""
        here, first = self.module_of(path), segments[0]
        if first == "crate":
            return segments[1:]
        if first == "self":
            return here + segments[1:]
        if first == "super":
            up = 0
            while up < len(segments) and segments[up] == "super":
                up += 1
            return here[: len(here) - up] + segments[up:]
        if first in self.children(path):
            return here + segments
        imported = self.uses.get(path, {}).get("names", {}).get(first)
        if imported and imported[0] != segments[:1]:
            return self.absolute(path, imported[0] + segments[1:])
        return None

    def read_uses(self, path):
        """A file's `use` lines: names it brings in (alias -> absolute path), its globs, and which were `pub`."""
        text = self.files[path]
        names, globs = {}, []
        for m in re.finditer(r"(\bpub(?:\s*\([^)]*\))?\s+)?\buse\s+([^;]*);", text):
            for segments, alias in expand_use_tree(m.group(2)):
                entry = (segments, bool(m.group(1)))
                if alias == "*":
                    globs.append(entry)
                else:
                    names[alias] = entry
        return {"names": names, "globs": globs}

    def resolve(self, path, segments, seen=None):
        """The file that defines the item `segments` (as written in file `path`) names, or None."""
        absolute = self.absolute(path, segments)
        if absolute is None:
            return None
        return self.resolve_absolute(absolute, seen or set())

    def resolve_absolute(self, segments, seen):
        """The file that defines the item at absolute path `segments`, following imports."""
        n = len(segments)
        while n >= 0 and self.file_of(segments[:n]) is None:
            n -= 1
        if n < 0:
            return None
        file = self.file_of(segments[:n])
        rest = segments[n:]
        if not rest or (file, rest[0]) in seen:
            return file
        seen = seen | {(file, rest[0])}
        imported = self.uses[file]["names"].get(rest[0])
        if imported:
            return self.resolve(file, imported[0] + rest[1:], seen) or file
        if self.defines(file, rest[0]):
            return file
        for glob, _ in self.uses[file]["globs"]:
            target = self.absolute(file, glob)
            if target is not None:
                found = self.resolve_absolute(target + rest, seen)
                if found is not None and found != self.file_of(target):
                    return found
                if found is not None and self.defines(found, rest[0]):
                    return found
        return file

    def defines(self, file, name):
        """Whether `file` writes an item called `name` itself."""
        kinds = r"\b(?:fn|struct|enum|union|const|static|type|trait|mod)\s+"
        return re.search(kinds + re.escape(name) + r"\b", self.files[file]) is not None

    def edges(self):
        """(user, used) -> the paths that make the edge, for every pair of different files."""
        found = {}
        for path, text in self.files.items():
            for segments, public in self.uses[path]["names"].values():
                if not public:
                    self.add(found, path, segments)
            for segments, public in self.uses[path]["globs"]:
                if not public:
                    self.add(found, path, segments)
            code = re.sub(r"\buse\s+[^;]*;", lambda m: " " * len(m.group(0)), text)
            starts = ["crate", "super", "self"] + sorted(self.children(path))
            pattern = PATH_START + r"((?:" + "|".join(starts) + r")(?:::" + IDENT + r")+)"
            for m in re.finditer(pattern, code):
                self.add(found, path, m.group(1).split("::"))
        return found

    def add(self, found, path, segments):
        target = self.resolve(path, segments)
        if target is not None and target != path:
            found.setdefault((path, target), set()).add("::".join(segments))


def circles(nodes, edges):
    """The strongly connected sets of more than one node (Tarjan), each sorted, in sorted order."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    successors = {n: sorted(b for a, b in edges if a == n) for n in nodes}

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in successors[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return sorted(found)


def top(path):
    first = path.split(os.sep)[0]
    return first[:-3] if first.endswith(".rs") else first


def graphs(root):
    """The uses under `root`: (title, edges) between top-level modules, then between files."""
    by_file = Crate(root).edges()
    by_top = {(top(a), top(b)): paths for (a, b), paths in by_file.items() if top(a) != top(b)}
    return (("between top-level modules", by_top), ("between files", by_file))


def report(root):
    """Prints the circles under `root`; returns how many there are."""
    total = 0
    for title, edges in graphs(root):
        nodes = {n for edge in edges for n in edge}
        found = circles(nodes, edges)
        total += len(found)
        print(f"{len(found)} circles {title}:")
        for component in found:
            print(f"  {len(component)}: " + ", ".join(component))
            for (a, b), paths in sorted(edges.items()):
                if a in component and b in component:
                    print(f"      {a} -> {b}: " + ", ".join(sorted(paths)[:4]))
    return total


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(1 if report(sys.argv[1]) else 0)
