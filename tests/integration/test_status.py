# SPDX-License-Identifier: Apache-2.0
"""The status surface on real SocketCAN: `atv312d --status FILE` rewrites FILE once a second with the
CAN controller state, the frame counters and one line per drive, replaced atomically (every read is
a whole file); SIGUSR1 writes the same to the log."""

import re
import signal
import time

from conftest import BOOT_TIMEOUT

NODE = 4

COUNTERS = re.compile(
    r"^vcan0: CAN error-active; frames received (\d+), sent (\d+), dropped 0, lost while down 0, "
    r"error frames 0, bus-offs 0; wake-ups (\d+), sendmmsg calls (\d+)$"
)


def read_until(path, predicate, timeout):
    """The first whole content of path for which predicate holds, polled until the deadline."""
    deadline = time.monotonic() + timeout
    text = None
    while time.monotonic() < deadline:
        if path.exists():
            text = path.read_text()
            if predicate(text):
                return text
        time.sleep(0.02)
    raise AssertionError(f"{path}: no matching content within {timeout} s; last: {text!r}")


def test_status_file_every_second(bus, start_daemon, tmp_path):
    path = tmp_path / "status"
    start_daemon(bus, "--node-id", "4-5", "--status", path)
    bus.nmt(0x01, 5)
    text = read_until(path, lambda t: "node 5: nmt Operational" in t, 2.5)
    lines = text.splitlines()
    assert len(lines) == 3, text
    m = COUNTERS.match(lines[0])
    assert m, lines[0]
    assert int(m.group(1)) >= 1  # the NMT start
    assert 1 <= int(m.group(4)) <= int(m.group(2)), lines[0]  # a write call carries 1 frame or more
    # The NMT command is routed to both drives; each sent its boot-up (and node 5 TPDOs since).
    assert lines[1] == (
        "node 4: nmt Pre-operational, cia402 Switch on disabled, statusword 0640, speed 0 rpm, "
        "current 0.0 A, torque 0 %, display nSt, RUN blinking, ERR off, fault none, "
        "frames received 1, sent 1, dropped 0, SDO requests 0, SDO aborts 0, EMCY 0"
    )
    assert lines[2].startswith("node 5: nmt Operational, cia402 Switch on disabled,"), lines[2]
    assert "RUN on, ERR off, fault none, frames received 1, sent " in lines[2], lines[2]
    # Rewritten about once a second, never seen half written; no temporary file left behind.
    rewrites, last, deadline = 0, path.stat().st_mtime_ns, time.monotonic() + 2.5
    while time.monotonic() < deadline:
        text = path.read_text()
        assert len(text.splitlines()) == 3 and text.endswith("\n"), repr(text)
        mtime = path.stat().st_mtime_ns
        rewrites += mtime != last
        last = mtime
        time.sleep(0.01)
    assert 2 <= rewrites <= 3, rewrites
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith("status")) in (["status"], ["status", "status.tmp"])


def test_sigusr1_logs_the_status(bus, start_daemon):
    d = start_daemon(bus, "--node-id", NODE)
    d.proc.send_signal(signal.SIGUSR1)
    deadline = time.monotonic() + BOOT_TIMEOUT
    while "status: node 4: nmt Pre-operational" not in d.log():
        assert time.monotonic() < deadline, d.log()
        time.sleep(0.02)
    log = d.log()
    assert re.search(r"status: vcan0: CAN error-active; frames received \d+, sent 1,", log), log
    assert d.running()
