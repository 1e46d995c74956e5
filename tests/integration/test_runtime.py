# SPDX-License-Identifier: Apache-2.0
"""The daemon as a Linux process: trace file, signals, tickless idle, interface down/up, command-line
errors (sysexits.h) and parameter storage (docs/decisions.md, D-ERRORS, D-STORE-FILE)."""

import os
import re
import signal
import socket
import subprocess
import time

import pytest

from conftest import BOOT_TIMEOUT, EX_OK, EX_USAGE, IFACE, Frame, cansend, daemon_path

NODE = 4
EX_UNAVAILABLE = 69  # sysexits.h: interface or CAN support missing
SAVE = 0x65766173  # "save" (CiA 301 1010h)
LOAD = 0x64616F6C  # "load" (CiA 301 1011h)


def test_trace_file_is_in_candump_log_format(bus, start_daemon, tmp_path):
    trace = tmp_path / "trace.log"
    d = start_daemon(bus, "--node-id", NODE, "--trace", trace)
    bus.sdo_read(NODE, 0x1000, 0)
    assert d.stop() == EX_OK
    lines = trace.read_text().splitlines()
    line_format = re.compile(rf"^\(\d{{10}}\.\d{{6}}\) {IFACE} [0-9A-F]{{3}}#(R\d?|([0-9A-F]{{2}})*)$")
    assert lines, "empty trace"
    assert [l for l in lines if not line_format.match(l)] == []
    frames = [l.split(" ", 2)[2] for l in lines]
    assert "704#00" in frames  # out
    assert "604#4000100000000000" in frames  # in
    assert "584#4300100092010100" in frames  # out
    stamps = [float(l[1:18]) for l in lines]
    assert stamps == sorted(stamps)
    assert abs(stamps[0] - time.time()) < 60


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_signal_exits_0(drive, sig):
    assert drive.stop(sig, timeout=2.0) == EX_OK


def test_idle_daemon_makes_almost_no_wakeups(bus, drive):
    # Pre-operational, heartbeat off: nothing is due, so the loop must sleep (tickless core,
    # timerfd armed to the next deadline only).
    bus.expect_none(0x704, 0.2)
    before = drive.proc_status("voluntary_ctxt_switches")
    frames = bus.collect(1.0)
    after = drive.proc_status("voluntary_ctxt_switches")
    assert frames == [], "the bus was not idle"
    assert after - before <= 2, f"{after - before} wake-ups in 1 s of idle"


def test_timer_that_fired_with_nothing_left_due_is_disarmed(bus, drive):
    # A segmented upload of 1008h left unanswered: the SDO timeout (1 s) fires the timer, and
    # then nothing is due. The timerfd is not read, so it must be disarmed (timerfd_settime resets
    # its expiration count), or epoll would report it again at once, forever.
    reply = bus.request(Frame(0x604, bytes.fromhex("4008100000000000")), 0x584)
    assert reply.data[:4] == bytes.fromhex("41081000"), reply
    abort = bus.expect(0x584, timeout=2.0)
    assert abort.data == bytes.fromhex("8008100000000405"), abort  # 0x05040000: SDO timeout
    # A loop that spins on a readable descriptor never sleeps, so it makes no context switch:
    # count its system calls instead.
    calls = strace_counts(drive.pid, 1.0)
    assert calls.get("epoll_wait", 0) <= 1, f"system calls in 1 s after the last deadline: {calls}"


def strace_counts(pid, seconds):
    """{system call: calls} of a process over `seconds` (strace -c; nothing for a sleeping one)."""
    run = subprocess.run(["timeout", "-s", "INT", str(seconds), "strace", "-c", "-p", str(pid)],
                         capture_output=True, text=True)
    assert "attached" in run.stderr, f"strace -p {pid} failed: {run.stderr}"
    calls = {}
    for line in run.stderr.splitlines():
        fields = line.split()
        if len(fields) >= 5 and fields[0][0].isdigit() and fields[-1] != "total":
            calls[fields[-1]] = int(fields[3])
    return calls


