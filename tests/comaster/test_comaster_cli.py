# SPDX-License-Identifier: Apache-2.0
"""comaster's command line without a bus: its errors as the convention of the four programs says
(docs/architecture.md, "Messages and exit statuses"): `comaster: error: WHAT` on stderr, after
wrong arguments the line naming the --help to read (the command's own when the command was
known), {"error", "exit"} on stdout with --json, and the exit status of each failure. The client
of a run's control socket talks to a stand-in here, so that each answer it can get is tested."""

import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from control_stand_in import StandIn  # noqa: E402

COMASTER = os.environ["COMASTER"]
EX_USAGE, EX_UNAVAILABLE, EX_PROTOCOL = 64, 69, 76
EXIT_REFUSED, EXIT_TIMEOUT = 1, 2
COMMANDS = ("read, write, nmt, scan, monitor, drive, boot, run, concise, set, get, status, disable, "
            "enable, can, configure, lss, time, gateway")


def run(*args):
    return subprocess.run([COMASTER, *map(str, args)], capture_output=True, text=True, timeout=30,
                          check=False)


class WrongArguments(unittest.TestCase):
    def check(self, args, message, command=None):
        result = run(*args)
        self.assertEqual((result.returncode, result.stdout), (EX_USAGE, ""), result.stderr)
        helped = f"comaster {command}" if command else "comaster"
        self.assertEqual(result.stderr, f"comaster: error: {message}\nTry '{helped} --help'.\n")

    def test_unknown_option(self):
        self.check(["--frob", "scan"], "unknown option '--frob'")
        self.check(["read", "4", "ACC", "--frob"], "read: unknown option '--frob'", "read")

    def test_option_without_its_value(self):
        self.check(["--timeout"], "option --timeout needs a value: give --timeout MS")
        self.check(["monitor", "4", "--heartbeat"],
                   "monitor: option --heartbeat needs a value: give --heartbeat MS", "monitor")
        self.check(["set", "4", "speed", "1", "--control"],
                   "set: option --control needs a value: give --control PATH", "set")

    def test_missing_and_extra_arguments(self):
        self.check([], f"no command: give one of {COMMANDS}")
        self.check(["frob"], f"unknown command 'frob': give one of {COMMANDS}")
        self.check(["write", "4", "ACC"], "write: missing arguments: usage: comaster write NODE "
                   "OBJECT [TYPE] VALUE [--block]", "write")
        self.check(["get", "4", "speed", "x"], "get: too many arguments from 'x': usage: comaster "
                   "get NODE NAME [--control PATH]", "get")

    def test_marker_arguments(self):
        """A PLC300 marker stands for NODE NAME (D-IMAGE-ADDRESS): each form its own count, and
        only the manual's addresses, before any run is asked."""
        syntax = ("is not a process image address: %IB/%IW/%ID (inputs) or %QB/%QW/%QD (outputs), "
                  "bytes 2000..2511, words even, double words multiples of 4")
        for marker in ("%IW2001", "%ID2002", "%IB2512", "%QB1999", "%XB2000", "%IW02000"):
            self.check(["get", marker], f"get: '{marker}' {syntax}", "get")
        self.check(["set", "%QW2001", "5"], f"set: '%QW2001' {syntax}", "set")
        self.check(["get", "%IW2000", "x"], "get: too many arguments from 'x': usage: comaster "
                   "get NODE NAME [--control PATH]", "get")
        self.check(["set", "%QW2000", "1", "2"], "set: too many arguments from '2': usage: comaster "
                   "set NODE NAME VALUE [--control PATH]", "set")
        self.check(["set", "4", "speed"], "set: missing arguments: usage: comaster set NODE NAME "
                   "VALUE [--control PATH]", "set")

    def test_lss_arguments(self):
        services = ("switch, set-node-id, set-bit-timing, activate, store, inquire, identify or "
                    "fastscan")
        self.check(["lss", "frob"], f"lss: 'frob' is not an LSS service: give {services}", "lss")
        self.check(["lss", "set-node-id", "128"],
                   "lss set-node-id: '128' is not a node-id: give 1..127, or none", "lss")
        self.check(["lss", "set-node-id"],
                   "lss set-node-id: takes 1 argument, 0 given (see lss --help)", "lss")
        self.check(["lss", "set-bit-timing", "300"],
                   "lss set-bit-timing: '300' is not a bit rate of CiA 305 table 0: give 1000, "
                   "800, 500, 250, 125, 50, 20, 10 (kbit/s) or auto", "lss")
        self.check(["lss", "activate", "70000"],
                   "lss activate: '70000' is not a switch delay: give milliseconds 0..65535", "lss")
        self.check(["lss", "switch", "sleeping"],
                   "lss switch: 'sleeping' is not an LSS state: give waiting or configuration, or "
                   "the four parts of an address", "lss")
        self.check(["lss", "switch", "1", "2", "3"],
                   "lss switch: give waiting, configuration, or VENDOR PRODUCT REVISION SERIAL "
                   "(3 values given)", "lss")
        self.check(["lss", "switch", "1", "2", "3", "x"],
                   "lss: 'x' is not a 32-bit number: give decimal or 0x hex, 0..4294967295", "lss")
        self.check(["lss", "inquire", "name"],
                   "lss inquire: 'name' is not something to inquire: give identity or node-id",
                   "lss")
        self.check(["lss", "identify", "1", "2"],
                   "lss identify: give non-configured, or VENDOR PRODUCT REV_LOW REV_HIGH "
                   "SERIAL_LOW SERIAL_HIGH (2 values given)", "lss")
        self.check(["lss", "fastscan", "0"],
                   "lss fastscan: '0' is not a node-id: give the first node-id to assign, 1..127",
                   "lss")
        self.check(["lss", "fastscan", "1", "--vendor"],
                   "lss: option --vendor needs a value: give --vendor N", "lss")
        self.check(["lss", "fastscan", "1", "--frame-ms", "0"],
                   "lss fastscan: --frame-ms 0 is out of range: give milliseconds 1..60000", "lss")

    def test_bad_values(self):
        self.check(["read", "128", "ACC"], "'128' is not a node-id: give a number 1..127", "read")
        self.check(["--timeout", "0", "scan"],
                   "--timeout: '0' is not a time: give milliseconds 1..600000", "scan")
        self.check(["drive", "4", "speed", "99999"],
                   "drive: speed '99999' is not a velocity: give rpm -32768..32767", "drive")

    def test_json_twin(self):
        result = run("--json", "read", "128", "ACC")
        self.assertEqual(result.returncode, EX_USAGE)
        message = "'128' is not a node-id: give a number 1..127"
        self.assertEqual(json.loads(result.stdout), {"error": message, "exit": EX_USAGE})
        self.assertEqual(result.stderr, f"comaster: error: {message}\nTry 'comaster read --help'.\n")


