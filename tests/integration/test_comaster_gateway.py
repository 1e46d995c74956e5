# SPDX-License-Identifier: Apache-2.0
"""comaster gateway, the CiA 309-3 ASCII gateway, against atv312d: the exact reply bytes of each
command line (CR LF ended, as CANopenNode's canopend writes them), the frames NMT commands put on
the bus, and the same gateway on a TCP port and a UNIX socket with two clients at once."""

import os
import queue
import signal
import socket
import subprocess
import threading
import time

import pytest

from conftest import IFACE, ROOT, Bus

COMASTER = os.environ.get("COMASTER") or str(ROOT / "build" / "apps" / "comaster" / "comaster")
REPLY_TIMEOUT = 3.0


class Gateway:
    """comaster gateway on standard input and output: lines in, reply lines out (bytes)."""

    def __init__(self, *args):
        self.proc = subprocess.Popen([COMASTER, "-i", IFACE, "gateway", *args],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE)
        self.lines = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line)
        self.lines.put(None)

    def send(self, text):
        self.proc.stdin.write(text.encode())
        self.proc.stdin.flush()

    def reply(self, timeout=REPLY_TIMEOUT):
        try:
            line = self.lines.get(timeout=timeout)
        except queue.Empty:
            raise AssertionError(f"no reply within {timeout} s") from None
        assert line is not None, f"the gateway ended: {self.proc.stderr.read()!r}"
        return line

    def ask(self, line, timeout=REPLY_TIMEOUT):
        self.send(line + "\r\n")
        return self.reply(timeout)

    def close(self):
        """Ends its input: the gateway answers what is left and exits 0."""
        self.proc.stdin.close()
        assert self.proc.wait(timeout=5) == 0, self.proc.stderr.read()
        assert self.lines.get(timeout=1) is None


@pytest.fixture
def gateway():
    g = Gateway()
    yield g
    if g.proc.poll() is None:
        g.proc.kill()
        g.proc.wait()


@pytest.fixture
def drive4(bus, start_daemon):
    return start_daemon(bus, "--node-id", "4")


def test_reads_writes_and_aborts(drive4, gateway):
    assert gateway.ask("[1] 4 read 0x1008 0 vs") == b'[1] "ATV312"\r\n'
    assert gateway.ask("[2] 4 r 0x1000 0 u32") == b"[2] 65938\r\n"
    assert gateway.ask("[3] 4 r 0x1000 0 x32") == b"[3] 0x00010192\r\n"
    assert gateway.ask("[4] 4 r 0x1000 0") == b"[4] 92 01 01 00\r\n"
    assert gateway.ask("[5] 4 read 0x203C 2 u16") == b"[5] 30\r\n"
    assert gateway.ask("[6] 4 write 0x203C 2 u16 55") == b"[6] OK\r\n"
    assert gateway.ask("[7] 4 read 0x203C 2 u16") == b"[7] 55\r\n"
    assert gateway.ask("[8] 4 read 0x1234 1 u8") == b"[8] ERROR:0x06020000\r\n"
    assert gateway.ask("[9] 4 write 0x1000 0 u32 1") == b"[9] ERROR:0x06010002\r\n"
    gateway.close()


def test_sdo_timeout_is_the_client_abort(drive4, gateway):
    assert gateway.ask("[1] set sdo_timeout 100") == b"[1] OK\r\n"
    start = time.monotonic()
    assert gateway.ask("[2] 9 read 0x1000 0 u32") == b"[2] ERROR:0x05040000\r\n"
    assert time.monotonic() - start < 1.0
    # The gateway goes on after the timeout.
    assert gateway.ask("[3] 4 read 0x1000 0 u32") == b"[3] 65938\r\n"
    gateway.close()


def test_nmt_frames(drive4, bus, gateway):
    assert gateway.ask("[1] 4 preop") == b"[1] OK\r\n"
    bus.expect(0x000, "8004")
    assert gateway.ask("[2] 4 start") == b"[2] OK\r\n"
    bus.expect(0x000, "0104")
    assert gateway.ask("[3] 0 stop") == b"[3] OK\r\n"
    bus.expect(0x000, "0200")
    assert gateway.ask("[4] 4 reset comm") == b"[4] OK\r\n"
    bus.expect(0x000, "8204")
    bus.expect(0x704, "00", timeout=REPLY_TIMEOUT)
    gateway.close()


def test_default_node_sequences_and_bad_lines(drive4, gateway):
    assert gateway.ask("[10] read 0x1000 0 u32") == b"[10] ERROR:105\r\n"
    assert gateway.ask("[11] set node 4") == b"[11] OK\r\n"
    assert gateway.ask("[12] read 0x1000 0 u32") == b"[12] 65938\r\n"
    assert gateway.ask("[4294967295] r 0x1000 0 u32") == b"[4294967295] 65938\r\n"
    assert gateway.ask("[13] 4 read 0x1000") == b"[13] ERROR:101\r\n"
    assert gateway.ask("4 read 0x1000 0 u32") == b"[13] ERROR:101\r\n"
    assert gateway.ask("[14] 200 start") == b"[14] ERROR:107\r\n"
    assert gateway.ask("[15] 2 4 start") == b"[15] ERROR:106\r\n"
    assert gateway.ask("[16] lss_allnodes") == b"[16] ERROR:100\r\n"
    assert gateway.ask("[17] 4 read 0x1000 0 d") == b"[17] ERROR:100\r\n"
    assert gateway.ask("[18] 4 bogus") == b"[18] ERROR:100\r\n"
    assert gateway.ask("# a comment") == b"\r\n"
    # A line longer than the gateway's buffer is a syntax error, and the next line is whole.
    assert gateway.ask("[19] 4 write 0x2000 0 vs " + "x" * 2000) == b"[18] ERROR:101\r\n"
    assert gateway.ask("[20] 4 r 0x1000 0 u32") == b"[20] 65938\r\n"
    # The same in the middle of one write: the long line has no sequence of its own.
    gateway.send("[21] 4 r 0x1000 0 u32\n[22] 4 start " + "y" * 1100 + "\n[23] 4 r 0x1000 0 x32\n")
    assert [gateway.reply() for _ in range(3)] == [b"[21] 65938\r\n", b"[21] ERROR:101\r\n",
                                                   b"[23] 0x00010192\r\n"]
    gateway.close()


