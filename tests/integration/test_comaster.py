# SPDX-License-Identifier: Apache-2.0
"""comaster against atv312d (two drives) and against python canopen's LocalNode, a server the
project did not write: the exact output lines, JSON fields, exit codes and, where it matters, the
frames on the bus."""

import json
import os
import queue
import re
import signal
import subprocess
import threading
import time

import pytest

from conftest import BOOT_TIMEOUT, EDS, IFACE, LOCAL_NODE, ROOT, Frame

COMASTER = os.environ.get("COMASTER") or str(ROOT / "build" / "apps" / "comaster" / "comaster")

EXIT_ABORT, EXIT_TIMEOUT = 1, 2
EX_USAGE, EX_DATAERR, EX_UNAVAILABLE = 64, 65, 69


def comaster(*args, stdin=None):
    """Runs comaster on vcan0; returns (exit status, stdout, stderr)."""
    p = subprocess.run([COMASTER, "-i", IFACE, *[str(a) for a in args]], capture_output=True,
                       text=True, timeout=30, input=stdin)
    return p.returncode, p.stdout, p.stderr


@pytest.fixture
def drives(bus, start_daemon):
    """Two ATV312 at node-ids 4 and 5, booted."""
    return start_daemon(bus, "--node-id", "4-5")


def test_read_by_index_and_by_name(drives):
    assert comaster("read", 4, "0x1008", "string") == (0, "ATV312\n", "")
    assert comaster("read", 5, "0x1000") == (0, "65938\n", "")  # 0x00010192, 4 bytes: UNSIGNED32
    # The EDS of the node's identity (1018h:01 = 0x5F, 1008h = ATV312) names ACC and its type.
    assert comaster("read", 4, "ACC") == (0, "30\n", "")
    rc, out, _ = comaster("--json", "read", 4, "acceleration time")
    assert rc == 0
    assert json.loads(out) == {"node": 4, "index": "0x203C", "subindex": 2,
                               "name": "ACC acceleration time (0.1 s)", "type": "UNSIGNED16",
                               "value": 30}


def test_write_changes_only_its_node(drives):
    assert comaster("write", 5, "ACC", "50") == (0, "", "")
    assert comaster("read", 5, "ACC") == (0, "50\n", "")
    assert comaster("read", 4, "ACC") == (0, "30\n", "")
    rc, out, _ = comaster("--json", "write", 4, "0x203C:3", "u16", "45")
    assert rc == 0 and json.loads(out) == {"node": 4, "index": "0x203C", "subindex": 3,
                                           "type": "UNSIGNED16", "written": 2}
    assert comaster("read", 4, "0x203C:3", "u16") == (0, "45\n", "")


def test_expedited_write_frames(drives, dump):
    """With --eds no identity is read: the transfer is the two frames of an expedited download."""
    mark = dump.mark()
    assert comaster("--eds", EDS, "write", 4, "ACC", "60") == (0, "", "")
    dump.expect(0x604, "2B3C20023C000000", since=mark)
    dump.expect(0x584, "603C200200000000", since=mark)
    sdo = [str(f) for f in dump.seen[mark:] if f.can_id in (0x604, 0x584)]
    assert sdo == ["604#2B3C20023C000000", "584#603C200200000000"]


def test_segmented_and_block_transfers_against_atv312d(drives):
    assert comaster("read", 4, "0x1008", "--block") == (0, "ATV312\n", "")
    assert comaster("write", 4, "0x203C:2", "u16", "55", "--block") == (0, "", "")
    assert comaster("read", 4, "0x203C:2", "u16", "--block") == (0, "55\n", "")


def test_abort_timeout_and_data_errors(drives):
    rc, out, err = comaster("read", 4, "0x1234:1")
    assert (rc, out) == (EXIT_ABORT, "")
    assert err == ("comaster: error: node 4, 1234:01: SDO abort 0x06020000: object does not exist in the "
                   "object dictionary\n")
    rc, out, err = comaster("--timeout", "100", "read", 9, "0x1000", "u32")
    assert rc == EXIT_TIMEOUT
    assert err == ("comaster: error: node 9, 1000:00: no answer within 100 ms: is the node on vcan0 and "
                   "its node-id 9? (--timeout MS waits longer)\n")
    rc, out, err = comaster("--json", "write", 4, "0x1008", "string", "X")
    assert rc == EXIT_ABORT
    assert json.loads(out) == {
        "error": "node 4, 1008:00: SDO abort 0x06010002: attempt to write a read only object",
        "exit": 1}
    rc, _, err = comaster("write", 4, "ACC", "u16", "70000")
    assert rc == EX_DATAERR
    assert err == "comaster: error: node 4, 203C:02: 70000 is out of range for UNSIGNED16 (0..65535)\n"


