# SPDX-License-Identifier: Apache-2.0
"""Shared helpers for the integration tests on real SocketCAN.

These tests run where a `vcan0` interface is up: ctest starts them through `tools/vcan-run`, which
boots User-Mode Linux once for the whole run when the host kernel has no vcan. The daemon under test
is `$ATV312D`: ctest sets it to the `atv312d` of the build it runs in (scripts/run-tests runs these
tests against build/, --full also against build-matrix/gcc-Release/); by hand it defaults to
build/'s. The session's header names it.

Every wait here is deadline based: a test waits for the frame it expects, never sleeps and hopes.
"""

import json
import os
import queue
import re
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import can
import pytest

ROOT = Path(__file__).resolve().parents[2]
EDS = ROOT / "eds" / "ATV312.eds"
IFACE = os.environ.get("ATV312_IFACE", "vcan0")

# How long a daemon may take from exec to its boot-up frame. Generous because User-Mode Linux makes
# every system call slower, and a loaded CI machine slower still; a healthy daemon takes ~10 ms.
BOOT_TIMEOUT = 5.0
# python canopen's LocalNode, an SDO server the project did not write (local_node below).
SDO_SERVER_HELPER = Path(__file__).with_name("sdo_server_helper.py")
LOCAL_NODE = 10
# How long a device may take to answer an SDO request or react to a command frame.
REPLY_TIMEOUT = 1.0

# A frame no CANopen device in these tests reacts to (not in the CiA 301 pre-defined connection set
# of any node-id): used to know that a listener is bound before the traffic it must see is sent.
MARKER_ID = 0x7FF

EX_OK = 0
EX_USAGE = 64


# Without ATV312D: build/'s daemon. One build's, never "the newest of build*/": after
# scripts/run-tests --full that would be build-asan/'s, which cannot run inside User-Mode Linux.
DEFAULT_DAEMON = ROOT / "build" / "apps" / "atv312d" / "atv312d"


def daemon_path():
    path = os.environ.get("ATV312D") or str(DEFAULT_DAEMON)
    if not os.access(path, os.X_OK):
        pytest.fail(f"the daemon is not built: set ATV312D to the atv312d binary (got {path!r})")
    return path


def pytest_report_header(config):
    return f"atv312d under test: {os.environ.get('ATV312D') or DEFAULT_DAEMON}"


# ---- frames --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Frame:
    can_id: int
    data: bytes = b""
    rtr: bool = False
    timestamp: float = 0.0  # kernel receive time, seconds

    @classmethod
    def parse(cls, text):
        """'604#4000100000000000' or '704#R' (cansend syntax, standard identifiers)."""
        ident, _, payload = text.partition("#")
        if payload.upper().startswith("R"):
            return cls(int(ident, 16), b"", True)
        return cls(int(ident, 16), bytes.fromhex(payload.replace(".", "")))

    def __str__(self):
        return f"{self.can_id:03X}#" + ("R" if self.rtr else self.data.hex().upper())


def as_data(data):
    if data is None or isinstance(data, bytes):
        return data
    return bytes.fromhex(data.replace(" ", "").replace(".", ""))


