# SPDX-License-Identifier: Apache-2.0
"""dnscan's command line without a bus: every argument error is `dnscan: error: WHAT` on stderr
with its exit status (64 wrong arguments, followed by `Try 'dnscan --help'.`; 65 data), --json
adds {"error", "exit"} on stdout, and a missing interface or CAN support is 69 (docs/dnscan.md,
docs/architecture.md "Messages and exit statuses")."""

import json
import os
import subprocess
import sys
import tempfile
import unittest

DNSCAN = os.environ["DNSCAN"]
MAN_FROM_HELP = os.path.join(os.environ["PROJECT_SOURCE_DIR"], "tools", "man-from-help.py")


def run(*args):
    return subprocess.run([DNSCAN, *args], capture_output=True, text=True, check=False)


class ArgumentErrors(unittest.TestCase):
    def check(self, args, status, message):
        result = run(*args)
        self.assertEqual(result.returncode, status, result.stderr)
        hint = "Try 'dnscan --help'.\n" if status == 64 else ""
        self.assertEqual(result.stderr, "dnscan: error: " + message + "\n" + hint)
        self.assertEqual(result.stdout, "")

    def test_no_command(self):
        self.check([], 64, "no command: give one of scan, get, set, allocate, release, poll, "
                   "monitor")

    def test_unknown_command(self):
        self.check(["frob"], 64, "unknown command 'frob': give one of scan, get, set, allocate, "
                   "release, poll, monitor")

    def test_unknown_option(self):
        self.check(["--frob", "scan"], 64, "unknown option '--frob'")

    def test_option_without_value(self):
        self.check(["scan", "--timeout"], 64, "option --timeout needs a value: give --timeout MS")
        self.check(["poll", "63", "--assembly", ""], 64,
                   "option --assembly needs a value: give --assembly OUT/IN")

    def test_bad_timeout(self):
        self.check(["--timeout", "0", "scan"], 64,
                   "--timeout: '0' is not a time: give milliseconds 1..600000")

    def test_bad_own_mac_id(self):
        self.check(["--mac-id", "64", "scan"], 64, "--mac-id: '64' is not a MAC ID: give 0..63")

    def test_missing_arguments(self):
        self.check(["get", "63", "1", "1"], 64,
                   "get: missing arguments: usage: dnscan get MAC CLASS INST ATTR [--type T]")

    def test_too_many_arguments(self):
        self.check(["release", "63", "3", "4"], 64,
                   "release: too many arguments from '4': usage: dnscan release MAC [CHOICE]")

    def test_bad_mac_id(self):
        self.check(["get", "64", "1", "1", "1"], 64, "'64' is not a MAC ID: give a number 0..63")

    def test_own_mac_id(self):
        self.check(["--mac-id", "5", "get", "5", "1", "1", "1"], 64,
                   "MAC ID 5 is the scanner's own: give the scanner another with --mac-id N")

    def test_bad_class(self):
        self.check(["get", "63", "0", "1", "1"], 64, "'0' is not a class: give 1..255")

    def test_bad_attribute(self):
        self.check(["get", "63", "1", "1", "256"], 64, "'256' is not an attribute: give 1..255")

    def test_bad_type(self):
        self.check(["get", "63", "1", "1", "7", "--type", "f32"], 64,
                   "--type: 'f32' is not a type: give u8, u16, u32, i8, i16, i32 or string")

    def test_bad_value(self):
        message = ("'%s' is not a value: give hexadecimal bytes (B0 04) or TYPE:NUMBER in the "
                   "type's range (u16:1200)")
        self.check(["set", "63", "0x70", "1", "4", "zz"], 65, message % "zz")
        self.check(["set", "63", "0x70", "1", "4", "u8:256"], 65, message % "u8:256")

    def test_poll_set_needs_assembly(self):
        self.check(["poll", "63", "--set", "Run_fwd=1"], 64,
                   "--set needs the output assembly: give --assembly OUT/IN (21/71)")

    def test_poll_bad_assembly(self):
        self.check(["poll", "63", "--assembly", "71/21"], 64,
                   "--assembly: '71/21' is not OUT/IN: give 20/70, 21/71 or 100/101 (or a mix)")

    def test_poll_unknown_field(self):
        self.check(["poll", "63", "--assembly", "21/71", "--set", "Speed=5"], 64,
                   "--set: 'Speed=5' is not NAME=VALUE with a field of assembly 21 (see "
                   "docs/dnscan.md)")

    def test_poll_field_out_of_range(self):
        self.check(["poll", "63", "--assembly", "21/71", "--set", "Run_fwd=2"], 65,
                   "--set: '2' does not fit Run fwd")

    def test_poll_bad_output(self):
        self.check(["poll", "63", "--output", "6x"], 65,
                   "--output: '6x' is not data: give hexadecimal bytes (61 00 B0 04)")


