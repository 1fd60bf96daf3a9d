#!/usr/bin/env python3
"""Tests of core_io_free.py on tiny source trees: each forbidden use is found where it is code, and
not where a comment names it.

usage: python3 -m unittest host/tools/test_core_io_free.py   (.ci/run runs it)
"""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import core_io_free  # noqa: E402


def uses_in(text):
    root = tempfile.mkdtemp(prefix="core-io-free-")
    with open(os.path.join(root, "lib.rs"), "w") as f:
        f.write(text)
    return [(line, why.split(" ")[0]) for _, line, why in core_io_free.forbidden_uses(root)]


class ForbiddenUses(unittest.TestCase):
    def test_each_kind_of_io_is_found_on_its_line(self):
        text = "\n".join([
            "use std::fs::File;",
            "use std::{fs, io};",
            "let t = std::time::Instant::now();",
            "let s = SystemTime::now();",
            "std::thread::spawn(|| ());",
            "std::process::exit(1);",
            "let l = std::net::TcpListener::bind(a);",
            "let i = std::io::stdin();",
        ])
        found = uses_in(text)
        self.assertEqual([line for line, _ in found], [1, 2, 3, 4, 5, 6, 7, 8], found)

    def test_comments_and_look_alikes_are_not_uses(self):
        text = "\n".join([
            "// the host reads std::fs and the Instant for us",
            "let epoch = time::OffsetDateTime::UNIX_EPOCH;",
            "let threads_in_a_screw = 3; // thread-count",
            "let instant_on = true;",
        ])
        self.assertEqual(uses_in(text), [])


if __name__ == "__main__":
    unittest.main()