def test_signal_ends_a_command_with_exit_3(dump):
    p = subprocess.Popen([COMASTER, "-i", IFACE, "--timeout", "10000", "read", "9", "0x1000",
                          "u32"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    dump.expect(0x609, "4000100000000000")  # its request is out: it waits for the answer
    p.send_signal(signal.SIGTERM)
    assert p.wait(timeout=5) == 3
    assert p.stderr.read() == "comaster: error: interrupted by a signal before the command finished\n"


def test_usage_errors():
    assert comaster("read", 128, "0x1000")[0::2] == (
        EX_USAGE, "comaster: error: '128' is not a node-id: give a number 1..127\n"
        "Try 'comaster read --help'.\n")
    assert comaster("frobnicate")[0::2] == (
        EX_USAGE, "comaster: error: unknown command 'frobnicate': give one of read, write, nmt, scan, monitor, "
        "drive, boot, run, concise, set, get, status, disable, enable, can, configure, lss, time, gateway\nTry 'comaster --help'.\n")
    assert comaster("read", 4, "0x1000", "u7")[0] == EX_USAGE
    # An object the EDS does not have: no data type to write VALUE as (read would guess by size).
    assert comaster("--eds", EDS, "write", 4, "0x1234:1", "5")[0::2] == (
        EX_USAGE, "comaster: error: write 4 0x1234:1: give the TYPE of the value (no EDS names its data "
        "type): one of bool i8 i16 i32 i64 u8 u16 u32 u64 f32 f64 string octets domain (or the "
        "CiA 301 names: UNSIGNED16, REAL32, VISIBLE_STRING ...)\nTry 'comaster write --help'.\n")
    assert comaster("write", 4, "0x1000")[0] == EX_USAGE  # no VALUE
    p = subprocess.run([COMASTER, "-i", "nosuchcan0", "read", "4", "0x1000"], capture_output=True,
                       text=True, timeout=30)
    assert p.returncode == EX_UNAVAILABLE
    assert p.stderr.startswith("comaster: error: no network interface 'nosuchcan0'")


def test_nmt_commands_frames_and_boot_up(drives, dump):
    mark = dump.mark()
    assert comaster("nmt", "start", 4) == (0, "", "")
    dump.expect(0x000, "0104", since=mark)
    assert comaster("--json", "nmt", "stop", "all") == (0, '{"node": "all", "command": "stop"}\n', "")
    dump.expect(0x000, "0200", since=mark)
    assert comaster("nmt", "reset-node", 5) == (0, "node 5: boot-up\n", "")
    dump.expect(0x000, "8105", since=mark)
    dump.expect(0x705, "00", since=mark)
    rc, out, err = comaster("--timeout", "200", "nmt", "reset-comm", 9)
    assert rc == EXIT_TIMEOUT
    assert err == ("comaster: error: node 9: no boot-up within 200 ms after reset-comm: is the node on "
                   "vcan0? (--timeout MS waits longer)\n")
    assert comaster("nmt", "go", 4)[0] == EX_USAGE


def test_expedited_and_segmented_against_local_node(local_node):
    assert comaster("read", LOCAL_NODE, "0x2000", "u32") == (0, "305419896\n", "")
    assert comaster("write", LOCAL_NODE, "0x2000", "u32", "0xCAFE") == (0, "", "")
    assert comaster("read", LOCAL_NODE, "0x2000", "u32") == (0, "51966\n", "")
    # 15 bytes: a segmented upload (the server's choice) and a segmented download.
    assert comaster("read", LOCAL_NODE, "0x2001", "string") == (0, "LocalNode label\n", "")
    text = "written by comaster, segmented"
    assert comaster("write", LOCAL_NODE, "0x2001", "string", text) == (0, "", "")
    assert comaster("read", LOCAL_NODE, "0x2001", "string") == (0, text + "\n", "")


def test_domain_to_and_from_files(local_node, tmp_path):
    blob = bytes(range(256)) * 4
    source, target = tmp_path / "in.bin", tmp_path / "out.bin"
    source.write_bytes(blob)
    assert comaster("write", LOCAL_NODE, "0x2002", "domain", source) == (0, "", "")
    rc, out, _ = comaster("--json", "read", LOCAL_NODE, "0x2002", "domain", "--output", target)
    assert rc == 0
    assert json.loads(out) == {"node": LOCAL_NODE, "index": "0x2002", "subindex": 0,
                               "type": "DOMAIN", "size": 1024, "file": str(target)}
    assert target.read_bytes() == blob


def test_block_transfers_against_local_node(local_node):
    """LocalNode has no block transfer: it aborts a block download with 0x05040001, and answers a
    block upload initiate with a plain upload (CiA 301 lets the server fall back), which the
    client follows: the value arrives segmented."""
    rc, _, err = comaster("write", LOCAL_NODE, "0x2001", "string", "block", "--block")
    assert rc == EXIT_ABORT
    assert err == ("comaster: error: node 10, 2001:00: SDO abort 0x05040001: client/server command "
                   "specifier not valid or unknown\n")
    assert comaster("read", LOCAL_NODE, "0x2001", "string", "--block") == (
        0, "LocalNode label\n", "")


# A DCF for LocalNode as configuration tools write one (CiA 306): a negative INTEGER16, and TPDO1's
# transmission type, inhibit time, event timer and mapping while the PDO is valid.
LOCAL_NODE_DCF = """[1000]
ParameterName=Device type
DataType=0x0007
AccessType=ro
DefaultValue=0
[1800sub1]
ParameterName=COB-ID
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x180
[1800sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=rw
ParameterValue=254
[1800sub3]
ParameterName=Inhibit time
DataType=0x0006
AccessType=rw
ParameterValue=100
[1800sub5]
ParameterName=Event timer
DataType=0x0006
AccessType=rw
ParameterValue=500
[1A00sub0]
ParameterName=Number of mapped objects
DataType=0x0005
AccessType=rw
ParameterValue=2
[1A00sub1]
ParameterName=Object 1
DataType=0x0007
AccessType=rw
ParameterValue=0x20030010
[1A00sub2]
ParameterName=Object 2
DataType=0x0007
AccessType=rw
ParameterValue=0x20000020
[2003]
ParameterName=Offset
DataType=0x0003
AccessType=rw
ParameterValue=-1234
"""


def test_boot_a_dcf_against_local_node(local_node, dump, tmp_path):
    """comaster boot downloads a negative INTEGER16 and a valid PDO's configuration to a server the
    project did not write: the PDO invalidated, configured, mapped (count 0, entries, count) and
    validated (docs/comaster.md, "The configuration of PDOs"). LocalNode itself has no rule of a
    valid PDO: it stores every write of the right length, so it would take them in any order."""
    dcf = tmp_path / "local.dcf"
    dcf.write_text(LOCAL_NODE_DCF)
    rc, out, err = comaster("boot", LOCAL_NODE, dcf)
    assert rc == 0, out + err
    for request in ("230018018A010080", "2F001802FE000000", "2B00180364000000", "2B001805F4010000",
                    "2F001A0000000000", "23001A0110000320", "23001A0220000020", "2F001A0002000000",
                    "230018018A010000", "2B0320002EFB0000"):
        dump.expect(0x60A, request)  # in this order
    assert comaster("read", LOCAL_NODE, "0x2003", "i16") == (0, "-1234\n", "")
    assert comaster("read", LOCAL_NODE, "0x1A00:1", "u32") == (0, f"{0x20030010}\n", "")
    assert comaster("read", LOCAL_NODE, "0x1800:1", "u32") == (0, f"{0x18A}\n", "")


def assert_enabled(lines, node):
    """The last line of an enable: Operation enabled with remote (bit 9) set; bit 10 (target
    reached) depends on how far the ramp is when the status word is read."""
    assert len(lines) == 1
    match = re.fullmatch(rf"node {node}: Operation enabled \(6041h = 0x([0-9A-F]{{4}})\)", lines[0])
    assert match and int(match.group(1), 16) & ~0x0400 == 0x0227, lines[0]


def test_drive_speed_runs_the_state_machine_by_sdo(drives, dump):
    mark = dump.mark()
    rc, out, err = comaster("drive", 4, "speed", "1200")
    assert (rc, err) == (0, "")
    lines = out.splitlines()
    assert lines[:3] == ["node 4: Switch on disabled (6041h = 0x0640)",
                         "node 4: Ready to switch on (6041h = 0x0621)",
                         "node 4: Switched on (6041h = 0x0623)"]
    assert_enabled(lines[3:], 4)
    dump.expect(0x604, "2B4060000F000000", since=mark)  # the last write: every frame before is seen
    requests = [str(f) for f in dump.seen[mark:] if f.can_id == 0x604 and f.data[0] == 0x2B]
    assert requests == ["604#2B426000B0040000", "604#2B40600006000000",
                        "604#2B40600007000000", "604#2B4060000F000000"]
    assert comaster("read", 4, "0x6042", "i16") == (0, "1200\n", "")
    assert comaster("read", 5, "0x6042", "i16") == (0, "0\n", "")  # the other drive untouched


def test_drive_quick_stop_disable_and_json(drives, dump):
    assert comaster("drive", 4, "enable")[0] == 0
    assert comaster("drive", 4, "quick-stop") == (
        0, "node 4: Operation enabled (6041h = 0x0627)\n"
        "node 4: Quick stop active (6041h = 0x0607)\n", "")
    rc, out, _ = comaster("--json", "drive", 4, "disable")
    assert rc == 0
    assert [json.loads(line) for line in out.splitlines()] == [
        {"node": 4, "state": "Quick stop active", "statusword": "0x0607"},
        {"node": 4, "state": "Switch on disabled", "statusword": "0x0640"}]
    # Already where disable and quick-stop lead: the status word is read, no control word written.
    # A read of 1000h before and after: every frame of the commands between is seen.
    assert comaster("read", 4, "0x1000", "u32")[0] == 0
    dump.expect(0x584, "4300100092010100")
    mark = dump.mark()
    for action in ("disable", "quick-stop"):
        assert comaster("drive", 4, action) == (0, "node 4: Switch on disabled (6041h = 0x0640)\n", "")
    assert comaster("read", 4, "0x1000", "u32")[0] == 0
    dump.expect(0x584, "4300100092010100", since=mark)
    assert [str(f) for f in dump.seen[mark:] if f.can_id == 0x604 and f.data[0] == 0x2B] == []


def test_drive_in_fault_needs_fault_reset(drives, bus):
    # A heartbeat consumer of node 0x7E, 50 ms, fed once: its loss is the network fault.
    assert comaster("write", 4, "0x1016:1", "u32", "0x007E0032") == (0, "", "")
    bus.send(Frame(0x77E, b"\x05"))
    bus.expect(0x84, timeout=2.0)  # the drive's EMCY (8130h)
    rc, out, err = comaster("drive", 4, "enable")
    assert rc == 4
    assert out == "node 4: Fault (6041h = 0x0608)\n"
    assert err == ("comaster: error: node 4 is in Fault (6041h = 0x0608): reset it first: comaster drive "
                   "4 fault-reset\n")
    assert comaster("drive", 4, "fault-reset") == (
        0, "node 4: Fault (6041h = 0x0608)\nnode 4: Switch on disabled (6041h = 0x0640)\n", "")


def test_drive_usage_errors():
    assert comaster("drive", 4, "speed", "99999")[0::2] == (
        EX_USAGE, "comaster: error: drive: speed '99999' is not a velocity: give rpm -32768..32767\n"
        "Try 'comaster drive --help'.\n")
    assert comaster("drive", 4, "fly")[0] == EX_USAGE
    assert comaster("drive", 4, "speed")[0] == EX_USAGE


def test_scan_lists_every_model_with_its_state(bus, start_daemon, dump):
    start_daemon(bus, "--node-id", "4-5", "--model", "atv312", "--node-id", "6", "--model",
                 "atv31", "--node-id", "7", "--model", "atv58", boot_ids=[4, 5, 6, 7],
                 padded_ids=[7])
    assert comaster("nmt", "start", 5)[0] == 0
    mark = dump.mark()
    rc, out, err = comaster("scan")
    assert (rc, err) == (0, "")
    assert out.splitlines() == [
        "node  device type vendor      product     revision    name              state",
        "   4  0x00010192  0x0000005F  -           -           ATV312            Pre-operational",
        "   5  0x00010192  0x0000005F  -           -           ATV312            Operational",
        "   6  0x00010192  0x0000005F  -           -           ATV31             Pre-operational",
        "   7  0x00010192  -           -           -           AT58              Pre-operational"]
    # Every node-id was asked for 1000h once; the states were asked by node guarding.
    dump.expect(0x707, "7F00000000000000", since=mark)  # the ATV58's reply, padded: the last
    requests = [f.can_id for f in dump.seen[mark:] if f.data[:4] == bytes.fromhex("40001000")]
    assert requests == list(range(0x601, 0x680))
    rc, out, _ = comaster("--json", "--timeout", "300", "scan")
    assert rc == 0
    assert json.loads(out.splitlines()[3]) == {
        "node": 7, "device_type": "0x00010192", "vendor": None, "product": None,
        "revision": None, "name": "AT58", "state": "Pre-operational"}


def test_scan_of_an_empty_bus():
    assert comaster("--timeout", "100", "scan")[0::2] == (
        EXIT_TIMEOUT, "comaster: error: no node answered on vcan0 within 100 ms (--timeout MS waits "
        "longer)\n")


class Monitor:
    """comaster monitor in the background; its lines without the time, read with deadlines."""

    def __init__(self, *args):
        self.proc = subprocess.Popen([COMASTER, "-i", IFACE, "monitor", *[str(a) for a in args]],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()
        ready = self.proc.stderr.readline()
        assert ready == "comaster: monitoring vcan0 (Ctrl-C ends)\n", ready + self.proc.stderr.read()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line)

    def expect(self, text, timeout=2.0):
        """Waits for the line `text` (after its time); returns the lines skipped on the way."""
        deadline = time.monotonic() + timeout
        skipped = []
        while True:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                pytest.fail(f"monitor printed no {text!r} within {timeout} s; it printed {skipped}")
            match = re.match(r"^ *\d+\.\d{3}  (.*)\n$", line)
            assert match, f"not a monitor line: {line!r}"
            if match.group(1) == text:
                return skipped
            skipped.append(match.group(1))

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        return self.proc.wait(timeout=5)


def test_monitor_states_pdos_by_name_sync_and_emcy(drives, bus):
    assert comaster("write", 4, "0x1805:1", "u32", "0x284") == (0, "", "")  # PDO6 valid
    monitor = Monitor(4)
    try:
        assert comaster("write", 4, "0x1017", "u16", "100") == (0, "", "")
        monitor.expect("node 4: Pre-operational")  # its first heartbeat
        assert comaster("nmt", "start", 4) == (0, "", "")
        monitor.expect("node 4: Pre-operational -> Operational")
        assert comaster("drive", 4, "enable")[0] == 0
        # PDO6 (1805h, 1A05h), its mapping read over SDO, named by the ATV312's EDS.
        monitor.expect("TPDO6 node 4: 6041:00 Statusword (ETAD) = 0x0627 Operation enabled, "
                       "6044:00 vl velocity actual value (RFRD) = 0")
        monitor.expect("TPDO1 node 4: 6041:00 Statusword (ETAD) = 0x0627 Operation enabled")
        bus.send(Frame(0x080))
        monitor.expect("SYNC")
        # Node 5 loses the heartbeat of node 0x7E: its network fault, decoded.
        assert comaster("write", 5, "0x1016:1", "u32", "0x007E0032") == (0, "", "")
        bus.send(Frame(0x77E, b"\x05"))
        monitor.expect("node 5: EMCY 0x8130 life guard error or heartbeat error, error register "
                       "0x01")
        assert comaster("nmt", "stop", 4) == (0, "", "")
        monitor.expect("node 4: Operational -> Stopped")
    finally:
        assert monitor.stop() == 0


def test_monitor_json_lines(drives, bus):
    monitor = Monitor("--json")
    try:
        bus.send(Frame(0x080, b"\x07"))
        line = json.loads(monitor.lines.get(timeout=2.0))
        assert line.pop("time") >= 0
        assert line == {"event": "sync", "counter": 7}
    finally:
        assert monitor.stop() == 0


def test_drive_by_the_mapped_rpdo(drives, dump):
    rc, out, err = comaster("--timeout", "300", "drive", 4, "enable", "--rpdo")
    assert (rc, out) == (EXIT_TIMEOUT, "node 4: Switch on disabled (6041h = 0x0640)\n")
    assert err == ("comaster: error: node 4: control word 0x0006: no Ready to switch on within 300 ms "
                   "(6041h = 0x0640): RPDOs count only in Operational: comaster nmt start NODE "
                   "(--timeout MS waits longer)\n")
    dump.expect(0x204, "0600")  # sent, and ignored in Pre-operational
    assert comaster("nmt", "start", 4)[0] == 0
    # RPDO1 (204h) maps 6040h alone: the velocity goes by SDO, the control words in RPDO1.
    mark = dump.mark()
    rc, out, _ = comaster("drive", 4, "speed", 600, "--rpdo")
    assert rc == 0
    assert_enabled(out.splitlines()[-1:], 4)
    dump.expect(0x204, "0F00", since=mark)
    assert [str(f) for f in dump.seen[mark:] if f.can_id == 0x204] == ["204#0600", "204#0700",
                                                                       "204#0F00"]
    assert any(str(f) == "604#2B42600058020000" for f in dump.seen[mark:])
    # RPDO6 (305h) maps 6040h and 6042h once RPDO1 is invalid: both go in it.
    assert comaster("write", 5, "0x1400:1", "u32", "0x80000205")[0] == 0
    assert comaster("write", 5, "0x1405:1", "u32", "0x305")[0] == 0
    assert comaster("nmt", "start", 5)[0] == 0
    mark = dump.mark()
    assert comaster("drive", 5, "speed", 700, "--rpdo")[0] == 0
    dump.expect(0x305, "0F00BC02", since=mark)
    assert [str(f) for f in dump.seen[mark:] if f.can_id == 0x305] == [
        "305#0000BC02", "305#0600BC02", "305#0700BC02", "305#0F00BC02"]
    assert comaster("read", 5, "0x6042", "i16") == (0, "700\n", "")


def test_drive_rpdo_without_a_mapped_control_word(drives):
    assert comaster("write", 4, "0x1400:1", "u32", "0x80000204")[0] == 0
    assert comaster("drive", 4, "enable", "--rpdo")[0::2] == (
        EX_DATAERR, "comaster: error: node 4: --rpdo: no valid RPDO (1400h-1407h) maps the control word "
        "6040h: make one valid (e.g. comaster write 4 0x1405:1 u32 0x304), or drive by SDO "
        "without --rpdo\n")


def test_monitor_heartbeat_lost_and_heard_again(drives):
    assert comaster("write", 4, "0x1017", "u16", "50") == (0, "", "")
    monitor = Monitor(4, "--heartbeat", 200)
    try:
        monitor.expect("node 4: Pre-operational")
        assert comaster("write", 4, "0x1017", "u16", "0") == (0, "", "")  # heartbeats stop
        monitor.expect("node 4: heartbeat lost")
        assert comaster("write", 4, "0x1017", "u16", "50") == (0, "", "")
        monitor.expect("node 4: heard again")
    finally:
        assert monitor.stop() == 0


def test_eds_dir_is_the_only_place_looked_in(drives, tmp_path):
    assert comaster("--eds-dir", tmp_path, "read", 4, "ACC")[0::2] == (
        EX_USAGE, "comaster: error: 'ACC' is not an object: give INDEX:SUB such as 0x203C:2, or a name "
        "with --eds FILE (or an EDS for the node's identity in the EDS directory)\n"
        "Try 'comaster read --help'.\n")
    (tmp_path / "ATV312.eds").write_text(EDS.read_text())
    assert comaster("--eds-dir", tmp_path, "read", 4, "ACC") == (0, "30\n", "")
