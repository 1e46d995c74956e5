# SPDX-License-Identifier: Apache-2.0
"""The nodes that are no drive on real SocketCAN (docs/plc300.md, docs/io.md): the PLC300 slave's
SDO example of its manual (6.2.2) frame for frame, its markers through RPDOs and TPDOs and the
control socket, Pre-operational after a heartbeat or guarding loss; the CiA 401 I/O node's PDOs
and serial numbers; a bus of drives, I/O nodes and a PLC300 in one process; and every object of
both EDS files against the running daemon with python canopen as the master."""

import json
import time

import canopen
import pytest
from canopen.sdo.exceptions import SdoAbortedError

from conftest import IFACE, NMT_START, NMT_STOP, ROOT, Frame
from test_control import ctl, state

PLC = 1
IO = 10
PLC300_EDS = ROOT / "eds" / "PLC300.eds"
IO401_EDS = ROOT / "eds" / "IO401.eds"
SDO_ABORT_READ_ONLY = 0x06010002
# 1018h:04 of each model: its base plus the node-id (D-PLC300-IDENTITY, D-IO401-IDENTITY).
SERIAL_BASE = {"plc300": 0x30000000, "io": 0x40100000}


@pytest.fixture
def plc(bus, start_daemon, tmp_path):
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", PLC, "--model", "plc300", "--control", sock)
    return sock


def test_plc300_answers_the_manuals_sdo_example(bus, plc):
    """The PLC300 CANopen manual, 6.2.2: reading 3000h of node 1 answers 4Bh with 999 (E7h 03h),
    the input memory's bytes 0 and 1 at power-up (docs/decisions.md, D-PLC300-3000H)."""
    reply = bus.request(Frame(0x601, bytes.fromhex("4000300000000000")), 0x581)
    assert reply.data == bytes.fromhex("4B003000E7030000")
    # The same bytes through the other views of the one memory.
    assert bus.sdo_read(PLC, 0x3400, 0) == 999
    assert bus.sdo_read(PLC, 0x3001, 0) == 0x03
    assert bus.sdo_read(PLC, 0x3800, 0) == 999


def test_plc300_identity_and_63_heartbeat_consumer_entries(bus, plc):
    assert bus.sdo_read(PLC, 0x1018, 1) == 0x123
    assert bus.sdo_read(PLC, 0x1018, 2) == 0x220
    assert bus.sdo_read(PLC, 0x1018, 4) == SERIAL_BASE["plc300"] + PLC
    assert bus.sdo_read(PLC, 0x1016, 0) == 63
    assert bus.sdo_read(PLC, 0x1016, 63) == 0


def map_pdo(bus, comm, mapping, entries, cob_id, transmission):
    """The manual's procedure (6.3.2): the PDO invalid (CiA 301), sub 0 = 0, the entries, sub 0 =
    n, then valid again."""
    bus.sdo_write(PLC, comm, 1, 0x80000000 | cob_id, 4)
    bus.sdo_write(PLC, comm, 2, transmission, 1)
    bus.sdo_write(PLC, mapping, 0, 0, 1)
    for sub, entry in enumerate(entries, 1):
        bus.sdo_write(PLC, mapping, sub, entry, 4)
    bus.sdo_write(PLC, mapping, 0, len(entries), 1)
    bus.sdo_write(PLC, comm, 1, cob_id, 4)