class FrameWatcher:
    """Something that yields the frames seen on the bus, in order, with deadline-based waits."""

    def __init__(self):
        self.seen = []  # every frame seen so far, for error messages

    def _next(self, timeout):
        raise NotImplementedError

    def next_frame(self, timeout):
        frame = self._next(max(0.0, timeout))
        if frame is not None:
            self.seen.append(frame)
        return frame

    def mark(self):
        """A position in the frames seen so far, for expect(..., since=mark)."""
        return len(self.seen)

    def expect(self, can_id, data=None, timeout=REPLY_TIMEOUT, rtr=False, since=None):
        """Waits for a frame with can_id (and exactly data, when given); returns it.

        With since (a mark()), a matching frame already seen after that mark counts too: for a frame
        that may come before or after another one the test waits for first. Other frames seen
        meanwhile are skipped. Fails with what was seen when the deadline passes."""
        data = as_data(data)
        if since is not None:
            for frame in self.seen[since:]:
                if frame.can_id == can_id and frame.rtr == rtr and (data is None or frame.data == data):
                    return frame
        deadline = time.monotonic() + timeout
        skipped = []
        while True:
            frame = self.next_frame(deadline - time.monotonic())
            if frame is None:
                want = f"{can_id:03X}#" + ("R" if rtr else (data.hex().upper() if data is not None else "*"))
                shown = " ".join(str(f) for f in skipped[-30:]) or "nothing"
                raise AssertionError(f"no {want} within {timeout:.2f} s; saw: {shown}")
            if frame.can_id == can_id and frame.rtr == rtr and (data is None or frame.data == data):
                return frame
            skipped.append(frame)

    def expect_none(self, can_id, duration):
        """Asserts that no frame with can_id appears during duration seconds."""
        deadline = time.monotonic() + duration
        while True:
            frame = self.next_frame(deadline - time.monotonic())
            if frame is None:
                return
            if frame.can_id == can_id:
                raise AssertionError(f"unexpected {frame} within {duration:.2f} s")

    def collect(self, duration, can_id=None):
        """Every frame (with can_id, when given) seen during duration seconds."""
        deadline = time.monotonic() + duration
        frames = []
        while True:
            frame = self.next_frame(deadline - time.monotonic())
            if frame is None:
                return frames
            if can_id is None or frame.can_id == can_id:
                frames.append(frame)

    def collect_n(self, can_id, count, timeout):
        """The next count frames with can_id; fails if they do not all come within timeout."""
        deadline = time.monotonic() + timeout
        frames = []
        while len(frames) < count:
            frames.append(self.expect(can_id, timeout=max(0.0, deadline - time.monotonic())))
        return frames


class Bus(FrameWatcher):
    """python-can socketcan bus: sends frames and watches the replies."""

    def __init__(self, channel=IFACE):
        super().__init__()
        self.channel = channel
        self.bus = can.Bus(interface="socketcan", channel=channel)

    def _next(self, timeout):
        deadline = time.monotonic() + timeout
        while True:
            try:
                msg = self.bus.recv(timeout=max(0.0, deadline - time.monotonic()))
            except can.CanOperationError:
                # The interface went down (ENETDOWN) under a test that does that on purpose.
                if time.monotonic() >= deadline:
                    return None
                time.sleep(0.01)
                continue
            if msg is None:
                return None
            if msg.is_error_frame or msg.is_extended_id:
                continue
            return Frame(msg.arbitration_id, bytes(msg.data), msg.is_remote_frame, msg.timestamp)

    def send(self, frame):
        if isinstance(frame, str):
            frame = Frame.parse(frame)
        if frame.rtr:
            msg = can.Message(arbitration_id=frame.can_id, is_extended_id=False, is_remote_frame=True, dlc=0)
        else:
            msg = can.Message(arbitration_id=frame.can_id, is_extended_id=False, data=frame.data)
        self.bus.send(msg, timeout=1.0)

    def request(self, frame, reply_id, reply=None, timeout=REPLY_TIMEOUT):
        """Sends frame, then waits for reply_id (with exactly reply, when given)."""
        self.send(frame)
        return self.expect(reply_id, reply, timeout)

    # SDO helpers (expedited transfers, node-id relative COB-IDs)
    def sdo_write(self, node, index, sub, value, size):
        cmd = {1: 0x2F, 2: 0x2B, 3: 0x27, 4: 0x23}[size]
        data = bytes([cmd, index & 0xFF, index >> 8, sub]) + value.to_bytes(4, "little")
        reply = self.request(Frame(0x600 + node, data), 0x580 + node)
        expected = bytes([0x60, index & 0xFF, index >> 8, sub, 0, 0, 0, 0])
        assert reply.data == expected, f"SDO write {index:04X}:{sub:02X} = {value}: got {reply}"

    def sdo_read(self, node, index, sub):
        data = bytes([0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0])
        reply = self.request(Frame(0x600 + node, data), 0x580 + node)
        assert reply.data[0] & 0xE3 == 0x43, f"SDO read {index:04X}:{sub:02X}: got {reply}"
        assert reply.data[1:4] == data[1:4], f"SDO read {index:04X}:{sub:02X}: got {reply}"
        size = 4 - ((reply.data[0] >> 2) & 3)
        return int.from_bytes(reply.data[4 : 4 + size], "little")

    def sdo_abort_code(self, node, request):
        """Sends an SDO request that must be refused; returns the abort code."""
        reply = self.request(Frame(0x600 + node, as_data(request)), 0x580 + node)
        assert reply.data[0] == 0x80, f"expected an abort, got {reply}"
        return int.from_bytes(reply.data[4:8], "little")

    def nmt(self, command, node):
        self.send(Frame(0x000, bytes([command, node])))

    def close(self):
        self.bus.shutdown()


