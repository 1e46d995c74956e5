# SPDX-License-Identifier: Apache-2.0
"""TIME (1012h, docs/time.md) on real SocketCAN: comaster as the producer, once and every PERIOD
ms on a fixed grid, the I/O node of atv312d as the consumer showing the time it received in its
state, and cotrace decoding the frame as a date and time."""

import calendar
import json
import os
import signal
import subprocess
import time

import pytest

from conftest import IFACE, NMT_STOP, ROOT, Frame
from test_control import ctl

IO = 10
COMASTER = os.environ.get("COMASTER") or str(ROOT / "build" / "apps" / "comaster" / "comaster")
COTRACE = os.environ.get("COTRACE") or str(ROOT / "build" / "apps" / "cotrace" / "cotrace")
SDO_ABORT_VALUE_RANGE = 0x06090030


@pytest.fixture
def io(bus, start_daemon, tmp_path):
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", IO, "--model", "io", "--control", sock)
    return sock


def io_time(sock):
    status, reply = ctl(sock, "--json", "state", IO)
    assert status == 0, reply
    return json.loads(reply)["nodes"][0]["time"]


def wait_for_time(sock, want, timeout=2.0):
    deadline = time.monotonic() + timeout
    while io_time(sock) != want:
        assert time.monotonic() < deadline, f"the I/O node's time is {io_time(sock)}, not {want}"
        time.sleep(0.02)


def decode(data):
    """TIME_OF_DAY: 28 bits of ms after midnight, days since 1984-01-01, as comaster prints it."""
    ms = int.from_bytes(data[0:4], "little") & 0x0FFFFFFF
    days = int.from_bytes(data[4:6], "little")
    t = time.gmtime(441763200 + days * 86400 + ms // 1000)
    return time.strftime("%Y-%m-%d %H:%M:%S", t) + f".{ms % 1000:03d}"


def test_io_node_consumes_the_time_comaster_sends(bus, io):
    assert bus.sdo_read(IO, 0x1012, 0) == 0x80000100
    assert io_time(io) is None
    p = subprocess.run([COMASTER, "-i", IFACE, "time"], capture_output=True, text=True, timeout=10)
    assert p.returncode == 0, p.stderr
    frame = bus.expect(0x100)
    assert len(frame.data) == 6 and frame.data[3] & 0xF0 == 0
    assert p.stdout == f"TIME {decode(frame.data)}\n"
    host = time.time()
    sent = calendar.timegm(time.strptime(decode(frame.data)[:19], "%Y-%m-%d %H:%M:%S"))
    assert abs(sent - host) < 5, "comaster sends the host's clock in UTC"
    wait_for_time(io, decode(frame.data))
    status, reply = ctl(io, "state", IO)
    assert reply.endswith(f", time {decode(frame.data)}"), reply


def test_a_time_of_our_own_and_the_1012h_rules(bus, io):
    # 2026-11-29 12:34:56.789: 45 296 789 ms (02B32C95h) of day 15673 (3D39h).
    bus.send(Frame(0x100, bytes.fromhex("952CB302393D")))
    wait_for_time(io, "2026-11-29 12:34:56.789")
    bus.send(Frame(0x100, bytes.fromhex("952CB30239")))  # 5 bytes: dropped
    bus.nmt(NMT_STOP, IO)  # Stopped: TIME not consumed
    bus.send(Frame(0x100, bytes.fromhex("000000000000")))
    time.sleep(0.2)
    assert io_time(io) == "2026-11-29 12:34:56.789"
    bus.nmt(0x80, IO)
    # CiA 301 7.5.2.12: no restricted CAN-ID, no new CAN-ID while consumed.
    assert bus.sdo_abort_code(IO, "2312100001010080") == SDO_ABORT_VALUE_RANGE
    assert bus.sdo_abort_code(IO, "2312100081010080") == SDO_ABORT_VALUE_RANGE
    bus.sdo_write(IO, 0x1012, 0, 0x00000181, 4)
    bus.sdo_write(IO, 0x1012, 0, 0x80000181, 4)
    bus.send(Frame(0x181, bytes.fromhex("000000000000")))
    wait_for_time(io, "1984-01-01 00:00:00.000")


def test_comaster_sends_time_every_period_until_sigint(bus):
    p = subprocess.Popen([COMASTER, "-i", IFACE, "time", "100"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        first = bus.expect(0x100, timeout=2.0)
        start = time.monotonic()
        for _ in range(5):
            bus.expect(0x100, timeout=0.5)
        elapsed = time.monotonic() - start
    finally:
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=5)
    assert p.returncode == 0, err
    # Five periods of 100 ms on a fixed grid; the bus reader's own delay is the margin.
    assert 0.4 < elapsed < 0.9, elapsed
    lines = out.splitlines()
    assert len(lines) >= 6 and lines[0] == f"TIME {decode(first.data)}"


def test_cotrace_decodes_time_as_a_date(tmp_path):
    log = tmp_path / "time.log"
    log.write_text("(1764419696.789000) vcan0 100#952CB302393D\n")
    p = subprocess.run([COTRACE, str(log)], capture_output=True, text=True, timeout=10)
    assert p.returncode == 0, p.stderr
    assert "TIME 2026-11-29 12:34:56.789" in p.stdout, p.stdout
