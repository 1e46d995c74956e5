# SPDX-License-Identifier: Apache-2.0
"""cotrace, the installed program: a trace recorded from atv312d decoded byte for byte as
expected, malformed lines reported with their line number, usage errors, exit codes: every error
is `cotrace: error: WHAT`, followed by `Try 'cotrace --help'.` after wrong arguments
(docs/architecture.md, "Messages and exit statuses")."""

import os
import select
import subprocess
import tempfile
import unittest
from pathlib import Path

COTRACE = os.environ["COTRACE"]
ROOT = Path(os.environ["PROJECT_SOURCE_DIR"])
HERE = Path(__file__).resolve().parent
EDS = ROOT / "eds" / "ATV312.eds"

EX_USAGE, EX_DATAERR, EX_NOINPUT = 64, 65, 66
HINT = "Try 'cotrace --help'.\n"


def cotrace(*args, stdin=None):
    return subprocess.run([COTRACE, *map(str, args)], input=stdin, capture_output=True, text=True,
                          timeout=30)


class RecordedTrace(unittest.TestCase):
    def test_trace_of_atv312d_decoded_as_expected(self):
        result = cotrace("--eds", EDS, "--node", 4, HERE / "atv312.log")
        self.assertEqual(result.stderr, "")
        self.assertEqual(result.returncode, 0)
        self.assertEqual(result.stdout, (HERE / "atv312.expected").read_text())

    def test_standard_input_is_the_same_as_the_file(self):
        log = (HERE / "atv312.log").read_text()
        from_file = cotrace(HERE / "atv312.log")
        from_stdin = cotrace(stdin=log)
        from_dash = cotrace("-", stdin=log)
        self.assertEqual(from_file.returncode, 0)
        self.assertEqual(from_stdin.stdout, from_file.stdout)
        self.assertEqual(from_dash.stdout, from_file.stdout)
        self.assertIn("SDO 4 request: upload 1008:00\n", from_file.stdout)


GOOD = "(1700000000.000100) vcan0 000#0104\n"
GOOD_OUT = "(1700000000.000100) vcan0 000#0104              NMT Start remote node, node 4\n"