def test_timer_wake_up_makes_four_system_calls(bus, drive):
    # A 20 ms heartbeat and nothing else: each wake-up is the timer's. It waits (epoll_wait),
    # reads the clock, sends the heartbeat (a lone frame: send, which strace names sendto) and
    # arms the next deadline
    # (timerfd_settime); the timerfd is never read (docs/runtime.md).
    bus.sdo_write(NODE, 0x1017, 0, 20, 2)
    bus.expect(0x704, "7F")
    calls = strace_counts(drive.pid, 1.0)
    wakeups = calls.get("epoll_wait", 0)
    assert wakeups >= 25, calls
    assert "read" not in calls, calls
    assert abs(calls.get("timerfd_settime", 0) - wakeups) <= 2, calls
    assert "sendmmsg" not in calls, calls
    assert abs(calls.get("sendto", 0) - wakeups) <= 2, calls
    assert sum(calls.values()) <= 4 * wakeups + 4, calls


def test_operational_wakeups_follow_the_event_timer(bus, drive):
    bus.nmt(0x01, NODE)
    bus.expect(0x184)
    before = drive.proc_status("voluntary_ctxt_switches")
    frames = bus.collect(1.0, 0x184)  # TPDO1 event timer 100 ms: 10 frames
    after = drive.proc_status("voluntary_ctxt_switches")
    assert 9 <= len(frames) <= 11
    assert after - before <= len(frames) + 3, f"{after - before} wake-ups for {len(frames)} TPDOs"


def ip_link(state):
    subprocess.run(["ip", "link", "set", IFACE, state], check=True, timeout=5)


def cpu_seconds(pid):
    """User + system CPU time of a process so far, from /proc/<pid>/stat (clock ticks)."""
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def test_interface_down_for_2_s_no_spinning_then_boot_up_and_heartbeat_within_1_s(bus, start_daemon, tmp_path):
    # The heartbeat is a stored communication parameter, so it resumes after the reset of
    # communication that follows the interface's return (docs/atv312d.md).
    store = tmp_path / "atv312.store"
    drive = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x1017, 0, 100, 2)
    bus.sdo_write(NODE, 0x1010, 2, SAVE, 4)
    bus.expect(0x704, "7F")
    try:
        ip_link("down")
        cpu_before, wakeups_before = cpu_seconds(drive.pid), drive.proc_status("voluntary_ctxt_switches")
        down = time.monotonic()
        # Two seconds without its interface: the daemon lives on, and sleeps (nothing polls the
        # socket; only its heartbeat timer, 20 times, and the netlink socket wake it).
        while time.monotonic() - down < 2.0:
            assert drive.running(), f"atv312d exited {drive.proc.returncode} on link down:\n{drive.log()}"
            time.sleep(0.05)
        cpu = cpu_seconds(drive.pid) - cpu_before
        wakeups = drive.proc_status("voluntary_ctxt_switches") - wakeups_before
    finally:
        up = time.time()  # the frames' kernel timestamps are CLOCK_REALTIME
        ip_link("up")
    assert cpu <= 0.1, f"{cpu:.2f} s of CPU in 2 s with the interface down: spinning"
    assert wakeups <= 20 + 10, f"{wakeups} wake-ups in 2 s with the interface down"
    boot_up = bus.expect(0x704, "00", timeout=1.0)
    heartbeat = bus.expect(0x704, "7F", timeout=1.0)
    assert boot_up.timestamp - up <= 1.0, f"boot-up {boot_up.timestamp - up:.3f} s after the link came up"
    assert heartbeat.timestamp - up <= 1.0, f"heartbeat {heartbeat.timestamp - up:.3f} s after the link came up"
    assert bus.sdo_read(NODE, 0x1000, 0) == 0x00010192
    assert "is down" in drive.log() and "is up: restarting communication" in drive.log(), drive.log()
    assert drive.running()


def run_cli(*args):
    return subprocess.run([daemon_path(), *map(str, args)], capture_output=True, text=True, timeout=BOOT_TIMEOUT)


@pytest.mark.parametrize(
    "args, words",
    [([], ["--node-id"]),
     ([IFACE], ["--node-id"]),
     ([IFACE, "--node-id", "0"], ["1..127"]),
     ([IFACE, "--node-id", "128"], ["1..127"]),
     ([IFACE, "--node-id", "four"], ["four"]),
     ([IFACE, "--node-id", "4", "--bogus"], ["--bogus"]),
     ([IFACE, "--node-id", "4", "--log-level", "loud"], ["loud"]),
     ([IFACE, "--node-id", "4", "--model", "atv99"], ["unknown model 'atv99'", "atv312"]),
     ([IFACE, "--model", "atv312", "--node-id", "4"], ["no --node-id before it"])],
    ids=["nothing", "no-node-id", "node-id-0", "node-id-128", "node-id-text", "unknown-option", "bad-log-level",
         "unknown-model", "model-before-node-id"],
)
def test_bad_command_line_exits_64_with_a_message(args, words):
    result = run_cli(*args)
    assert result.returncode == EX_USAGE, result.stderr
    for word in words:
        assert word.lower() in result.stderr.lower(), result.stderr


