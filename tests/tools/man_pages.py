# SPDX-License-Identifier: Apache-2.0
"""The man pages of the built programs, written by tools/man-from-help.py from their --help: every
item of a list in the help is one term of the page. A term and its description are told apart by
two spaces or more, so a name one space short of its description swallows it (`atv31-v1.1
Schneider Altivar 31 ...` as one term), and a list under a paragraph that is no heading ending in
':' is run into that paragraph (`... a JSON object. fault NODE CODE     the fault ...`).

  man_pages.py ATV312D COMASTER DNSCAN COTRACE COMMAND...

ATV312D's models (as its --model error lists them) and control commands, and COMASTER's
COMMANDs, must each be a term of its own; in every page every term has a description and no
paragraph has a list run into it. Standard library only."""
import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.normpath(os.path.join(HERE, "..", "..", "tools", "man-from-help.py"))
ATV312D, COMASTER, DNSCAN, COTRACE, COMMANDS = None, None, None, None, []
# atv312d's control commands as its help writes their synopses (docs/atv312d.md).
CONTROL_COMMANDS = ["fault NODE CODE", "clear NODE CODE|all", "mains NODE undervoltage|normal",
                    "stop-key NODE", "run-key NODE", "local NODE on|off", "load NODE PERCENT",
                    "input NODE LIn|DIn on|off", "analog NODE AIn VALUE", "pot NODE PERCENT",
                    "marker NODE MARKER [VALUE]", "state [NODE]"]


def man_page(name, program):
    """The roff lines of the man page of program, as the build writes it."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, name + ".1")
        subprocess.run([sys.executable, TOOL, "--name", name, "--summary", "test", "--version", "test",
                        "--output", out, "--", program], check=True, capture_output=True, text=True)
        with open(out) as f:
            return f.read().splitlines()


def roff(text):
    return text.replace("-", "\\-")


def terms(page):
    """{term: its description} of every tagged paragraph (.TP, the bold term, the description)."""
    found = {}
    for i, line in enumerate(page[:-2]):
        m = re.fullmatch(r"\\fB(.*)\\fR", page[i + 1])
        if line == ".TP" and m:
            found[m.group(1)] = page[i + 2] if not page[i + 2].startswith(".") else ""
    return found


class ManPagesTest(unittest.TestCase):
    def test_every_model_of_atv312d_is_a_term(self):
        p = subprocess.run([ATV312D, "vcan0", "--node-id", "4", "--model", "none"], capture_output=True,
                           text=True)
        models = re.search(r"the models are (.*)$", p.stderr.splitlines()[0]).group(1).split(", ")
        self.assertIn("atv31-v1.1", models)
        page = terms(man_page("atv312d", ATV312D))
        for model in models:
            self.assertIn(roff(model), page, "model %s is no term of its own" % model)
            self.assertTrue(page[roff(model)].startswith(("Schneider Altivar", "WEG PLC300", "CiA 401")),
                            page[roff(model)])

    def test_every_control_command_of_atv312d_is_a_term(self):
        page = terms(man_page("atv312d", ATV312D))
        for command in CONTROL_COMMANDS:
            self.assertIn(roff(command), page, "control command %s is no term of its own" % command)

    def test_every_term_has_a_description_and_no_list_is_a_paragraph(self):
        for name, program in ("atv312d", ATV312D), ("comaster", COMASTER), ("dnscan", DNSCAN), \
                ("cotrace", COTRACE):
            page = man_page(name, program)
            for term, description in terms(page).items():
                self.assertTrue(description, "%s: term %r has no description" % (name, term))
            for line in page:
                if not line.startswith("."):
                    self.assertNotIn("   ", line, "%s: a list run into a paragraph" % name)

    def test_exit_statuses_are_terms_of_exit_status(self):
        """Each program's --help ends with its exit statuses, one a line: the EXIT STATUS section
        is their list, each number a term with its meaning, 0 and 64 (usage) in every one."""
        for name, program in ("atv312d", ATV312D), ("comaster", COMASTER), ("dnscan", DNSCAN), \
                ("cotrace", COTRACE):
            page = man_page(name, program)
            section = page[page.index('.SH "EXIT STATUS"') + 1:page.index('.SH "SEE ALSO"')
                           if '.SH "SEE ALSO"' in page else len(page)]
            statuses = terms(section)
            self.assertTrue({"0", "64"} <= set(statuses), "%s: %s" % (name, statuses))
            for status, meaning in statuses.items():
                self.assertRegex(status, r"^\d+$", "%s: %r is no exit status" % (name, status))
                self.assertTrue(meaning, "%s: exit status %s has no meaning" % (name, status))

    def test_every_command_of_comaster_is_a_term(self):
        page = terms(man_page("comaster", COMASTER))
        for command in COMMANDS:
            self.assertIn(roff(command), page, "command %s is no term of its own" % command)
            self.assertTrue(page[roff(command)], "command %s has no description" % command)


if __name__ == "__main__":
    ATV312D, COMASTER, DNSCAN, COTRACE = sys.argv[1:5]
    COMMANDS = sys.argv[5:]
    unittest.main(argv=sys.argv[:1])
