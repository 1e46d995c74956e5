"""The daemon as a Linux process: trace file, signals, tickless idle, interface down/up, command-line
errors (sysexits.h) and parameter storage (SPEC.md sections 1.2 and 3)."""

import re
import signal
import subprocess
import time

import pytest

from conftest import BOOT_TIMEOUT, EX_OK, EX_USAGE, IFACE, daemon_path

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


def test_interface_down_and_up_keeps_the_daemon_running(bus, drive):
    bus.sdo_write(NODE, 0x1017, 0, 100, 2)
    bus.expect(0x704, "7F")
    try:
        ip_link("down")
        deadline = time.monotonic() + 0.5
        while time.monotonic() < deadline:  # it must survive a while without its interface
            assert drive.running(), f"atv312d exited {drive.proc.returncode} on link down:\n{drive.log()}"
            time.sleep(0.05)
    finally:
        ip_link("up")
    up = time.monotonic()
    frame = bus.expect(0x704, timeout=1.0)
    assert frame.data in (b"\x00", b"\x7f"), f"want a boot-up or a heartbeat, got {frame}"
    assert time.monotonic() - up <= 1.0
    assert bus.sdo_read(NODE, 0x1000, 0) == 0x00010192
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
     ([IFACE, "--node-id", "4", "--log-level", "loud"], ["loud"])],
    ids=["nothing", "no-node-id", "node-id-0", "node-id-128", "node-id-text", "unknown-option", "bad-log-level"],
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
