# SPDX-License-Identifier: Apache-2.0
"""atv312d, the program, without a bus: its errors as the convention of the four programs says
(docs/architecture.md, "Messages and exit statuses"): `atv312d: error: WHAT` on stderr, the line
`Try 'atv312d --help'.` after wrong arguments, and the exit status of each failure. `atv312d ctl`
talks to a stand-in for the daemon's control socket here, so that each answer it can get is
tested: ok, a refusal, a closed connection, nobody listening."""

import os
import sys
import subprocess
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from control_stand_in import StandIn  # noqa: E402

ATV312D = os.environ["ATV312D"]
HINT = "Try 'atv312d --help'.\n"
EX_USAGE, EX_NOINPUT, EX_UNAVAILABLE, EX_CANTCREAT, EX_PROTOCOL = 64, 66, 69, 73, 76
EXIT_REFUSED = 1


def run(*args):
    return subprocess.run([ATV312D, *map(str, args)], capture_output=True, text=True, timeout=30,
                          check=False)


class WrongArguments(unittest.TestCase):
    def check(self, args, message):
        result = run(*args)
        self.assertEqual((result.returncode, result.stdout), (EX_USAGE, ""), result.stderr)
        self.assertEqual(result.stderr, f"atv312d: error: {message}\n{HINT}")

    def test_unknown_option(self):
        self.check(["vcan0", "--node-id", "4", "--bitrate", "250000"], "unknown option '--bitrate'")

    def test_option_without_its_value(self):
        self.check(["vcan0", "--node-id"], "option --node-id needs a value: give --node-id N")

    def test_missing_argument(self):
        self.check(["--node-id", "4"], "missing interface: run atv312d IFACE --node-id N, e.g. "
                   "atv312d vcan0 --node-id 4")

    def test_bad_value(self):
        self.check(["vcan0", "--node-id", "0"], "--node-id: 0 is out of range: node-ids are 1..127")


class StartFailures(unittest.TestCase):
    """What stops the daemon before it opens the interface: one error line, its own status."""

    def test_trace_file_cannot_be_created_is_73(self):
        result = run("vcan0", "--node-id", 4, "--trace", "/nonexistent/t.log")
        self.assertEqual(result.returncode, EX_CANTCREAT, result.stderr)
        self.assertEqual(result.stderr, "atv312d: error: cannot create the trace file "
                                        "'/nonexistent/t.log': No such file or directory\n")

    def test_store_that_cannot_be_read_is_66(self):
        with tempfile.TemporaryDirectory() as tmp:
            result = run("vcan0", "--node-id", 4, "--store", tmp)  # a directory: read() fails
        self.assertEqual(result.returncode, EX_NOINPUT, result.stderr)
        self.assertRegex(result.stderr, rf"^atv312d: error: store {tmp}: cannot be read: .+\n$")

    def test_no_interface_is_69(self):
        """No such interface, or (this kernel) no SocketCAN at all: both are 69."""
        result = run("nosuch0", "--node-id", 4)
        self.assertEqual(result.returncode, EX_UNAVAILABLE, result.stderr)
        self.assertRegex(result.stderr, r"^atv312d: error: (no network interface 'nosuch0'|this "
                                        r"kernel has no SocketCAN support).*\n$")


class Ctl(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "atv312d.sock")

    def tearDown(self):
        self.tmp.cleanup()

    def ctl(self, reply, *words):
        """Runs atv312d ctl PATH WORDS... against a stand-in answering `reply`; the request line
        is the words, --json written "json" (the protocol's word)."""
        stand_in = StandIn(self.path, reply)
        try:
            return run("ctl", self.path, *words)
        finally:
            stand_in.close()
            request = " ".join("json" if w == "--json" else str(w) for w in words)
            self.assertEqual(stand_in.requests, [request + "\n"])

    def test_ok_on_stdout(self):
        result = self.ctl("ok node 4: LI3 on\n", "input", 4, "LI3", "on")
        self.assertEqual((result.returncode, result.stdout, result.stderr),
                         (0, "ok node 4: LI3 on\n", ""))

    def test_refusal_is_the_error_of_the_program(self):
        result = self.ctl("error: node 9 is not present: this daemon runs node-id 4\n",
                          "fault", 9, "OHF")
        self.assertEqual((result.returncode, result.stdout, result.stderr), (
            EXIT_REFUSED, "",
            "atv312d: error: node 9 is not present: this daemon runs node-id 4\n"))

    def test_refusal_in_json_is_the_reply(self):
        reply = '{"ok":false,"error":"node 9 is not present: this daemon runs node-id 4"}\n'
        result = self.ctl(reply, "--json", "fault", 9, "OHF")
        self.assertEqual((result.returncode, result.stdout, result.stderr), (EXIT_REFUSED, reply, ""))

    def test_no_reply_is_76(self):
        result = self.ctl(None, "state")
        self.assertEqual((result.returncode, result.stdout), (EX_PROTOCOL, ""))
        self.assertEqual(result.stderr, f"atv312d: error: ctl: no reply from {self.path}: the "
                                        "daemon closed the connection\n")

    def test_nobody_listening_is_69(self):
        result = run("ctl", self.path, "state")
        self.assertEqual((result.returncode, result.stdout), (EX_UNAVAILABLE, ""))
        self.assertEqual(result.stderr, f"atv312d: error: ctl: cannot connect to {self.path}: No "
                                        f"such file or directory: is atv312d running with "
                                        f"--control {self.path}?\n")

    def test_wrong_arguments(self):
        result = run("ctl", self.path)
        self.assertEqual((result.returncode, result.stdout), (EX_USAGE, ""))
        self.assertEqual(result.stderr, "atv312d: error: ctl: give the daemon's socket and a "
                                        "command: atv312d ctl PATH [--json] COMMAND..., e.g. "
                                        f"atv312d ctl /tmp/atv312d.sock fault 4 OHF\n{HINT}")
        long_path = "/tmp/" + "x" * 120 + ".sock"
        result = run("ctl", long_path, "state")
        self.assertEqual((result.returncode, result.stdout), (EX_USAGE, ""))
        self.assertEqual(result.stderr, f"atv312d: error: ctl: the path {long_path} is longer "
                                        f"than 107 characters: give a shorter one\n{HINT}")


class Help(unittest.TestCase):
    def test_help_ends_with_the_exit_statuses(self):
        result = run("--help")
        self.assertEqual(result.returncode, 0)
        statuses = result.stdout.split("\nExit status:\n")[1]
        self.assertEqual([line.split()[0] for line in statuses.splitlines()
                          if not line.startswith("      ")],
                         ["0", "1", "64", "65", "66", "69", "70", "71", "73", "76"])


if __name__ == "__main__":
    unittest.main()
