# SPDX-License-Identifier: Apache-2.0
"""cotrace -i on a live vcan: frames sent on the bus come out as the same lines as from a log
(after the timestamp), it stops cleanly on SIGTERM, and a missing interface is a clear error."""

import os
import queue
import re
import signal
import subprocess
import threading
import time

import pytest

from conftest import IFACE, MARKER_ID, ROOT, Frame

COTRACE = os.environ.get("COTRACE") or str(ROOT / "build" / "apps" / "cotrace" / "cotrace")
EX_UNAVAILABLE = 69
LINE = re.compile(r"^\((\d{10}\.\d{6})\) (.*)$")


class Cotrace:
    def __init__(self, *args):
        self.proc = subprocess.Popen([COTRACE, *args], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        self.lines = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line)

    def next_line(self, timeout=2.0):
        """The next line without its timestamp, which must be the time of day."""
        try:
            line = self.lines.get(timeout=timeout)
        except queue.Empty:
            pytest.fail(f"cotrace printed nothing within {timeout} s")
        match = LINE.match(line)
        assert match, f"not a cotrace line: {line!r}"
        assert abs(float(match.group(1)) - time.time()) < 5.0, f"wrong timestamp: {line!r}"
        return match.group(2)

    def wait_listening(self, bus):
        """Sends the marker until cotrace shows it: from then on it sees every frame."""
        deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline:
            bus.send(Frame(MARKER_ID, b"\x01"))
            try:
                line = self.lines.get(timeout=0.2)
            except queue.Empty:
                continue
            assert LINE.match(line).group(2) == \
                f"{IFACE} 7FF#01                COB-ID 0x7FF: no predefined meaning"
            while not self.lines.empty():  # markers sent before the first one was shown
                assert "7FF#01" in self.lines.get_nowait()
            return
        pytest.fail("cotrace -i showed no frame within 5 s")

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        return self.proc.wait(timeout=5)


def test_live_frames_decoded(bus):
    tracer = Cotrace("-i", IFACE, "--eds", str(ROOT / "eds" / "ATV312.eds"), "--node", "4")
    try:
        tracer.wait_listening(bus)
        expected = [
            ("000#0104", "NMT Start remote node, node 4"),
            ("604#4008100000000000", "SDO 4 request: upload 1008:00 Manufacturer device name"),
            ("584#4108100006000000",
             "SDO 4 reply: upload 1008:00 Manufacturer device name, 6 bytes, segmented"),
            ("604#6000000000000000", "SDO 4 request: upload segment, toggle 0"),
            ("584#0341545633313200", "SDO 4 reply: upload segment, toggle 0, 6 bytes: \"ATV312\", "
                                     "last: 1008:00 Manufacturer device name = \"ATV312\" (6 bytes)"),
            ("704#R", "guarding request, node 4"),
            ("704#85", "guarding reply, node 4: Operational, toggle 1"),
            ("084#3081010000000000", "EMCY node 4: 0x8130 life guard error or heartbeat error, "
                                     "error register 0x01 (generic), manufacturer "
                                     "bytes 00 00 00 00 00"),
            ("284#27062C01", "TPDO6 node 4: 6041:00 Statusword (ETAD) = 0x0627 Operation enabled, "
                             "6044:00 vl velocity actual value (RFRD) = 300"),
            ("080#", "SYNC"),
        ]
        for frame, meaning in expected:
            bus.send(frame)
            assert tracer.next_line() == f"{IFACE} {frame:<20}  {meaning}"
        assert tracer.stop() == 0
        assert tracer.proc.stderr.read() == ""
    finally:
        if tracer.proc.poll() is None:
            tracer.proc.kill()
            tracer.proc.wait()


def test_missing_interface():
    result = subprocess.run([COTRACE, "-i", "nosuch0"], capture_output=True, text=True, timeout=10)
    assert result.returncode == EX_UNAVAILABLE
    assert result.stdout == ""
    assert result.stderr == ("cotrace: error: no network interface 'nosuch0': give one with -i IFACE (list "
                             "them: ip link show type can, or type vcan)\n")
