# SPDX-License-Identifier: Apache-2.0
"""Unit tests of tools/man-from-help.py: the roff it writes from a program's --help text (usage,
tagged options with continuation lines, headings, exit status, subcommands, escapes) and its
errors. Standard library only; the programs documented are small Python scripts."""
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.normpath(os.path.join(HERE, "..", "..", "tools", "man-from-help.py"))

HELP = """\
usage: prog.py IFACE --node-id N [options]

Puts things on an interface. A word split after its hyphen: sub-
index.

  IFACE          the interface
  --node-id N    node-id 1..127; a range 4-9 puts several
                 nodes on one socket
  --a-very-long-option FILE
                 described on the next line

.starts with a dot, and a backslash \\ here

Exit status: 0 success,
64 usage error.
"""

SUB_HELP = """\
usage: prog.py gen [-h] --out DIR

Generates.

options:
  -h, --help  show this help message and exit
  --out DIR   output directory
"""


class ManFromHelpTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def program(self, helps, status=0):
        """A program printing helps[sub] for `prog [sub] --help`, exiting with status."""
        path = os.path.join(self.dir, "prog.py")
        with open(path, "w") as f:
            f.write(textwrap.dedent("""\
                import sys
                helps = %r
                sub = sys.argv[1] if len(sys.argv) > 2 else ""
                sys.stdout.write(helps.get(sub, ""))
                sys.exit(%d)
                """) % (helps, status))
        return [sys.executable, path]

    def run_tool(self, command, *options):
        out = os.path.join(self.dir, "prog.1")
        p = subprocess.run([sys.executable, TOOL, "--name", "prog", "--summary", "does things",
                            "--version", "pkg 1.0", "--output", out] + list(options) + ["--"]
                           + command, capture_output=True, text=True)
        page = None
        if p.returncode == 0:
            with open(out) as f:
                page = f.read().splitlines()
        return p.returncode, page, p.stderr

    def test_page(self):
        status, page, _ = self.run_tool(self.program({"": HELP}), "--see-also", "other(1)")
        self.assertEqual(status, 0)
        self.assertEqual(page[:7], [
            '.TH PROG 1 "" "pkg 1.0" "User Commands"',
            ".SH NAME", "prog \\- does things",
            ".SH SYNOPSIS", ".B prog", "IFACE \\-\\-node\\-id N [options]", ".br"])
        description = page[page.index(".SH DESCRIPTION") + 1:page.index('.SH "EXIT STATUS"')]
        self.assertEqual(description, [
            ".PP", "Puts things on an interface. A word split after its hyphen: sub\\-index.",
            ".TP", "\\fBIFACE\\fR", "the interface",
            ".TP", "\\fB\\-\\-node\\-id N\\fR",
            "node\\-id 1..127; a range 4\\-9 puts several nodes on one socket",
            ".TP", "\\fB\\-\\-a\\-very\\-long\\-option FILE\\fR", "described on the next line",
            ".PP", "\\&.starts with a dot, and a backslash \\e here"])
        self.assertEqual(page[page.index('.SH "EXIT STATUS"') + 1:page.index('.SH "SEE ALSO"')],
                         [".PP", "0 success, 64 usage error."])
        self.assertEqual(page[-1], "other(1)")

    def test_exit_status_list(self):
        """`Exit status:` alone on its line over indented statuses: each status a tagged
        paragraph of EXIT STATUS, not a subsection of DESCRIPTION."""
        listed = HELP.replace("Exit status: 0 success,\n64 usage error.\n",
                              "Exit status:\n  0   success\n  64  usage error: an unknown\n"
                              "      option\n")
        status, page, _ = self.run_tool(self.program({"": listed}))
        self.assertEqual(status, 0)
        self.assertNotIn(".SS Exit status", page)
        self.assertEqual(page[page.index('.SH "EXIT STATUS"') + 1:], [
            ".TP", "\\fB0\\fR", "success",
            ".TP", "\\fB64\\fR", "usage error: an unknown option"])

    def test_subcommand(self):
        status, page, _ = self.run_tool(self.program({"": HELP, "gen": SUB_HELP}),
                                        "--subcommand", "gen")
        self.assertEqual(status, 0)
        synopsis = page[page.index(".SH SYNOPSIS") + 1:page.index(".SH DESCRIPTION")]
        self.assertEqual(synopsis, [".B prog", "IFACE \\-\\-node\\-id N [options]", ".br",
                                    ".B prog", "gen [\\-h] \\-\\-out DIR", ".br"])
        section = page[page.index('.SH "PROG GEN"') + 1:page.index('.SH "EXIT STATUS"')]
        self.assertEqual(section, [
            ".PP", "Generates.", ".SS Options",
            ".TP", "\\fB\\-h, \\-\\-help\\fR", "show this help message and exit",
            ".TP", "\\fB\\-\\-out DIR\\fR", "output directory"])

    def test_program_failing(self):
        status, _, err = self.run_tool(self.program({"": HELP}, status=3))
        self.assertEqual(status, 1)
        self.assertIn("failed (exit status 3)", err)

    def test_no_usage_line(self):
        status, _, err = self.run_tool(self.program({"": "Just text.\n"}))
        self.assertEqual(status, 1)
        self.assertIn("no 'usage:' line in the help of prog", err)

    def test_missing_program(self):
        status, _, err = self.run_tool([os.path.join(self.dir, "missing")])
        self.assertEqual(status, 1)
        self.assertIn("cannot run", err)


if __name__ == "__main__":
    unittest.main()