NMT_START, NMT_STOP, NMT_PRE_OPERATIONAL, NMT_RESET_NODE, NMT_RESET_COMMUNICATION = 0x01, 0x02, 0x80, 0x81, 0x82


class Candump(FrameWatcher):
    """`candump -L IFACE` in a subprocess: frames with the kernel's receive timestamps."""

    LINE = re.compile(r"^\((\d+\.\d{6})\) (\S+) ([0-9A-F]{3})#(R\d?|[0-9A-F]*)$")

    def __init__(self, channel=IFACE):
        super().__init__()
        self.channel = channel
        self.proc = subprocess.Popen(
            ["candump", "-L", channel],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            bufsize=1,
        )
        self.lines = queue.Queue()
        self.bad_lines = []
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def _next(self, timeout):
        deadline = time.monotonic() + timeout
        while True:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                return None
            if line is None:
                raise AssertionError(f"candump exited with {self.proc.wait()}")
            m = self.LINE.match(line)
            if not m:
                self.bad_lines.append(line)
                continue
            ts, _, ident, payload = m.groups()
            if payload.startswith("R"):
                return Frame(int(ident, 16), b"", True, float(ts))
            return Frame(int(ident, 16), bytes.fromhex(payload), False, float(ts))

    def wait_ready(self):
        """Returns once candump prints a marker frame we send: it is bound and listening."""
        deadline = time.monotonic() + BOOT_TIMEOUT
        while True:
            cansend(Frame(MARKER_ID, b"\xca\xfe"), self.channel)
            try:
                self.expect(MARKER_ID, timeout=0.2)
                return
            except AssertionError:
                if time.monotonic() > deadline:
                    raise AssertionError("candump did not start listening") from None

    def close(self):
        self.proc.terminate()
        self.proc.wait(timeout=5)


def cansend(frame, channel=IFACE):
    """Sends one frame with can-utils' cansend ('604#40...', '704#R')."""
    subprocess.run(["cansend", channel, str(frame)], check=True, timeout=5)


# ---- the daemon ----------------------------------------------------------------------------------


class Daemon:
    """One atv312d process, its stderr captured to a file."""

    def __init__(self, args, log_path):
        self.args = [daemon_path(), *args]
        self.log_path = log_path
        with open(log_path, "wb") as log:
            self.proc = subprocess.Popen(self.args, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT)
        self.pid = self.proc.pid

    def running(self):
        return self.proc.poll() is None

    def log(self):
        return Path(self.log_path).read_text(errors="replace")

    def stop(self, sig=signal.SIGTERM, timeout=5.0):
        """Sends sig and returns the exit status (fails if the daemon does not exit in time)."""
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
            try:
                self.proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
                raise AssertionError(f"atv312d did not exit within {timeout} s of signal {sig}") from None
        return self.proc.returncode

    def proc_status(self, field):
        """A numeric field of /proc/<pid>/status (e.g. voluntary_ctxt_switches)."""
        for line in Path(f"/proc/{self.pid}/status").read_text().splitlines():
            key, _, value = line.partition(":")
            if key == field:
                return int(value.split()[0])
        raise KeyError(field)