def test_missing_interface_says_how_to_create_it():
    result = run_cli("nosuch0", "--node-id", NODE)
    assert result.returncode == EX_UNAVAILABLE, result
    assert "nosuch0" in result.stderr and "ip link add" in result.stderr, result.stderr


def test_help_and_version_exit_0():
    shown = run_cli("--help")
    assert shown.returncode == EX_OK and "--node-id" in shown.stdout
    assert "--model" in shown.stdout and "atv312" in shown.stdout
    version = run_cli("--version")
    assert version.returncode == EX_OK and re.search(r"\d+\.\d+", version.stdout)


def test_store_keeps_saved_parameters_across_restart(bus, start_daemon, tmp_path):
    store = tmp_path / "atv312.store"
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x203C, 2, 77, 2)
    bus.sdo_write(NODE, 0x1010, 1, SAVE, 4)
    bus.sdo_write(NODE, 0x203C, 2, 88, 2)  # not saved
    assert d.stop() == EX_OK
    assert store.exists()
    start_daemon(bus, "--node-id", NODE, "--store", store)
    assert bus.sdo_read(NODE, 0x203C, 2) == 77


def test_restore_defaults_takes_effect_after_restart(bus, start_daemon, tmp_path):
    store = tmp_path / "atv312.store"
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x203C, 2, 77, 2)
    bus.sdo_write(NODE, 0x1010, 1, SAVE, 4)
    bus.sdo_write(NODE, 0x1011, 1, LOAD, 4)
    assert bus.sdo_read(NODE, 0x203C, 2) == 77  # CiA 301: defaults apply at the next reset
    assert d.stop() == EX_OK
    start_daemon(bus, "--node-id", NODE, "--store", store)
    assert bus.sdo_read(NODE, 0x203C, 2) == 30


