# SPDX-License-Identifier: Apache-2.0
"""atv312d under a service manager (systemd's Type=notify, sd_notify(3)): READY=1 on $NOTIFY_SOCKET
only once every drive's boot-up is on the bus (on DeviceNet: the duplicate MAC ID checks over),
never when the interface cannot be opened, and STOPPING=1 on SIGTERM (docs/atv312d.md, "systemd")."""

import socket
import struct
import subprocess
import time

import pytest

from conftest import BOOT_TIMEOUT, EX_OK, IFACE, ONLINE_TIMEOUT, daemon_path

EX_UNAVAILABLE = 69
CHECK_25 = 0x4CF  # the duplicate MAC ID check request of MAC ID 25 (Group 2, message 7)
SO_TIMESTAMP = 29  # asm-generic/socket.h (Python's socket module does not name it)
TIMEVAL = struct.Struct("qq")  # struct timeval of a 64-bit kernel: seconds, microseconds


class NotifySocket:
    """The service manager's end: a datagram AF_UNIX socket whose messages carry the kernel's
    receive time (SO_TIMESTAMP, CLOCK_REALTIME like the CAN frames' timestamps)."""

    def __init__(self, address):
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, SO_TIMESTAMP, 1)
        self.sock.bind(address)

    def receive(self, timeout):
        """(text, kernel time) of the next message, or None when none comes within timeout."""
        self.sock.settimeout(timeout)
        try:
            data, ancillary, _, _ = self.sock.recvmsg(4096, socket.CMSG_SPACE(TIMEVAL.size))
        except socket.timeout:
            return None
        stamp = None
        for level, kind, value in ancillary:
            if level == socket.SOL_SOCKET and kind == SO_TIMESTAMP:  # SCM_TIMESTAMP
                seconds, micros = TIMEVAL.unpack(value[: TIMEVAL.size])
                stamp = seconds + micros / 1e6
        assert stamp is not None, "no SO_TIMESTAMP on the message"
        return data.decode(), stamp

    def close(self):
        self.sock.close()


@pytest.fixture(params=["path", "abstract"])
def notify(request, tmp_path, monkeypatch):
    if request.param == "path":
        address = str(tmp_path / "notify")
        monkeypatch.setenv("NOTIFY_SOCKET", address)
    else:
        name = f"atv312d-test-{time.monotonic_ns()}"
        address = "\0" + name
        monkeypatch.setenv("NOTIFY_SOCKET", "@" + name)
    n = NotifySocket(address)
    yield n
    n.close()


def test_ready_after_every_boot_up_is_on_the_bus_then_stopping(bus, start_daemon, notify):
    d = start_daemon(bus, "--node-id", "4-6")
    ready = notify.receive(BOOT_TIMEOUT)
    assert ready is not None, d.log()
    text, when = ready
    assert text == f"READY=1\nSTATUS=3 drive(s) booted on {IFACE}"
    boot_ups = [f for f in bus.seen if f.can_id in (0x704, 0x705, 0x706) and f.data == b"\x00"]
    assert len(boot_ups) == 3, bus.seen
    assert max(f.timestamp for f in boot_ups) <= when, (boot_ups, when)
    assert d.stop() == EX_OK
    assert notify.receive(BOOT_TIMEOUT)[0] == "STOPPING=1"
    assert notify.receive(0.1) is None


def ip_link(state):
    subprocess.run(["ip", "link", "set", IFACE, state], check=True, timeout=5)


def test_interface_down_at_start_ready_only_after_it_came_up(bus, start_daemon, notify):
    ip_link("down")
    try:
        d = start_daemon(bus, "--node-id", 4, boot_ids=[])
        assert notify.receive(0.5) is None, d.log()  # no boot-up could leave: not ready
    finally:
        ip_link("up")
    bus.expect(0x704, "00", timeout=BOOT_TIMEOUT)
    text, when = notify.receive(BOOT_TIMEOUT)
    assert text == f"READY=1\nSTATUS=1 drive(s) booted on {IFACE}"
    boot_up = [f for f in bus.seen if f.can_id == 0x704][-1]
    assert boot_up.timestamp <= when


def test_never_ready_when_the_interface_cannot_be_opened(notify):
    run = subprocess.run([daemon_path(), "vcan9", "--node-id", "4"], capture_output=True, timeout=10)
    assert run.returncode == EX_UNAVAILABLE, run
    assert notify.receive(0.2) is None


def test_devicenet_ready_once_the_duplicate_mac_id_check_is_over(bus, start_daemon, notify):
    d = start_daemon(bus, "--devicenet", "--mac-id", 25, boot_ids=[])
    checks = bus.collect_n(CHECK_25, 2, timeout=ONLINE_TIMEOUT)
    text, when = notify.receive(ONLINE_TIMEOUT)
    assert text == f"READY=1\nSTATUS=1 drive(s) on DeviceNet on {IFACE}: 1 online, 0 faulted", d.log()
    # Online one second after the second request went unanswered (docs/devicenet.md).
    assert when - checks[1].timestamp >= 0.99, (checks, when)