def test_plc300_markers_through_pdos_and_the_control_socket(bus, plc):
    # The manual's mapping examples: RPDO {3400h 16 bit, 3804h 32 bit}, TPDO {4000h 8 bit, 4804h
    # 32 bit}; the TPDO synchronous (type 1).
    map_pdo(bus, 0x1400, 0x1600, [0x34000010, 0x38040020], 0x201, 254)
    map_pdo(bus, 0x1800, 0x1A00, [0x40000008, 0x48040020], 0x181, 1)
    bus.nmt(NMT_START, PLC)
    bus.send(Frame(0x201, bytes.fromhex("3412785634120000")[:6]))
    deadline = time.monotonic() + 1.0
    while bus.sdo_read(PLC, 0x3400, 0) != 0x1234:
        assert time.monotonic() < deadline, "RPDO1 not applied to 3400h"
    # One memory: the byte and double word views of the same bytes changed with it.
    assert bus.sdo_read(PLC, 0x3000, 0) == 0x1234
    assert bus.sdo_read(PLC, 0x3001, 0) == 0x12
    assert bus.sdo_read(PLC, 0x3804, 0) == 0x12345678
    # No such object: a word marker's number is even.
    assert bus.sdo_abort_code(PLC, bytes.fromhex("4006380000000000")) == 0x06020000
    assert ctl(plc, "marker", PLC, "%ID2004") == (0, "ok node 1: %ID2004 = 305419896 (0x12345678, 3804h)")
    # The PLC program writes the outputs; the synchronous TPDO sends them at the next SYNC.
    assert ctl(plc, "marker", PLC, "%QB2000", "0x5A") == (0, "ok node 1: %QB2000 = 90 (4000h)")
    assert ctl(plc, "marker", PLC, "%QW2004", 0x3344)[0] == 0
    assert ctl(plc, "marker", PLC, "%QB2007", 0x11)[0] == 0
    mark = bus.mark()
    bus.send(Frame(0x80, b""))
    bus.expect(0x181, "5A44330011", since=mark)
    assert bus.sdo_read(PLC, 0x4804, 0) == 0x11003344
    s = state(plc, PLC)
    assert (s["kind"], s["model"], s["nmt"]) == ("node", "plc300", "Operational")
    assert s["outputs"] == {"%QB2000": 0x5A, "%QB2004": 0x44, "%QB2005": 0x33, "%QB2007": 0x11}
    assert s["inputs"] == {"%IB2000": 0x34, "%IB2001": 0x12, "%IB2004": 0x78, "%IB2005": 0x56,
                           "%IB2006": 0x34, "%IB2007": 0x12}


def test_plc300_refuses_what_is_no_marker_and_the_drive_commands(bus, plc):
    status, reply = ctl(plc, "marker", PLC, "%IW2001", 1)
    assert status == 1 and "'%IW2001' is no network marker" in reply, reply
    status, reply = ctl(plc, "marker", PLC, "%QB2000", 256)
    assert status == 1 and "marker %QB2000 256: give 0..255" in reply, reply
    status, reply = ctl(plc, "fault", PLC, "OHF")
    assert status == 1 and "node 1 is a plc300 node, not a drive" in reply, reply
    bus.expect_none(0x81, 0.1)


def heartbeat_then_silence(bus, producer):
    bus.send(Frame(0x700 + producer, bytes([0x05])))


@pytest.mark.parametrize("start_state", [NMT_START, NMT_STOP])
def test_plc300_goes_to_pre_operational_on_a_heartbeat_loss(bus, plc, start_state):
    """6.5.3: a consumer's timeout takes the PLC300 to Pre-operational, from Stopped too; its red
    LED double flashes and the green one is off (2.4: red over green)."""
    bus.sdo_write(PLC, 0x1016, 1, (5 << 16) | 100, 4)
    bus.sdo_write(PLC, 0x1017, 0, 50, 2)
    bus.nmt(start_state, PLC)
    heartbeat_then_silence(bus, 5)
    state_byte = "05" if start_state == NMT_START else "04"
    bus.expect(0x701, state_byte, timeout=0.2)
    mark = bus.mark()
    bus.expect(0x701, "7F", timeout=0.5, since=mark)
    s = state(plc, PLC)
    assert s["nmt"] == "Pre-operational"
    assert s["error_control"] == {"by": "heartbeat", "node": 5}
    assert (s["err_led"], s["run_led"]) == ("double flash", "off")