def test_corrupt_store_file_is_reported_and_ignored(bus, start_daemon, tmp_path):
    store = tmp_path / "atv312.store"
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x203C, 2, 77, 2)
    bus.sdo_write(NODE, 0x1010, 1, SAVE, 4)
    assert d.stop() == EX_OK
    content = bytearray(store.read_bytes())
    content[len(content) // 2] ^= 0xFF
    store.write_bytes(bytes(content))
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    assert bus.sdo_read(NODE, 0x203C, 2) == 30  # defaults, nothing half-loaded
    assert str(store.name) in d.log(), f"the bad store file is not reported:\n{d.log()}"


def test_store_keeps_each_drive_of_a_bench_apart(bus, start_daemon, tmp_path):
    store = tmp_path / "bench.store"
    d = start_daemon(bus, "--node-id", "4-5", "--store", store)
    bus.sdo_write(4, 0x203C, 2, 44, 2)
    bus.sdo_write(5, 0x203C, 2, 55, 2)
    bus.sdo_write(4, 0x1010, 1, SAVE, 4)  # only drive 4 saves
    assert d.stop() == EX_OK
    start_daemon(bus, "--node-id", "4-5", "--store", store)
    assert bus.sdo_read(4, 0x203C, 2) == 44
    assert bus.sdo_read(5, 0x203C, 2) == 30


# ---- CAN error frames (docs/runtime.md "Error frames") -------------------------------------------
# On vcan an error frame written by a process reaches every socket whose error mask matches it,
# as if a controller driver had reported it: the daemon cannot tell the difference.
CAN_ERR_FLAG = 0x20000000
CAN_ERR_CRTL, CAN_ERR_BUSOFF, CAN_ERR_RESTARTED = 0x004, 0x040, 0x100  # linux/can/error.h classes
CRTL_RX_OVERFLOW, CRTL_RX_WARNING, CRTL_TX_WARNING, CRTL_TX_PASSIVE, CRTL_ACTIVE = 0x01, 0x04, 0x08, 0x20, 0x40  # data[1]
EMCY = 0x080 + NODE
COMMUNICATION_ERROR_REGISTER = 0x01  # 1001h: the ATV312 manual's "=1 (error)", no class bit


def send_error_frame(error_class, controller_status=0):
    cansend(f"{CAN_ERR_FLAG | error_class:08X}#00{controller_status:02X}000000000000")


def emcy(code, register):
    return code.to_bytes(2, "little") + bytes([register]) + bytes(5)


@pytest.mark.parametrize(
    "raise_it,clear_it,code",
    [
        ((CAN_ERR_BUSOFF, 0), (CAN_ERR_RESTARTED, 0), 0x8140),
        ((CAN_ERR_CRTL, CRTL_TX_PASSIVE), (CAN_ERR_CRTL, CRTL_ACTIVE), 0x8120),
    ],
    ids=["bus-off then restarted", "error passive then active"],
)
def test_error_frames_raise_and_clear_an_emergency(bus, drive, raise_it, clear_it, code):
    send_error_frame(*raise_it)
    bus.expect(EMCY, emcy(code, COMMUNICATION_ERROR_REGISTER))
    assert bus.sdo_read(NODE, 0x1001, 0) == COMMUNICATION_ERROR_REGISTER
    assert bus.sdo_read(NODE, 0x1003, 1) == code  # newest entry of the error history
    send_error_frame(*raise_it)  # the same condition again is not news
    bus.expect_none(EMCY, 0.2)
    send_error_frame(*clear_it)
    bus.expect(EMCY, emcy(0x0000, 0x00))
    assert bus.sdo_read(NODE, 0x1001, 0) == 0
    assert drive.running()


def test_controller_overflow_is_an_event_kept_in_the_error_history(bus, drive):
    # Frames were lost once: the condition ends as soon as a frame is written again (here the EMCY
    # itself), so the emergency and its reset come together and the history keeps the code.
    send_error_frame(CAN_ERR_CRTL, CRTL_RX_OVERFLOW)
    bus.expect(EMCY, emcy(0x8110, COMMUNICATION_ERROR_REGISTER))
    bus.expect(EMCY, emcy(0x0000, 0x00))
    assert bus.sdo_read(NODE, 0x1003, 1) == 0x8110


# ---- transmit back-pressure (docs/runtime.md "Transmit path and back-pressure") -----------------
# A plug queueing discipline on vcan0 holds every frame written after it is installed, up to its
# byte limit, then refuses the rest with ENOBUFS: the state of a CAN interface whose queue is full.
TXQ_CAPACITY = 256  # co_linux_loop_config_t.txq_capacity as atv312d sets it
PLUG_LIMIT = 8 * 16  # bytes: eight struct can_frame
SO_RCVBUFFORCE = 33  # asm-generic/socket.h (root may exceed net.core.rmem_max)


def tc_plug(action, *options):
    """`tc qdisc add|change dev vcan0 root plug OPTIONS...`, or `del` to remove it."""
    plug = ["plug", *options] if action != "del" else []
    subprocess.run(["tc", "qdisc", action, "dev", IFACE, "root", *plug], check=True, timeout=5)


def wait_for_log(daemon, text, timeout):
    deadline = time.monotonic() + timeout
    while text not in daemon.log():
        assert time.monotonic() < deadline, f"no {text!r} in the log within {timeout} s:\n{daemon.log()}"
        time.sleep(0.01)


def stopped_stats(daemon):
    """The counters of the daemon's last log line: {'wake-ups': n, 'sent': n, 'dropped': n, ...}."""
    line = daemon.log().strip().splitlines()[-1]
    return {name: int(n) for n, name in re.findall(r"(\d+) (wake-ups|sent|dropped)", line)}


def test_transmit_back_pressure_queues_in_order_then_drops_and_reports_the_overrun(bus, drive):
    started = time.monotonic()
    # The released queue arrives as one burst, more than a default receive buffer holds.
    bus.bus.socket.setsockopt(socket.SOL_SOCKET, SO_RCVBUFFORCE, 4 << 20)
    bus.sdo_write(NODE, 0x1017, 0, 1, 2)  # a heartbeat every 1 ms fills the queue in 0.26 s
    bus.expect(0x704, "7F")
    tc_plug("add", "limit", str(PLUG_LIMIT))
    try:
        wait_for_log(drive, "transmit queue full", timeout=5.0)
        tc_plug("change", "release_indefinite")
        released = bus.mark()
        emcy_frame = bus.expect(EMCY, emcy(0x8110, COMMUNICATION_ERROR_REGISTER), timeout=5.0)
    finally:
        tc_plug("del")
    before = bus.seen[released:-1]
    # The whole queue went out, in order, before the EMCY queued behind it; nothing else got in.
    assert len(before) >= TXQ_CAPACITY, f"only {len(before)} frames before {emcy_frame}"
    assert {str(f) for f in before} == {"704#7F"}
    bus.expect(EMCY, emcy(0x0000, 0x00))  # the queue is empty again
    bus.sdo_write(NODE, 0x1017, 0, 0, 2)
    assert bus.sdo_read(NODE, 0x1003, 1) == 0x8110
    assert drive.stop() == EX_OK
    lived_ms = (time.monotonic() - started) * 1000
    stats = stopped_stats(drive)
    assert stats["dropped"] > 0
    # Refused writes are retried every 1 ms, not in a busy loop: at most a heartbeat and a retry
    # per millisecond (a busy loop makes several wake-ups per millisecond even in User-Mode Linux).
    assert stats["wake-ups"] <= 2 * lived_ms + 50, f"{stats['wake-ups']} wake-ups in {lived_ms:.0f} ms"


def test_warning_level_is_logged_without_an_emergency(bus, drive):
    send_error_frame(CAN_ERR_CRTL, CRTL_RX_WARNING)
    bus.expect_none(EMCY, 0.3)
    assert bus.sdo_read(NODE, 0x1001, 0) == 0
    assert drive.stop() == EX_OK
    assert "error warning level" in drive.log()


def status_line(daemon, expected_start, timeout=BOOT_TIMEOUT):
    """The status surface's first line as SIGUSR1 logs it, once it starts with expected_start."""
    deadline = time.monotonic() + timeout
    while True:
        daemon.proc.send_signal(signal.SIGUSR1)
        time.sleep(0.05)
        lines = [l for l in daemon.log().splitlines() if f"status: {IFACE}: CAN" in l]
        if lines and lines[-1].split("status: ", 1)[1].startswith(expected_start):
            return lines[-1].split("status: ", 1)[1]
        assert time.monotonic() < deadline, f"no status line starting {expected_start!r}:\n{daemon.log()}"


def test_status_tells_warning_from_passive_and_counts_bus_offs(bus, start_daemon, tmp_path):
    sock = tmp_path / "ctl"
    d = start_daemon(bus, "--node-id", NODE, "--control", sock)
    send_error_frame(CAN_ERR_CRTL, CRTL_TX_WARNING)
    line = status_line(d, "vcan0: CAN error-warning;")
    assert ", error frames 1, bus-offs 0;" in line, line
    send_error_frame(CAN_ERR_CRTL, CRTL_TX_PASSIVE)
    bus.expect(EMCY, emcy(0x8120, COMMUNICATION_ERROR_REGISTER))
    status_line(d, "vcan0: CAN error-passive;")
    send_error_frame(CAN_ERR_CRTL, CRTL_TX_WARNING)  # back under the passive limit
    bus.expect(EMCY, emcy(0x0000, 0x00))
    status_line(d, "vcan0: CAN error-warning;")
    for _ in range(2):
        send_error_frame(CAN_ERR_BUSOFF)
        bus.expect(EMCY, emcy(0x8140, COMMUNICATION_ERROR_REGISTER))
        send_error_frame(CAN_ERR_RESTARTED)
        bus.expect(EMCY, emcy(0x0000, 0x00))
    line = status_line(d, "vcan0: CAN error-active;")
    assert ", error frames 7, bus-offs 2;" in line, line
    send_error_frame(CAN_ERR_CRTL, CRTL_RX_WARNING)
    status_line(d, "vcan0: CAN error-warning;")
    reply = subprocess.run([daemon_path(), "ctl", str(sock), "--json", "state"],
                           capture_output=True, text=True, timeout=5)
    assert reply.returncode == 0, reply
    assert reply.stdout.startswith('{"ok":true,"can":{"state":"error-warning","bus_offs":2},"nodes":[{"node":4,'), reply.stdout
    assert '"err_led":"single flash"' in reply.stdout, reply.stdout
    send_error_frame(CAN_ERR_CRTL, CRTL_ACTIVE)
    status_line(d, "vcan0: CAN error-active;")
