# SPDX-License-Identifier: Apache-2.0
"""The ATV58 with its VW3-A58308 card (atv312d --model atv58, docs/atv58.md) on real SocketCAN: its
8-byte frames, its SDO error layout, the padded guarding reply and the life guarding EMCY, NMT
Disconnect, node-ids 1..63, python canopen scanning every object of eds/ATV58.eds against the running
drive, and a mixed bench of ATV312, ATV31 and ATV58 in one daemon."""

import subprocess

import can
import canopen
import pytest
from canopen.sdo.exceptions import SdoAbortedError

from conftest import BOOT_TIMEOUT, EX_USAGE, IFACE, ROOT, Frame, daemon_path
from test_canopen_master import network, readable_entries  # noqa: F401 (network: a fixture)

NODE = 4
EDS = ROOT / "eds" / "ATV58.eds"
# In the card's layout (byte 6 code, byte 7 class, bytes 4-5 zero) read as a 32-bit abort code.
NO_OBJECT = 0x06020000
ACCESS = 0x06010000


def pad(hex_data):
    return bytes.fromhex(hex_data).ljust(8, b"\x00")


@pytest.fixture
def atv58(bus, start_daemon):
    """An ATV58 at node-id 4, booted: its boot-up is 00 and seven zero bytes."""
    return start_daemon(bus, "--node-id", NODE, "--model", "atv58", padded_ids=[NODE])


def guard_request(bus, node, dlc):
    """A node-guarding remote frame of the given DLC (python-can keeps it on the wire)."""
    msg = can.Message(arbitration_id=0x700 + node, is_extended_id=False, is_remote_frame=True, dlc=dlc)
    bus.bus.send(msg, timeout=1.0)


def test_eight_byte_frames_run_the_manual_example(bus, atv58):
    """T58-01..03: NMT, control PDO and monitoring PDO of 8 bytes, run forward at 1500 rpm."""
    bus.send(Frame(0x000, pad("0104")))
    bus.expect(0x184, pad("4006"))
    bus.send(Frame(0x204, pad("0600DC05")))
    bus.expect(0x184, pad("2106"))
    bus.send(Frame(0x204, pad("0700DC05")))
    bus.expect(0x184, pad("2306"))
    bus.send(Frame(0x204, pad("0F00DC05")))  # T58-02
    bus.expect(0x184, pad("2706DC05"), timeout=5.0)  # T58-03, after the 3 s ramp
    bus.send(Frame(0x000, pad("8004")))  # T58-01
    guard_request(bus, NODE, 8)
    bus.expect(0x704, pad("7F"))
    frames = [f for f in bus.seen if f.can_id in (0x184, 0x704, 0x084)]
    assert frames and all(len(f.data) == 8 for f in frames), [str(f) for f in frames]


def test_sdo_manual_frames_and_error_layout(bus, atv58):
    """T58-04..11 byte for byte, then T58-14: 80 index sub 00 00 code class."""
    exchanges = [
        ("2BE55F03E8030000", "60E55F0300000000"),  # T58-06/07 ACC = 1000
        ("40E55F0300000000", "4BE55F03E8030000"),  # T58-04/05
        ("230C1000F4010000", "600C100000000000"),  # T58-08/09, 4 bytes to a Word
        ("2F0D100004000000", "600D100000000000"),  # T58-10/11
        ("4000300000000000", "8000300000000206"),  # no object
        ("4018100100000000", "8018100100000206"),  # 1018h: the card has none
        ("40E55F0100000000", "80E55F0100000906"),  # no sub-index
        ("2B41600000000000", "8041600000000106"),  # read only
        ("2300180184010080", "8000180100000106"),  # fixed COB-ID
        ("4008100000000000", "4308100041543538"),  # 1008h "AT58", expedited
        ("21E55F0302000000", "80E55F0300000305"),  # segmented: not supported
        ("A4E55F0310000000", "80E55F0300000305"),  # block upload: not supported
    ]
    for request, reply in exchanges:
        bus.request(Frame(0x604, bytes.fromhex(request)), 0x584, bytes.fromhex(reply))