class Json(unittest.TestCase):
    def test_error_object(self):
        result = run("--json", "get", "64", "1", "1", "1")
        self.assertEqual(result.returncode, 64)
        self.assertEqual(json.loads(result.stdout),
                         {"error": "'64' is not a MAC ID: give a number 0..63", "exit": 64})
        self.assertEqual(result.stderr, "dnscan: error: '64' is not a MAC ID: give a number 0..63\n"
                                        "Try 'dnscan --help'.\n")


class Interface(unittest.TestCase):
    def test_missing_interface_is_69(self):
        """No such interface, or (this kernel) no SocketCAN at all: both are 69, in one line."""
        result = run("-i", "nosuch0", "--no-check", "get", "63", "1", "1", "1")
        self.assertEqual(result.returncode, 69, result.stderr)
        self.assertRegex(result.stderr, r"^dnscan: error: (no network interface 'nosuch0'|this "
                                        r"kernel has no SocketCAN support)[^\n]*\n$")


class Help(unittest.TestCase):
    def test_help_names_every_command_and_exit_code(self):
        result = run("--help")
        self.assertEqual(result.returncode, 0)
        for word in ("scan", "get MAC", "set MAC", "allocate MAC", "release MAC", "poll MAC",
                     "monitor", "else can0\n"
                     "                         (a real bus: the examples give -i vcan0"):
            self.assertIn(word, result.stdout)
        statuses = result.stdout.split("\nExit status:\n")[1]
        self.assertEqual([line.split()[0] for line in statuses.splitlines()
                          if not line.startswith("      ")],
                         ["0", "1", "2", "3", "5", "64", "65", "69", "70", "71"])

    def test_version(self):
        result = run("--version")
        self.assertEqual(result.returncode, 0)
        self.assertRegex(result.stdout, r"^dnscan \d+\.\d+\.\d+\n$")


class ManPage(unittest.TestCase):
    """The man page is written from --help by tools/man-from-help.py: the poll command, whose
    synopsis takes two lines of the help, is one tagged paragraph with its description."""

    def test_poll_is_one_item(self):
        with tempfile.TemporaryDirectory() as tmp:
            page = os.path.join(tmp, "dnscan.1")
            subprocess.run([sys.executable, MAN_FROM_HELP, "--name", "dnscan", "--summary", "s",
                            "--version", "v", "--output", page, "--", DNSCAN], check=True)
            with open(page, encoding="utf-8") as f:
                roff = f.read()
        self.assertIn(".TP\n\\fBpoll MAC [\\-\\-assembly OUT/IN] [\\-\\-output HEX] "
                      "[\\-\\-set NAME=VALUE]... [\\-\\-every MS] [\\-\\-count N]\\fR\n"
                      "poll I/O once, or every MS (N times, or until interrupted); values by the "
                      "assembly's names\n.TP\n\\fBmonitor\\fR\n", roff)


if __name__ == "__main__":
    unittest.main()
