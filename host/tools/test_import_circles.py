#!/usr/bin/env python3
"""Tests of import_circles.py on tiny source trees: a circle through `super::` is found, paths are
resolved to the file that defines the item, and what is no use (a re-export, a comment, a test)
makes no circle.

usage: python3 -m unittest host/tools/test_import_circles.py   (.ci/run runs it)
"""
import os
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import import_circles  # noqa: E402

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "import_circles.py")


def tree(files):
    """A temporary source root holding `files` (path -> text)."""
    root = tempfile.mkdtemp(prefix="import-circles-")
    for path, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
        with open(os.path.join(root, path), "w") as f:
            f.write(text)
    return root


def file_circles(root):
    edges = dict(import_circles.graphs(root))["between files"]
    return import_circles.circles({n for e in edges for n in e}, edges)


# A folder whose two files use each other only through `super::` (the shape of the pairs split at a
# line limit), below a mod.rs that uses neither.
PAIR = {
    "lib.rs": "mod a;\n",
    "a/mod.rs": "mod x;\nmod y;\npub use y::Y;\n",
    "a/x.rs": "use super::y::Y;\npub struct X;\npub fn make() -> Y { Y }\n",
    "a/y.rs": "pub struct Y;\npub fn take(_: super::x::X) {}\n",
}


class Circles(unittest.TestCase):
    def test_a_circle_through_super_between_two_files_is_found_and_fails_the_run(self):
        root = tree(PAIR)
        self.assertEqual(file_circles(root), [["a/x.rs", "a/y.rs"]])
        run = subprocess.run([sys.executable, TOOL, root], capture_output=True, text=True)
        self.assertEqual(run.returncode, 1, run.stdout)
        self.assertIn("a/x.rs -> a/y.rs: super::y::Y", run.stdout)
        self.assertIn("a/y.rs -> a/x.rs: super::x::X", run.stdout)

    def test_super_super_and_self_paths_resolve_to_the_file_that_defines_the_item(self):
        root = tree({
            "lib.rs": "mod a;\n",
            "a/mod.rs": "mod b;\nmod z;\n",
            "a/z.rs": "pub struct Z;\n",
            "a/b/mod.rs": "mod c;\npub fn f() { self::c::g() }\n",
            "a/b/c.rs": "pub fn g() { let _ = super::super::z::Z; }\n",
        })
        edges = dict(import_circles.graphs(root))["between files"]
        self.assertIn(("a/b/c.rs", "a/z.rs"), edges)
        self.assertIn(("a/b/mod.rs", "a/b/c.rs"), edges)
        self.assertEqual(file_circles(root), [])

    def test_a_reexport_is_followed_to_its_file_and_makes_no_use_of_its_own(self):
        # x reaches Y through mod.rs's `pub use y::Y`: the use is of y.rs, and mod.rs uses nothing.
        root = tree(dict(PAIR, **{"a/x.rs": "use super::Y;\npub struct X;\n", "a/y.rs": "pub struct Y;\n"}))
        edges = dict(import_circles.graphs(root))["between files"]
        self.assertEqual(set(edges), {("a/x.rs", "a/y.rs")})

    def test_a_path_in_a_comment_a_string_or_test_code_is_no_use(self):
        y = ('pub struct Y;\n// super::x::X\nconst S: &str = "super::x::X";\n'
             "#[cfg(test)]\nmod tests {\n    use super::super::x::X;\n}\n")
        root = tree(dict(PAIR, **{"a/y.rs": y}))
        self.assertEqual(file_circles(root), [])
        run = subprocess.run([sys.executable, TOOL, root], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout)


if __name__ == "__main__":
    unittest.main()