@pytest.fixture
def local_node():
    """python canopen's LocalNode as node LOCAL_NODE (10) in a helper process."""
    p = subprocess.Popen([sys.executable, str(SDO_SERVER_HELPER), IFACE, str(LOCAL_NODE)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert p.stdout.readline() == "ready\n", p.stderr.read()
        yield p
    finally:
        p.terminate()
        p.wait(timeout=BOOT_TIMEOUT)


@pytest.fixture
def bus():
    b = Bus()
    yield b
    b.close()


@pytest.fixture
def dump():
    """candump -L on vcan0, already listening."""
    d = Candump()
    d.wait_ready()
    yield d
    d.close()


@pytest.fixture
def start_daemon(tmp_path, request):
    """Factory: start_daemon(watcher, '--node-id', '4', ..., boot_ids=[4]) starts atv312d on vcan0 and
    waits (deadline) for the boot-up frame of each node in boot_ids: 00, or 00 and seven zero bytes
    for the nodes in padded_ids (a model of 8-byte frames, the ATV58). Each daemon is stopped with
    SIGTERM at the end of the test, which must make it exit 0; its log is printed on failure."""
    daemons = []

    def start(watcher, *args, boot_ids=None, padded_ids=(), iface=IFACE):
        args = [str(a) for a in args]
        if boot_ids is None:
            boot_ids = node_ids_from_args(args)
        d = Daemon([iface, *args], tmp_path / f"atv312d-{len(daemons)}.log")
        daemons.append(d)
        for node in boot_ids:
            try:
                boot = bytes(8) if node in padded_ids else b"\x00"
                watcher.expect(0x700 + node, boot, timeout=BOOT_TIMEOUT)
            except AssertionError as e:
                raise AssertionError(f"node {node} did not boot: {e}\n--- atv312d log ---\n{d.log()}") from None
        return d

    yield start
    failures = []
    for d in daemons:
        if d.proc.poll() is not None:
            continue  # the test ended it and checked how
        status = d.stop()
        if status != EX_OK:
            failures.append(f"atv312d {' '.join(d.args[1:])} exited {status} on SIGTERM")
    for d in daemons:
        print(f"--- log of atv312d {' '.join(d.args[1:])} ---\n{d.log()}")
    if failures:
        pytest.fail("; ".join(failures))


def node_ids_from_args(args):
    """The node-ids a daemon command line asks for ('--node-id 4', '--node-id 4-6', repeated)."""
    ids = []
    for i, a in enumerate(args):
        value = None
        if a == "--node-id" and i + 1 < len(args):
            value = args[i + 1]
        elif a.startswith("--node-id="):
            value = a.split("=", 1)[1]
        if value is None:
            continue
        lo, _, hi = value.partition("-")
        ids.extend(range(int(lo), int(hi or lo) + 1))
    return ids


@pytest.fixture
def drive(bus, start_daemon):
    """A single ATV312 at node-id 4, booted (pre-operational)."""
    return start_daemon(bus, "--node-id", 4)


def intervals(frames):
    return [b.timestamp - a.timestamp for a, b in zip(frames, frames[1:])]


# How late a periodic frame may leave after its due time: the wake-up latency of a daemon inside
# User-Mode Linux on a loaded 2-core machine (measured up to about 12 ms).
PERIODIC_LATENESS = 0.020


def assert_periodic(frames, period, what):
    """Frame k is due at t0 + k x period (a heartbeat producer schedules from the previous due
    time, never from the late send): after removing that schedule, the frames may differ only by
    wake-up lateness. A wrong period drifts out of the band (1 % over 10 periods is 10 ms); one frame
    early or late by more than the band fails too."""
    offsets = [f.timestamp - k * period for k, f in enumerate(frames)]
    spread = max(offsets) - min(offsets)
    assert spread <= PERIODIC_LATENESS, (
        f"{what}: {len(frames)} frames drift or jitter {spread * 1000:.1f} ms from a {period * 1000:.0f} ms "
        f"schedule; intervals {[round(i, 4) for i in intervals(frames)]}")


# How much earlier than its send a frame may be stamped: the kernel stamps it when its write
# completes, and the write of the frame before may have been the slower one.
STAMP_SLACK = 0.002


def assert_restarting_timer(frames, period, what):
    """A timer that restarts at each transmission (a TPDO's event timer, CiA 301 7.5.2.35): each
    interval is at least the period and at most one wake-up lateness over it. Lateness does not
    add up across frames, unlike a fixed schedule's (assert_periodic). A shorter period fails at
    once; a longer one fails when even the least late interval is past its lateness budget."""
    gaps = intervals(frames)
    assert min(gaps) >= period - STAMP_SLACK and max(gaps) <= period + PERIODIC_LATENESS, (
        f"{what}: intervals {[round(i, 4) for i in gaps]} for a {period * 1000:.0f} ms timer "
        f"that restarts at each transmission")
    assert min(gaps) <= period + PERIODIC_LATENESS / 4, (
        f"{what}: even the shortest interval {min(gaps) * 1000:.1f} ms is late: the period is "
        f"longer than {period * 1000:.0f} ms")


# ---- DeviceNet drives ---------------------------------------------------------------------------

# From the daemon's start to online: two check requests a second apart, then a second of silence,
# with room for User-Mode Linux on a loaded machine.
ONLINE_TIMEOUT = 4.0
STATE_TIMEOUT = 3.0


def ctl_state(sock, mac_id):
    done = subprocess.run([daemon_path(), "ctl", str(sock), "--json", "state", str(mac_id)], capture_output=True,
                          text=True, timeout=10)
    assert done.returncode == 0, done.stdout + done.stderr
    return json.loads(done.stdout)["nodes"][0]


def wait_state(sock, mac_id, timeout=STATE_TIMEOUT, **wanted):
    """Polls the control surface until the drive's state has every wanted field; returns it."""
    deadline = time.monotonic() + timeout
    while True:
        state = ctl_state(sock, mac_id)
        if all(state[k] == v for k, v in wanted.items()):
            return state
        if time.monotonic() > deadline:
            raise AssertionError(f"MAC ID {mac_id}: no {wanted} within {timeout} s; last {state}")
        time.sleep(0.02)


@pytest.fixture
def start_dn(start_daemon, dump, tmp_path):
    """start_dn(mac_ids, *args): atv312d --devicenet with --control; waits for each MAC ID's two
    check requests, a second apart, and for every drive online (NS flashing green: no connection
    yet). Returns (daemon, control socket)."""

    def start(mac_ids, *args):
        sock = tmp_path / f"dn-{time.monotonic_ns()}.sock"
        mark = dump.mark()
        d = start_daemon(dump, "--devicenet", "--mac-id", ",".join(map(str, mac_ids)), "--control", sock, *args,
                         boot_ids=[])
        for mac_id in mac_ids:
            check = (0x400 | mac_id << 3 | 7, f"00F300{mac_id:02X}002031")
            first = dump.expect(*check, timeout=ONLINE_TIMEOUT, since=mark)
            second = dump.expect(*check, timeout=ONLINE_TIMEOUT)
            assert 0.95 <= second.timestamp - first.timestamp <= 1.1, (first, second)
        for mac_id in mac_ids:
            wait_state(sock, mac_id, timeout=ONLINE_TIMEOUT, ns="flashing-green", ms="green")
        return d, sock

    return start
