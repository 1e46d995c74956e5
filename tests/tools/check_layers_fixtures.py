#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""scripts/check-layers on small trees of its own, compiled here with cc: it names two C files
calling each other, two headers including each other and two files of one name, each with exit
status 1; passes a tree in floors (whatever tests/ does); and refuses a tree not built (2)."""

import json
import os
import shlex
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "check-layers")


def make_tree(root, files, built=True):
    """Writes `files` ({path: text}) under root and compiles each .c into root/build, with a
    compile_commands.json as CMake writes it."""
    entries = []
    for path, text in files.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w", encoding="utf-8") as f:
            f.write(text)
    build = os.path.join(root, "build")
    os.makedirs(build, exist_ok=True)
    for path in files:
        if not path.endswith(".c"):
            continue
        obj = os.path.join("objects", path + ".o")
        os.makedirs(os.path.join(build, os.path.dirname(obj)), exist_ok=True)
        source = os.path.join(root, path)
        command = ["cc", "-I" + os.path.join(root, "src"), "-o", obj, "-c", source]
        entries.append({"directory": build, "command": shlex.join(command), "file": command[-1]})
        if built:
            subprocess.run(command, cwd=build, check=True)
    with open(os.path.join(build, "compile_commands.json"), "w", encoding="utf-8") as f:
        json.dump(entries, f)
    return build


def check_layers(root, build):
    run = subprocess.run(
        [sys.executable, SCRIPT, "--source", root, build], capture_output=True, text=True
    )
    return run.returncode, run.stdout, run.stderr


class CheckLayers(unittest.TestCase):
    def run_on(self, files, built=True):
        with tempfile.TemporaryDirectory() as root:
            return check_layers(root, make_tree(root, files, built))

    def test_two_files_calling_each_other_are_a_circle(self):
        status, out, _ = self.run_on(
            {
                "src/a/one.c": "int two(void);\n"
                "static int helper(void) { return 1; }\n"
                "int one(void) { return two() + helper(); }\n",
                "src/a/two.c": "int one(void);\n"
                "static int helper(void) { return 2; }\n"
                "int two(void) { return one() + helper(); }\n",
            }
        )
        self.assertEqual(status, 1)
        self.assertIn("circle 1 of calls: 2 files: src/a/one.c, src/a/two.c\n", out)
        self.assertIn("  src/a/one.c -> src/a/two.c: two\n", out)
        self.assertIn("  src/a/two.c -> src/a/one.c: one\n", out)
        self.assertNotIn("helper", out)  # static: no name of the object file

    def test_two_headers_including_each_other_are_a_circle(self):
        status, out, _ = self.run_on(
            {
                "src/p/a.h": '#ifndef A_H\n#define A_H\n#include "p/b.h"\n#endif\n',
                "src/p/b.h": '#ifndef B_H\n#define B_H\n#include "p/a.h"\n#endif\n',
                "src/p/user.c": '#include "p/a.h"\nint user(void) { return 0; }\n',
            }
        )
        self.assertEqual(status, 1)
        self.assertIn("circle 1 of includes: 2 files: src/p/a.h, src/p/b.h\n", out)
        self.assertIn("  src/p/a.h -> src/p/b.h: #include b.h\n", out)
        self.assertIn("  src/p/b.h -> src/p/a.h: #include a.h\n", out)

    def test_two_files_of_one_name_are_named(self):
        status, out, _ = self.run_on(
            {
                "src/x/name.c": "int x_name(void) { return 1; }\n",
                "apps/y/name.c": "int y_name(void) { return 2; }\n",
                "apps/y/main.c": "int main(void) { return 0; }\n",
                "apps/z/main.c": "int main(void) { return 0; }\n",
            }
        )
        self.assertEqual(status, 1)
        self.assertEqual(out, "shared name name.c: apps/y/name.c, src/x/name.c\n")

    def test_a_tree_in_floors_passes(self):
        status, out, err = self.run_on(
            {
                "src/low/bottom.h": "#ifndef BOTTOM_H\n#define BOTTOM_H\n"
                "int bottom(void);\n#endif\n",
                "src/low/bottom.c": '#include "low/bottom.h"\nint bottom(void) { return 1; }\n',
                "apps/top/main.c": '#include "low/bottom.h"\nint main(void) { return bottom(); }\n',
                # A test may call what calls it: tests/ is no floor of the house.
                "tests/low/test_bottom.c": '#include "low/bottom.h"\n'
                "int top(void);\nint check(void) { return bottom() + top(); }\n",
                "src/low/uses_test.c": "int check(void);\nint top(void) { return check(); }\n",
            }
        )
        summary = "check-layers: 3 C files of src/ and apps/: 0 circles, 0 shared names\n"
        self.assertEqual((status, out, err), (0, summary, ""))

    def test_a_tree_not_built_is_refused(self):
        status, out, err = self.run_on({"src/a/one.c": "int one(void) { return 1; }\n"}, False)
        self.assertEqual((status, out), (2, ""))
        self.assertIn("no object file for src/a/one.c (build the tree first)", err)


if __name__ == "__main__":
    unittest.main()