class Pipe(unittest.TestCase):
    def test_each_line_written_as_it_comes(self):
        """`atv312d --trace - | cotrace`: a frame's line comes out before the next is written."""
        proc = subprocess.Popen([COTRACE], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        try:
            proc.stdin.write(GOOD)
            proc.stdin.flush()
            ready = select.select([proc.stdout], [], [], 10.0)[0]
            self.assertEqual(ready, [proc.stdout], "no line while the pipe stays open")
            self.assertEqual(proc.stdout.readline(), GOOD_OUT)
        finally:
            proc.stdin.close()
            self.assertEqual(proc.wait(timeout=10), 0)
            proc.stdout.close()


class MalformedLines(unittest.TestCase):
    def test_reported_with_line_number_and_skipped(self):
        result = cotrace(stdin=GOOD + "garbage\n" + GOOD)
        self.assertEqual(result.returncode, EX_DATAERR)
        self.assertEqual(result.stdout, GOOD_OUT + GOOD_OUT)
        self.assertEqual(result.stderr,
                         "cotrace: error: <stdin>:2: not a candump -L line: 'garbage': expected "
                         "'(SECONDS.FRACTION) IFACE ID#DATA', e.g. (1700000000.000100) vcan0 "
                         "604#4008100000000000\n")

    def test_strict_stops_at_the_first(self):
        with tempfile.NamedTemporaryFile("w", suffix=".log") as f:
            f.write(GOOD + "(1700000000.000200) vcan0 604#12345\n" + GOOD)
            f.flush()
            result = cotrace("--strict", f.name)
        self.assertEqual(result.returncode, EX_DATAERR)
        self.assertEqual(result.stdout, GOOD_OUT)
        self.assertTrue(result.stderr.startswith(f"cotrace: error: {f.name}:2: not a candump -L line: "
                                                 "'(1700000000.000200) vcan0 604#12345'"))

    def test_every_timestamp_canplayer_reads(self):
        """canplayer and log2asc read any number of digits on either side of the point; the
        fraction is a decimal fraction of a second (D-CANDUMP-FRACTION), shown to the microsecond."""
        lines = ["(1.0) vcan0 000#0104\n", "(0.5) vcan0 000#0104\n",
                 "(1700000000.1234567891) vcan0 000#0104\n", "(01.000100) vcan0 000#0104\n"]
        result = cotrace(stdin="".join(lines))
        self.assertEqual(result.stderr, "")
        self.assertEqual(result.returncode, 0)
        meaning = " vcan0 000#0104              NMT Start remote node, node 4\n"
        self.assertEqual(result.stdout, "".join(f"({stamp}){meaning}" for stamp in [
            "0000000001.000000", "0000000000.500000", "1700000000.123456", "0000000001.000100"]))

    def test_timestamp_without_digits_refused(self):
        for stamp in ["(1.)", "(.5)", "(1)", "(1.5x)"]:
            result = cotrace(stdin=f"{stamp} vcan0 000#0104\n")
            self.assertEqual(result.returncode, EX_DATAERR, stamp)
            self.assertEqual(result.stderr,
                             f"cotrace: error: <stdin>:1: not a candump -L line: '{stamp} vcan0 000#0104': "
                             "expected '(SECONDS.FRACTION) IFACE ID#DATA', e.g. (1700000000.000100) "
                             "vcan0 604#4008100000000000\n")

    def test_blank_lines_are_ignored(self):
        result = cotrace(stdin=GOOD + "\n" + GOOD)
        self.assertEqual((result.returncode, result.stdout), (0, GOOD_OUT + GOOD_OUT))


class CommandLine(unittest.TestCase):
    def check_usage_error(self, args, message):
        result = cotrace(*args)
        self.assertEqual(result.returncode, EX_USAGE)
        self.assertEqual(result.stderr, f"cotrace: error: {message}\n{HINT}")
        self.assertEqual(result.stdout, "")

    def test_usage_errors(self):
        self.check_usage_error(["--bogus"], "unknown option '--bogus'")
        self.check_usage_error(["--eds"], "option --eds needs a value: give --eds FILE")
        self.check_usage_error(["--assemblies", ""],
                               "option --assemblies needs a value: give --assemblies OUT,IN")
        self.check_usage_error(["--eds", EDS], f"--eds {EDS} needs --node N: the node-id the EDS "
                                               "describes")
        self.check_usage_error(["--eds", EDS, "--node", "128"],
                               "--node: '128' is not a node-id: use a number 1..127")
        self.check_usage_error(["--node", "4"],
                               "--node 4 needs --eds FILE: without an EDS there is nothing to "
                               "apply it to")
        self.check_usage_error(["--emcy-table", "atv71"],
                               "--emcy-table: unknown table 'atv71': the tables are atv58")
        self.check_usage_error(["-i", "vcan0", "x.log"], "give either files or -i vcan0, not both")
        self.check_usage_error(["--devicenet", "--emcy-table", "atv58"],
                               "--devicenet: an EDS and an EMCY table are CANopen's, not "
                               "DeviceNet's")
        self.check_usage_error(["--assemblies", "100,101"],
                               "--assemblies needs --devicenet: assemblies are DeviceNet's")
        self.check_usage_error(["--devicenet", "--assemblies", "100,70,1"],
                               "--assemblies: '100,70,1' is not OUT,IN: OUT 20, 21 or 100, IN "
                               "70, 71 or 101, e.g. 100,101")

    def test_missing_files(self):
        result = cotrace("/nonexistent.log")
        self.assertEqual(result.returncode, EX_NOINPUT)
        self.assertEqual(result.stderr,
                         "cotrace: error: cannot read '/nonexistent.log': No such file or "
                         "directory\n")
        result = cotrace("--eds", "/nonexistent.eds", "--node", "4", stdin="")
        self.assertEqual(result.returncode, EX_NOINPUT)
        self.assertEqual(result.stderr, "cotrace: error: cannot read the EDS '/nonexistent.eds': "
                                        "No such file or directory\n")

    def test_malformed_eds(self):
        with tempfile.NamedTemporaryFile("w", suffix=".eds") as f:
            f.write("[1000]\nno equals sign\n")
            f.flush()
            result = cotrace("--eds", f.name, "--node", "4", stdin="")
        self.assertEqual(result.returncode, EX_DATAERR)
        self.assertEqual(result.stderr, f"cotrace: error: {f.name}:2: 'no equals sign' is neither "
                                        "a [section] nor a key=value line\n")

    def test_output_that_cannot_be_written_is_74(self):
        with open("/dev/full", "w") as full:
            result = subprocess.run([COTRACE, HERE / "atv312.log"], stdout=full,
                                    stderr=subprocess.PIPE, text=True, timeout=30)
        self.assertEqual(result.returncode, 74)
        self.assertEqual(result.stderr, "cotrace: error: cannot write the output: No space left on "
                                        "device\n")

    def test_vendor_emcy_table(self):
        result = cotrace("--emcy-table", "atv58",
                         stdin="(1700000000.000100) vcan0 084#1023010000000000\n")
        self.assertEqual(result.returncode, 0)
        self.assertIn("EMCY node 4: 0x2310 OCF: overcurrent fault (ATV58), ", result.stdout)

    def test_help_and_version(self):
        result = cotrace("--help")
        self.assertEqual(result.returncode, 0)
        self.assertTrue(result.stdout.startswith("usage: cotrace [FILE... | -i IFACE] "))
        statuses = result.stdout.split("\nExit status:\n")[1]
        self.assertEqual([line.split()[0] for line in statuses.splitlines()
                          if not line.startswith("      ")],
                         ["0", "64", "65", "66", "69", "71", "74"])
        result = cotrace("--version")
        self.assertEqual(result.returncode, 0)
        self.assertRegex(result.stdout, r"^cotrace \d+\.\d+\.\d+\n$")


if __name__ == "__main__":
    unittest.main()