def test_lines_in_one_write_answered_in_order(drive4, gateway):
    gateway.send("[1] 4 r 0x1000 0 u32\n[2] 4 w 0x203C 2 u16 40\n[3] 4 r 0x203C 2 u16\n[4] 4 start")
    assert [gateway.reply() for _ in range(3)] == [b"[1] 65938\r\n", b"[2] OK\r\n", b"[3] 40\r\n"]
    # The last line without its newline runs at the end of the input.
    gateway.proc.stdin.close()
    assert gateway.reply() == b"[4] OK\r\n"
    assert gateway.proc.wait(timeout=5) == 0


# D-IO401-IDENTITY: the first unconfigured I/O node's address.
IO_ADDRESS = b"0x00000000 0x00000191 0x00010000 0x40100081"


def test_lss_commissions_an_unconfigured_node(bus, start_daemon, tmp_path):
    start_daemon(bus, "--model", "io", "--unconfigured", 1, "--store", tmp_path / "io.store",
                 boot_ids=[])
    g = Gateway("--timeout", "200")
    try:
        assert g.ask("[1] lss_get_node") == b"[1] ERROR:103\r\n"  # nobody in configuration
        # (A slave lost to a late answer is scanned again with 100 ms a frame: 14 s at most.)
        assert g.ask("[2] _lss_fastscan 100", timeout=20) == b"[2] " + IO_ADDRESS + b"\r\n"
        assert g.ask("[3] lss_get_node") == b"[3] 0xFF\r\n"
        assert g.ask("[4] lss_inquire_addr") == b"[4] " + IO_ADDRESS + b"\r\n"
        assert g.ask("[5] lss_inquire_addr 3") == b"[5] 0x40100081\r\n"
        assert g.ask("[6] lss_set_node 9") == b"[6] OK\r\n"
        assert g.ask("[7] lss_store") == b"[7] OK\r\n"
        # A watcher of its own: `bus` has not read the fastscan's frames, more than its socket
        # buffer holds, so it would miss frames from here on.
        watcher = Bus()
        try:
            assert g.ask("[8] lss_switch_glob 0") == b"[8] OK\r\n"
            watcher.expect(0x7E5, "0400000000000000")
            watcher.expect(0x709, "00", timeout=REPLY_TIMEOUT)  # the pending node-id is active
        finally:
            watcher.close()
        assert g.ask("[9] lss_switch_sel 0 401 0x10000 0x40100081") == b"[9] OK\r\n"
        assert g.ask("[10] lss_get_node") == b"[10] 0x09\r\n"
        assert g.ask("[11] lss_switch_glob 0") == b"[11] OK\r\n"
        g.close()
    finally:
        if g.proc.poll() is None:
            g.proc.kill()


def test_help(gateway):
    gateway.send("[1] help\n")
    first = gateway.reply()
    assert first.startswith(b"[1] comaster gateway")
    text = first
    while not text.endswith(b"\r\n"):
        text += gateway.reply()
    assert b"r[ead] <index> <subindex> [<datatype>]" in text
    gateway.close()


def _connect_unix(path, deadline):
    while True:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            s.connect(path)
            return s
        except OSError:
            s.close()
            if time.monotonic() > deadline:
                raise
            time.sleep(0.02)


def _connect_tcp(port, deadline):
    while True:
        try:
            return socket.create_connection(("127.0.0.1", port), timeout=REPLY_TIMEOUT)
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.02)


def _ask(sock, line, replies=1):
    sock.sendall(line.encode() + b"\r\n")
    data = b""
    sock.settimeout(REPLY_TIMEOUT)
    while data.count(b"\r\n") < replies:
        chunk = sock.recv(256)
        assert chunk, "the gateway closed the connection"
        data += chunk
    return data


def test_tcp_and_unix_listeners_two_clients(drive4, tmp_path):
    path = str(tmp_path / "gw.sock")
    port = 30000 + os.getpid() % 20000
    proc = subprocess.Popen([COMASTER, "-i", IFACE, "gateway", "--listen", str(port), "--socket",
                             path], stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 5
        a = _connect_unix(path, deadline)
        b = _connect_tcp(port, deadline)
        # Each connection keeps its own defaults.
        assert _ask(a, "[1] set node 4") == b"[1] OK\r\n"
        assert _ask(b, "[1] read 0x1000 0 u32") == b"[1] ERROR:105\r\n"
        # Both send before either reads: one transfer at a time, each answered on its own socket.
        a.sendall(b"[2] r 0x1008 0 vs\r\n")
        b.sendall(b"[2] 4 r 0x1000 0 x32\r\n")
        assert _ask(a, "[3] r 0x203C 2 u16", 2) == b'[2] "ATV312"\r\n[3] 30\r\n'
        assert _ask(b, "[3] 4 start", 2) == b"[2] 0x00010192\r\n[3] OK\r\n"
        a.close()
        assert _ask(b, "[4] 4 r 0x1000 0 u32") == b"[4] 65938\r\n"
        b.close()
    finally:
        proc.send_signal(signal.SIGTERM)
        assert proc.wait(timeout=5) == 0, proc.stderr.read()
    assert not os.path.exists(path)
