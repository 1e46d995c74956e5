# SPDX-License-Identifier: Apache-2.0
"""dnscan's command line without a bus: every argument error is `dnscan: error: WHAT` on stderr
with its exit status (64 wrong arguments, followed by `Try 'dnscan --help'.`; 65 data), --json
adds {"error", "exit"} on stdout, and a missing interface or CAN support is 69 (docs/dnscan.md,
docs/architecture.md "Messages and exit statuses").

On a bus (DNSCAN_BUS, set inside tools/vcan-run by the test dnscan_socketcan, with ATV312D): `poll
1-63 --every` re-establishes every drive's polled connection after the daemon stood still for a
second, its summary adds up, and SIGINT or SIGTERM releases each slave's connections on the bus
(docs/dnscan.md, docs/decisions.md D-DEVICENET-RECONNECT)."""

import json
import os
import re
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest

DNSCAN = os.environ["DNSCAN"]
MAN_FROM_HELP = os.path.join(os.environ["PROJECT_SOURCE_DIR"], "tools", "man-from-help.py")
BUS = os.environ.get("DNSCAN_BUS")
ATV312D = os.environ.get("ATV312D")


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

    def test_poll_bad_mac_list(self):
        self.check(["poll", "5-3"], 64, "'5-3' is not a MAC ID or a list of them: give 0..63, a "
                   "range like 1-63 or a list like 5,7")
        self.check(["poll", "1,,2"], 64, "'1,,2' is not a MAC ID or a list of them: give 0..63, a "
                   "range like 1-63 or a list like 5,7")
        self.check(["poll", "0-3"], 64,
                   "MAC ID 0 is the scanner's own: give the scanner another with --mac-id N")

    def test_poll_bad_output(self):
        self.check(["poll", "63", "--output", "6x"], 65,
                   "--output: '6x' is not data: give hexadecimal bytes (61 00 B0 04)")

    def test_ucmm_connection_for_get_and_set_only(self):
        self.check(["--ucmm-connection", "scan"], 64,
                   "--ucmm-connection: for get and set only, not scan")
        self.check(["allocate", "63", "--ucmm-connection"], 64,
                   "--ucmm-connection: for get and set only, not allocate")


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
                     "monitor", "--ucmm-connection", "else can0\n"
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


class Frames:
    """Every DeviceNet frame of group 2 messages 3 (the slaves' explicit responses) and 6 (the
    scanner's unconnected requests, Allocate and Release) and the duplicate MAC ID checks (7),
    as candump text with their time, read from a raw CAN socket by a thread."""

    def __init__(self, iface):
        self.sock = socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW)
        filters = b"".join(struct.pack("=II", 0x400 | message, 0x607) for message in (3, 6, 7))
        self.sock.setsockopt(socket.SOL_CAN_RAW, socket.CAN_RAW_FILTER, filters)
        self.sock.bind((iface,))
        self.sock.settimeout(0.2)
        self.seen = []
        self.lock = threading.Lock()
        self.running = True
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        while self.running:
            try:
                raw = self.sock.recv(16)
            except socket.timeout:
                continue
            can_id, length, data = struct.unpack("=IB3x8s", raw)
            with self.lock:
                self.seen.append((time.monotonic(), f"{can_id & 0x7FF:03X}#{data[:length].hex().upper()}"))

    def mark(self):
        with self.lock:
            return len(self.seen)

    def wait(self, wanted, timeout, since=0):
        """Waits until every frame of `wanted` (candump texts, the first byte of the data as a
        regular expression's `..` where it carries the XID) was seen after `since`."""
        patterns = {w: re.compile(w + "$") for w in wanted}
        deadline = time.monotonic() + timeout
        while True:
            with self.lock:
                texts = [t for _, t in self.seen[since:]]
            missing = [w for w, p in patterns.items() if not any(p.match(t) for t in texts)]
            if not missing:
                return
            if time.monotonic() > deadline:
                raise AssertionError(f"not seen within {timeout} s: {missing[:5]} ({len(missing)})")
            time.sleep(0.05)

    def close(self):
        self.running = False
        self.thread.join()
        self.sock.close()


def release_of(mac_id):
    """The scanner's Release of explicit and polled (any XID), and the slave's answer."""
    return [f"{0x406 | mac_id << 3:03X}#[04]04C030103", f"{0x403 | mac_id << 3:03X}#[04]0CC"]


class Lines:
    """A stream of a process read by a thread: the lines so far, waited for with deadlines."""

    def __init__(self, stream):
        self.lines = []
        self.lock = threading.Lock()
        self.thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self.thread.start()

    def _read(self, stream):
        for line in stream:
            with self.lock:
                self.lines.append(line.rstrip("\n"))

    def count(self, pattern):
        with self.lock:
            return sum(1 for line in self.lines if re.search(pattern, line))

    def wait(self, pattern, count, timeout):
        deadline = time.monotonic() + timeout
        while self.count(pattern) < count:
            if time.monotonic() > deadline:
                with self.lock:
                    tail = self.lines[-5:]
                raise AssertionError(f"{self.count(pattern)} of {count} lines {pattern!r} within "
                                     f"{timeout} s; last {tail}")
            time.sleep(0.05)

    def all(self):
        self.thread.join(timeout=10)
        with self.lock:
            return list(self.lines)


# The polls' period: the expected packet rate too, so a drive times the connection out after
# 4 x 104 ms without a poll, well inside the 1 s the daemon stands still.
POLL_MS = 100
ALL = range(1, 64)


@unittest.skipUnless(BUS and ATV312D, "on a bus only: DNSCAN_BUS and ATV312D (the test "
                     "dnscan_socketcan sets them inside tools/vcan-run)")