def test_plc300_goes_to_pre_operational_on_a_life_guarding_loss(bus, plc):
    bus.sdo_write(PLC, 0x100C, 0, 50, 2)
    bus.sdo_write(PLC, 0x100D, 0, 2, 1)
    bus.nmt(NMT_START, PLC)
    bus.send(Frame(0x701, b"", rtr=True))
    bus.expect(0x701, "05")
    bus.send(Frame(0x701, b"", rtr=True))
    bus.expect(0x701, "85")
    time.sleep(0.2)  # guard time x life time factor = 100 ms without a request
    s = state(plc, PLC)
    assert (s["nmt"], s["error_control"], s["err_led"]) == ("Pre-operational", {"by": "guarding"}, "double flash")
    # The master guards again, now every second: the node answers in Pre-operational and the
    # event is over (6.5.2: re-enabling the service clears the error indication).
    bus.sdo_write(PLC, 0x100C, 0, 1000, 2)
    bus.send(Frame(0x701, b"", rtr=True))
    bus.expect(0x701, "7F")
    s = state(plc, PLC)
    assert (s["error_control"], s["err_led"], s["run_led"]) == (None, "off", "blinking")


@pytest.fixture
def mixed(bus, start_daemon, tmp_path):
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", 4, "--model", "atv312", "--node-id", "10-12", "--model", "io",
                 "--node-id", PLC, "--model", "plc300", "--control", sock, boot_ids=[1, 4, 10, 11, 12])
    return sock


def test_a_bus_of_drives_io_nodes_and_a_plc300(bus, mixed):
    serials = [bus.sdo_read(n, 0x1018, 4) for n in (10, 11, 12)]
    assert serials == [SERIAL_BASE["io"] + n for n in (10, 11, 12)]
    assert bus.sdo_read(4, 0x1000, 0) == 0x00010192
    assert bus.sdo_read(IO, 0x1000, 0) == 0x00070191
    assert bus.sdo_read(PLC, 0x1000, 0) == 0
    status, reply = ctl(mixed, "--json", "state")
    kinds = [(n["node"], n["kind"]) for n in json.loads(reply)["nodes"]]
    assert kinds == [(1, "node"), (4, "drive"), (10, "node"), (11, "node"), (12, "node")]


def test_io_node_pdos_follow_its_terminals(bus, mixed):
    """CiA 401's default PDOs: TPDO1 the digital inputs, TPDO2 the analogue inputs, each sent when
    it changes (type 255); RPDO1 the outputs."""
    bus.nmt(NMT_START, IO)
    mark = bus.mark()
    assert ctl(mixed, "input", IO, "DI3", "on") == (0, "ok node 10: DI3 on (6000h:01 = 04)")
    bus.expect(0x18A, "04", since=mark)
    mark = bus.mark()
    assert ctl(mixed, "analog", IO, "AI2", -300) == (0, "ok node 10: AI2 -300 (6401h:02)")
    bus.expect(0x28A, "0000D4FE", since=mark)
    bus.send(Frame(0x20A, bytes([0x05])))
    deadline = time.monotonic() + 1.0
    while state(mixed, IO)["outputs"] != ["DO1", "DO3"]:
        assert time.monotonic() < deadline, "RPDO1 not applied to 6200h:01"
    assert bus.sdo_read(IO, 0x6200, 1) == 0x05
    # The other I/O nodes did not move.
    assert bus.sdo_read(11, 0x6000, 1) == 0


def test_io_node_stays_stopped_on_a_heartbeat_loss(bus, mixed):
    """1029h:01 = 0, CiA 301's default: Pre-operational only from Operational."""
    bus.sdo_write(IO, 0x1016, 1, (5 << 16) | 100, 4)
    bus.nmt(NMT_STOP, IO)
    heartbeat_then_silence(bus, 5)
    time.sleep(0.3)
    s = state(mixed, IO)
    assert (s["nmt"], s["error_control"], s["err_led"]) == ("Stopped", {"by": "heartbeat", "node": 5}, "double flash")
    assert s["run_led"] == "single flash"  # CiA 303-3: both LEDs show


# ---- every object against the EDS, python canopen as the master -------------------------------

# Each model, its EDS and node-id; 1018h:04 is the node's own serial number (checked above).
EDS_MODELS = {"plc300": (PLC300_EDS, PLC), "io": (IO401_EDS, IO)}
NOT_COMPARED = {(0x1018, 4)}


@pytest.fixture(params=list(EDS_MODELS))
def eds_node(request, bus, start_daemon):
    eds, node_id = EDS_MODELS[request.param]
    start_daemon(bus, "--node-id", node_id, "--model", request.param)
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=IFACE)
    node = canopen.RemoteNode(node_id, str(eds))
    net.add_node(node)
    yield node
    net.disconnect()