def test_life_guarding_emcy_and_padded_guard_replies(bus, atv58):
    """Guarded at 100 ms x 3: replies 8 bytes with the toggle bit, then silence faults the drive
    (CnF): EMCY 0x8130 with error register 1 (T58-15), and the fault reset's EMCY 0000."""
    bus.request(Frame(0x604, bytes.fromhex("230C100064000000")), 0x584, bytes.fromhex("600C100000000000"))
    bus.request(Frame(0x604, bytes.fromhex("2F0D100003000000")), 0x584, bytes.fromhex("600D100000000000"))
    guard_request(bus, NODE, 0)
    bus.expect(0x704, pad("7F"))
    guard_request(bus, NODE, 1)
    first = bus.expect(0x704, pad("FF"))
    emcy = bus.expect(0x084, pad("308101"))
    assert 0.29 <= emcy.timestamp - first.timestamp <= 0.45, emcy.timestamp - first.timestamp
    assert bus.sdo_read(NODE, 0x1001, 0) == 1
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0608
    mark = bus.mark()
    bus.request(Frame(0x604, bytes.fromhex("2B40600080000000")), 0x584, bytes.fromhex("6040600000000000"))
    bus.expect(0x084, bytes(8), since=mark)
    assert bus.sdo_read(NODE, 0x1001, 0) == 0


def test_nmt_disconnect_stops_the_node(bus, atv58):
    bus.send(Frame(0x000, pad("0304")))
    guard_request(bus, NODE, 8)
    bus.expect(0x704, pad("04"))
    bus.send(Frame(0x604, bytes.fromhex("4000100000000000")))
    bus.expect_none(0x584, 0.3)
    bus.send(Frame(0x000, pad("0100")))  # broadcast start
    bus.expect(0x184, pad("4006"))


def test_node_ids_above_63_refused():
    result = subprocess.run([daemon_path(), IFACE, "--node-id", "64", "--model", "atv58"],
                            capture_output=True, text=True, timeout=BOOT_TIMEOUT)
    assert result.returncode == EX_USAGE, result.stderr
    assert result.stderr == ("atv312d: error: --node-id 64: the atv58 takes node-ids 1..63, "
                             "give it one of those\nTry 'atv312d --help'.\n")


def test_every_object_of_the_eds_equals_the_running_drive(network, atv58):
    """python canopen with eds/ATV58.eds: every readable object has its EDS default, read-only
    ones refuse a write (01/06), writable ones take back their value; 1018h (in the EDS for CiA
    306, not in the card) does not exist."""
    node = canopen.RemoteNode(NODE, str(EDS))
    del node.object_dictionary[0x1018]
    network.add_node(node)
    with pytest.raises(SdoAbortedError) as info:
        node.sdo.upload(0x1018, 0)
    assert info.value.code == NO_OBJECT
    checked = 0
    mismatches = []
    for var in readable_entries(node.object_dictionary):
        where = f"{var.index:04X}:{var.subindex:02X} {var.name}"
        raw = node.sdo.upload(var.index, var.subindex)
        if var.fixed_size and len(raw) != len(var) // 8:
            mismatches.append(f"{where}: {len(raw)} bytes, EDS type has {len(var) // 8}")
        elif var.decode_raw(raw) != var.default:
            mismatches.append(f"{where}: device {var.decode_raw(raw)!r}, EDS default {var.default!r}")
        try:
            node.sdo.download(var.index, var.subindex, raw)
            if not var.writable:
                mismatches.append(f"{where}: {var.access_type} but a write was accepted")
        except SdoAbortedError as e:
            if var.writable or e.code != ACCESS:
                mismatches.append(f"{where}: write back aborted 0x{e.code:08X}")
        checked += 1
    assert not mismatches, "\n".join(mismatches)
    assert checked == 30


def test_mixed_bench_of_atv312_atv31_and_atv58(bus, start_daemon):
    d = start_daemon(bus, "--node-id", "4", "--model", "atv312", "--node-id", "5", "--model", "atv31",
                     "--node-id", "6", "--model", "atv58", padded_ids=[6])
    assert "3 drive(s), node-id 4 (atv312), 5 (atv31), 6 (atv58)" in d.log(), d.log()
    # Each its own frames: the ATV58 pads to 8 bytes and answers in its error layout.
    bus.nmt(0x01, 0)
    bus.expect(0x184, "4006")
    bus.expect(0x185, "4006")
    bus.expect(0x186, pad("4006"))
    bus.send(Frame(0x206, pad("0600DC05")))
    bus.expect(0x186, pad("2106"))
    bus.send("205#0600")
    bus.expect(0x185, "2106")
    assert bus.sdo_read(4, 0x6041, 0) == 0x0640
    guard_request(bus, 4, 0)
    bus.expect(0x704, "05")
    guard_request(bus, 6, 0)
    bus.expect(0x706, pad("05"))
    assert bus.sdo_abort_code(5, "4000100500000000") == 0x06090011
    assert bus.sdo_abort_code(6, "4000100500000000") == 0x06090000
    assert bus.sdo_abort_code(6, "4000300000000000") == NO_OBJECT
    assert bus.sdo_read(4, 0x203C, 2) == 30
    assert bus.sdo_read(6, 0x5FE5, 3) == 30