class OnTheBus(unittest.TestCase):
    def setUp(self):
        self.frames = Frames(BUS)
        self.addCleanup(self.frames.close)
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.control = os.path.join(self.tmp.name, "control.sock")
        mark = self.frames.mark()
        self.daemon = subprocess.Popen([ATV312D, BUS, "--devicenet", "--mac-id", "1-63", "--control",
                                        self.control], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.addCleanup(self.stop_daemon)
        # every drive's two check requests, then every drive online (no connection yet)
        checks = [f"{0x407 | m << 3:03X}#00F300{m:02X}002031" for m in ALL]
        self.frames.wait(checks, timeout=10, since=mark)
        self.wait_drives(lambda node: node["ns"] == "flashing-green", timeout=10)

    def stop_daemon(self):
        self.daemon.send_signal(signal.SIGCONT)
        self.daemon.terminate()
        self.daemon.wait(timeout=10)

    def drives(self):
        done = subprocess.run([ATV312D, "ctl", self.control, "--json", "state"], capture_output=True,
                              text=True, timeout=10, check=False)
        return json.loads(done.stdout)["nodes"] if done.returncode == 0 else []

    def wait_drives(self, predicate, timeout):
        deadline = time.monotonic() + timeout
        while True:
            nodes = self.drives()
            if len(nodes) == len(ALL) and all(predicate(node) for node in nodes):
                return nodes
            if time.monotonic() > deadline:
                raise AssertionError(f"not every drive as wanted within {timeout} s: "
                                     f"{[n for n in nodes if not predicate(n)][:3]}")
            time.sleep(0.1)

    def poll(self, macs, *args):
        proc = subprocess.Popen([DNSCAN, "-i", BUS, "--no-check", "poll", macs, "--assembly", "21/71",
                                 "--every", str(POLL_MS), *args], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        self.addCleanup(self.end, proc)
        return proc, Lines(proc.stdout), Lines(proc.stderr)

    @staticmethod
    def end(proc):
        if proc.poll() is None:
            proc.kill()
        proc.wait(timeout=10)
        proc.stdout.close()
        proc.stderr.close()

    def summary(self, out, mac_id):
        pattern = re.compile(rf"MAC ID {mac_id}: polls (\d+), answered (\d+), missed (\d+), awaiting ([01]), "
                             r"late (\d+), lost (\d+), re-established (\d+)$")
        found = [pattern.match(line) for line in out]
        found = [m for m in found if m]
        self.assertEqual(len(found), 1, out[-3:])
        return [int(n) for n in found[0].groups()]

    def test_every_connection_recovers_after_a_stall_and_sigint_releases_them(self):
        proc, out, err = self.poll("1-63")
        for mac_id in ALL:
            out.wait(rf"^MAC ID {mac_id}: Faulted=", 1, timeout=20)
        # The daemon stands still for a second: every drive's polled connection times out
        self.daemon.send_signal(signal.SIGSTOP)
        time.sleep(1.0)
        self.daemon.send_signal(signal.SIGCONT)
        for mac_id in ALL:
            err.wait(rf"^dnscan: warn: MAC ID {mac_id}: the polled connection is lost \(4 polls in a "
                     r"row unanswered\): re-establishing it$", 1, timeout=20)
            err.wait(rf"^dnscan: warn: MAC ID {mac_id}: the polled connection is re-established "
                     r"\(try \d\)$", 1, timeout=20)
        # polled again: every drive answers after its connection came back
        answered = {m: out.count(rf"^MAC ID {m}: Faulted=") for m in ALL}
        for mac_id in ALL:
            out.wait(rf"^MAC ID {mac_id}: Faulted=", answered[mac_id] + 2, timeout=20)
        nodes = self.wait_drives(lambda node: node["ns"] == "green", timeout=10)
        # The drives whose polls the daemon's socket dropped in the stall timed their connection
        # out; those whose early polls it kept read them on waking, before their watchdog ran, and
        # did not: the scanner found every connection lost and re-established each all the same.
        self.assertNotEqual([n["node"] for n in nodes if n["frames"]["timeouts"] >= 1], [])
        mark = self.frames.mark()
        proc.send_signal(signal.SIGINT)
        self.assertEqual(proc.wait(timeout=20), 2)  # the polls missed in the stall
        self.frames.wait([f for m in ALL for f in release_of(m)], timeout=5, since=mark)
        self.wait_drives(lambda node: node["ns"] == "flashing-green", timeout=10)
        lines = out.all()
        for mac_id in ALL:
            polls, answered, missed, awaiting, late, lost, restored = self.summary(lines, mac_id)
            self.assertEqual(polls, answered + missed + awaiting, (mac_id, lines[-63:]))
            self.assertEqual(answered, len([1 for line in lines if line.startswith(f"MAC ID {mac_id}: Faulted=")]))
            self.assertGreaterEqual(lost, 1)
            self.assertEqual(restored, lost)
        self.assertEqual(err.count(r"^dnscan: error: MAC ID \d+: the polled connection is not"), 0)

    def test_sigterm_releases_the_connections(self):
        proc, out, err = self.poll("5,6")
        for mac_id in (5, 6):
            out.wait(rf"^MAC ID {mac_id}: Faulted=", 1, timeout=10)
        mark = self.frames.mark()
        proc.send_signal(signal.SIGTERM)
        self.assertEqual(proc.wait(timeout=10), 0)
        self.frames.wait(release_of(5) + release_of(6), timeout=5, since=mark)
        self.assertEqual(err.all(), [])
        lines = out.all()
        for mac_id in (5, 6):
            polls, answered, missed, awaiting, late, lost, restored = self.summary(lines, mac_id)
            self.assertEqual((polls, missed, awaiting, late, lost, restored), (answered, 0, 0, 0, 0, 0))


if __name__ == "__main__":
    unittest.main()