def entries(od):
    for obj in od.values():
        if isinstance(obj, canopen.objectdictionary.ODVariable):
            yield obj
        else:
            yield from obj.values()


SDO_ABORT_UNSUPPORTED_ACCESS = 0x06010000
SDO_ABORT_VALUE_RANGE = 0x06090030
SDO_ABORT_DATA_STORE = 0x08000020


def refused_by_cia301(node, var):
    """The abort a writable object gives its own value by a CiA 301 rule, or None: a valid PDO's
    mapping (06010000) and a valid TPDO's inhibit time (06090030) are locked (docs/pdo.md); 1010h
    and 1011h take only their signatures, and without --store not even those (08000020)."""
    if var.index in (0x1010, 0x1011) and var.subindex:
        return SDO_ABORT_DATA_STORE
    if 0x1600 <= var.index <= 0x17FF or 0x1A00 <= var.index <= 0x1BFF:
        comm = var.index - 0x200
    elif 0x1800 <= var.index <= 0x19FF and var.subindex == 3:
        comm = var.index
    else:
        return None
    valid = not node.sdo[comm][1].raw & 0x80000000
    if not valid:
        return None
    return SDO_ABORT_VALUE_RANGE if comm == var.index else SDO_ABORT_UNSUPPORTED_ACCESS


def test_every_object_matches_the_eds(eds_node):
    """Type (the length read), access (a read-only object refuses its own value with 06010002, a
    writable one takes it back but for CiA 301's locks) and default, object by object."""
    mismatches = []
    checked = 0
    for var in entries(eds_node.object_dictionary):
        where = f"{var.index:04X}:{var.subindex:02X} {var.name}"
        try:
            raw = eds_node.sdo.upload(var.index, var.subindex)
        except SdoAbortedError as e:
            mismatches.append(f"{where}: read aborted 0x{e.code:08X}")
            continue
        checked += 1
        if var.fixed_size and len(raw) != len(var) // 8:
            mismatches.append(f"{where}: {len(raw)} bytes, EDS type has {len(var) // 8}")
            continue
        value = var.decode_raw(raw)
        if (var.index, var.subindex) not in NOT_COMPARED and value != var.default:
            mismatches.append(f"{where}: device {value!r}, EDS default {var.default!r}")
        try:
            eds_node.sdo.download(var.index, var.subindex, raw)
            if not var.writable:
                mismatches.append(f"{where}: {var.access_type} but a write was accepted")
        except SdoAbortedError as e:
            want = refused_by_cia301(eds_node, var) if var.writable else SDO_ABORT_READ_ONLY
            if e.code != want:
                mismatches.append(f"{where}: write of its own value aborted 0x{e.code:08X}")
    assert not mismatches, "\n".join(mismatches[:40])
    assert checked == len(list(entries(eds_node.object_dictionary)))


def test_io_node_keeps_what_1010h_saved_and_the_plc300_nothing(bus, start_daemon, tmp_path):
    """--store binds a plain node as a drive: what the I/O node's 1010h saved (1017h) comes back
    after a restart; the PLC300 has no 1010h (06020000) and its markers start from their
    defaults again (6.2.2: not kept)."""
    store = tmp_path / "bench.store"
    args = ("--node-id", IO, "--model", "io", "--node-id", PLC, "--model", "plc300", "--store", store)
    d = start_daemon(bus, *args, boot_ids=[PLC, IO])
    bus.sdo_write(IO, 0x1017, 0, 500, 2)
    bus.sdo_write(IO, 0x1010, 1, int.from_bytes(b"save", "little"), 4)
    assert bus.sdo_abort_code(PLC, bytes.fromhex("2310100173617665")) == 0x06020000
    bus.sdo_write(PLC, 0x4400, 0, 0x1234, 2)
    assert d.stop() == 0
    start_daemon(bus, *args, boot_ids=[PLC, IO])
    assert bus.sdo_read(IO, 0x1017, 0) == 500
    assert bus.sdo_read(PLC, 0x4400, 0) == 0