class Interface(unittest.TestCase):
    def test_missing_interface_is_69(self):
        """No such interface, or (this kernel) no SocketCAN at all: both are 69, in one line."""
        result = run("-i", "nosuch0", "read", "4", "0x1000", "u32")
        self.assertEqual((result.returncode, result.stdout), (EX_UNAVAILABLE, ""), result.stderr)
        self.assertRegex(result.stderr, r"^comaster: error: (no network interface 'nosuch0'|this "
                                        r"kernel has no SocketCAN support)[^\n]*\n$")


class ControlSocket(unittest.TestCase):
    """Each reply of a run: ok on stdout; its refusal and an SDO abort are 1, no answer in time
    2, as comaster's own errors; a run that closed without a reply 76, none listening 69."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "run.sock")

    def tearDown(self):
        self.tmp.cleanup()

    def set_speed(self, reply):
        stand_in = StandIn(self.path, reply)
        try:
            return run("set", 4, "speed", 1200, "--control", self.path)
        finally:
            stand_in.close()
            self.assertEqual(stand_in.requests, ["set\t4\tspeed\t1200\n"])

    def test_ok(self):
        result = self.set_speed("ok\n")
        self.assertEqual((result.returncode, result.stdout, result.stderr), (0, "ok\n", ""))

    def test_refused_is_1(self):
        result = self.set_speed("error: node 4: 6040h:00 (control) is an input\n")
        self.assertEqual((result.returncode, result.stdout, result.stderr), (
            EXIT_REFUSED, "", "comaster: error: node 4: 6040h:00 (control) is an input\n"))

    def test_abort_is_1_and_timeout_2(self):
        result = self.set_speed("abort: node 4, 6042:00: SDO abort 0x06090030: value range of "
                                "parameter exceeded\n")
        self.assertEqual((result.returncode, result.stderr), (
            EXIT_REFUSED, "comaster: error: node 4, 6042:00: SDO abort 0x06090030: value range of "
                          "parameter exceeded\n"))
        result = self.set_speed("timeout: node 4, 6042:00: no answer within 500 ms\n")
        self.assertEqual((result.returncode, result.stderr), (
            EXIT_TIMEOUT, "comaster: error: node 4, 6042:00: no answer within 500 ms\n"))

    def test_no_reply_is_76(self):
        result = self.set_speed(None)
        self.assertEqual((result.returncode, result.stdout, result.stderr), (
            EX_PROTOCOL, "", f"comaster: error: the comaster run on {self.path} closed without a "
                             "reply\n"))

    def test_no_run_is_69(self):
        result = run("status", "--control", self.path)
        self.assertEqual((result.returncode, result.stdout, result.stderr), (
            EX_UNAVAILABLE, "", f"comaster: error: no comaster run answers on {self.path} (No "
                                "such file or directory): start one with comaster run NETWORK, "
                                "or give its --control PATH\n"))


class Concise(unittest.TestCase):
    """comaster concise: drive4.dcf's configuration as CiA 302's concise DCF, byte for byte (1017h
    = 100, the PDO6 COB-IDs of node 4, 203Ch:02 and 03 = 20), and back to a DCF through the
    ATV312's EDS, which encodes to the same bytes."""

    ROOT = Path(__file__).resolve().parents[2]
    DRIVE4 = bytes.fromhex("05000000" "1710000200000064 00" "0514010400000004030000"
                           "0518010400000084020000" "3C20020200000014 00" "3C20030200000014 00"
                           .replace(" ", ""))

    def test_encode_decode_and_encode_again(self):
        with tempfile.TemporaryDirectory() as tmp:
            cdcf, dcf, again = Path(tmp, "d4.cdcf"), Path(tmp, "d4.dcf"), Path(tmp, "again.cdcf")
            result = run("concise", "encode", 4, self.ROOT / "examples/netmaster/drive4.dcf", cdcf)
            self.assertEqual((result.returncode, result.stderr), (0, ""))
            self.assertEqual(cdcf.read_bytes(), self.DRIVE4)
            result = run("concise", "decode", cdcf, self.ROOT / "eds/ATV312.eds", dcf)
            self.assertEqual((result.returncode, result.stderr), (0, ""))
            text = dcf.read_text()
            self.assertEqual([line for line in text.splitlines() if line.startswith("ParameterValue")],
                             ["ParameterValue=0x64", "ParameterValue=0x304", "ParameterValue=0x284",
                              "ParameterValue=0x14", "ParameterValue=0x14"])
            self.assertIn("[1017]\nParameterValue=0x64\n", text)
            result = run("concise", "encode", 4, dcf, again)
            self.assertEqual((result.returncode, result.stderr), (0, ""))
            self.assertEqual(again.read_bytes(), self.DRIVE4)
            result = subprocess.run([COMASTER, "concise", "encode", "4",
                                     str(self.ROOT / "examples/netmaster/drive4.dcf"), "-"],
                                    capture_output=True, timeout=30, check=False)
            self.assertEqual((result.returncode, result.stdout), (0, self.DRIVE4))

    def test_what_is_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            cut = Path(tmp, "cut.cdcf")
            cut.write_bytes(self.DRIVE4[:-1])
            result = run("concise", "decode", cut, self.ROOT / "eds/ATV312.eds", Path(tmp, "x.dcf"))
            self.assertEqual((result.returncode, result.stderr),
                             (65, f"comaster: error: concise: {cut} is not a concise DCF\n"))
            alien = Path(tmp, "alien.cdcf")
            alien.write_bytes(bytes.fromhex("01000000" "0050000100000001"))
            result = run("concise", "decode", alien, self.ROOT / "eds/ATV312.eds", "-")
            self.assertEqual((result.returncode, result.stdout, result.stderr),
                             (65, "", "comaster: error: concise: 5000h:00 is not an object of the EDS\n"))
            odd = Path(tmp, "odd.cdcf")  # 1017h is an UNSIGNED16: 3 bytes are no value of it
            odd.write_bytes(bytes.fromhex("01000000" "1710000300000064 0000".replace(" ", "")))
            result = run("concise", "decode", odd, self.ROOT / "eds/ATV312.eds", Path(tmp, "odd.dcf"))
            self.assertEqual((result.returncode, result.stderr),
                             (65, "comaster: error: concise: 1017h:00, 3 bytes, has no ParameterValue "
                                  "form as DataType 0x0006\n"))
            result = run("concise", "turn", 4, "a", "b")
            self.assertEqual(result.returncode, 64)
            self.assertIn("'turn' is neither encode nor decode", result.stderr)


class Help(unittest.TestCase):
    def test_help_ends_with_the_exit_statuses(self):
        result = run("--help")
        self.assertEqual(result.returncode, 0)
        self.assertIn("else can0\n                 (a real bus: the examples give -i vcan0",
                      result.stdout)
        statuses = result.stdout.split("\nExit status:\n")[1]
        self.assertEqual([line.split()[0] for line in statuses.splitlines()
                          if not line.startswith("      ")],
                         ["0", "1", "2", "3", "4", "64", "65", "66", "69", "70", "71", "73", "76"])


if __name__ == "__main__":
    unittest.main()
