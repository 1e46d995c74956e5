# SPDX-License-Identifier: Apache-2.0
"""The drive on real SocketCAN, driven with can-utils: `cansend` for the master's frames, `candump -L`
for what is on the bus (with the kernel's receive timestamps, used for every timing check).

Frames are for node-id 4. Byte strings come from the ATV312 manual (its example frames T31-xx,
numbered in docs/manuals.md), CiA 301 and CiA 402."""

import pytest

from conftest import Frame, assert_periodic, assert_restarting_timer, cansend

NODE = 4
BOOTUP = "704#00"


@pytest.fixture
def drive(dump, start_daemon):
    """atv312d --node-id 4 on vcan0, booted, with candump already listening."""
    return start_daemon(dump, "--node-id", NODE)


def sdo(dump, request, reply):
    """Sends an SDO request with cansend and waits for exactly reply (cansend syntax both)."""
    cansend(request)
    expected = Frame.parse(reply)
    return dump.expect(expected.can_id, expected.data)


def heartbeat_on(dump, period_ms):
    sdo(dump, f"604#2B171000{period_ms.to_bytes(2, 'little').hex().upper()}0000", "584#6017100000000000")


def start_node(dump):
    cansend("000#0104")


def test_bootup_frame_is_704_00(dump, start_daemon):
    # The fixture fails unless exactly 704#00 arrives; here also nothing else comes first.
    start_daemon(dump, "--node-id", NODE)
    assert [str(f) for f in dump.seen if f.can_id != 0x7FF] == [BOOTUP]


def test_nmt_start_stop_pre_operational_and_resets(dump, drive):
    heartbeat_on(dump, 100)
    dump.expect(0x704, "7F")  # pre-operational
    cansend("000#0104")
    dump.expect(0x704, "05")  # operational
    cansend("000#0204")
    dump.expect(0x704, "04")  # stopped
    cansend("604#4000100000000000")
    dump.expect_none(0x584, 0.3)  # no SDO while stopped
    cansend("000#8004")
    dump.expect(0x704, "7F")
    cansend("000#8104")  # reset node: boot-up again, 1017 back to its default (0)
    dump.expect(0x704, "00")
    dump.expect_none(0x704, 0.3)
    cansend("000#8204")  # reset communication
    dump.expect(0x704, "00")
    cansend("000#0100")  # broadcast start: operational, so TPDO1 flows
    dump.expect(0x184, "4006")


def test_manual_sdo_example_frames_byte_for_byte(dump, drive):
    sdo(dump, "604#2B3C2002E8030000", "584#603C200200000000")  # T31-10/11: ACC = 1000
    sdo(dump, "604#403C200200000000", "584#4B3C2002E8030000")  # T31-08/09: read ACC
    sdo(dump, "604#2B0C1000F4010000", "584#600C100000000000")  # T31-12/13: guard time 500 ms
    sdo(dump, "604#2F0D100004000000", "584#600D100000000000")  # T31-14/15: life time factor 4
    sdo(dump, "604#400C100000000000", "584#4B0C1000F4010000")
    sdo(dump, "604#400D100000000000", "584#4F0D100004000000")


def test_heartbeat_period_is_1017(dump, drive):
    heartbeat_on(dump, 100)
    beats = dump.collect_n(0x704, 11, timeout=2.0)
    assert {f.data for f in beats} == {b"\x7f"}
    assert_periodic(beats, 0.100, "heartbeat")


def test_heartbeat_off_again_stops_it(dump, drive):
    heartbeat_on(dump, 100)
    dump.expect(0x704, "7F")
    heartbeat_on(dump, 0)
    dump.expect_none(0x704, 0.35)


def test_node_guarding_toggles_and_reports_state(dump, drive):
    replies = []
    for _ in range(3):
        cansend("704#R")
        replies.append(dump.expect(0x704).data.hex().upper())
    start_node(dump)
    for _ in range(2):
        cansend("704#R")
        replies.append(dump.expect(0x704).data.hex().upper())
    # Toggle bit 7 starts at 0 and alternates; state 0x7F pre-operational, 0x05 operational.
    assert replies == ["7F", "FF", "7F", "85", "05"]


def test_tpdo1_event_timer_100ms(dump, drive):
    start_node(dump)
    frames = dump.collect_n(0x184, 8, timeout=2.0)
    assert {f.data for f in frames} == {bytes.fromhex("4006")}  # 0x0640 switch on disabled
    assert_restarting_timer(frames[1:], 0.100, "TPDO1")


def test_tpdo1_sent_on_status_change_after_inhibit_time(dump, bus, start_daemon):
    # At --log-level warn: the info line of the NMT start would be written to the log, a slow
    # write under User-Mode Linux (3 ms and more on a loaded machine), before the first TPDO1 of
    # the same wake-up leaves, and shorten the gap seen on the bus by as much.
    start_daemon(dump, "--node-id", NODE, "--log-level", "warn")
    # Event timer off, so a TPDO1 after the first one can only be the change being detected.
    sdo(dump, "604#2B00180500000000", "584#6000180500000000")
    start_node(dump)
    previous = dump.expect(0x184, "4006")
    bus.send("204#0600")  # shutdown: status becomes Ready to switch on
    rpdo = dump.expect(0x204, "0600")
    changed = dump.expect(0x184, "2106")
    # Sent on the change as soon as the inhibit time (1800:03 = 30 x 1 ms) since the previous
    # TPDO1 allows. The daemon times the inhibit from its wake-up, the kernel stamps each frame
    # when its write completes: 2 ms are allowed for the first TPDO1's way from the one to the
    # other. The upper bound only keeps a stalled daemon from passing.
    due = max(rpdo.timestamp, previous.timestamp + 0.030)
    assert changed.timestamp - previous.timestamp >= 0.028, "inhibit time not respected"
    assert changed.timestamp - due <= 0.100, f"{changed.timestamp - due:.3f} s late"
    dump.expect_none(0x184, 0.3)  # nothing more: no event timer, no other change


def test_pdo6_mapping_from_the_manual(dump, drive):
    # TPDO6: ETAD 6041, RFRD 6044, LCR 2002:04, OTR 2002:09 (T31-06) through the CiA 301 procedure.
    for request in ["2F051A0000000000", "23051A0110004160", "23051A0210004460", "23051A0310040220",
                    "23051A0410090220", "2F051A0004000000"]:
        sdo(dump, f"604#{request}", f"584#60{request[2:8]}00000000")
    sdo(dump, "604#2305180184020000", "584#6005180100000000")  # 1805:01 = 0x284, valid
    # RPDO6: CMDD 6040, ACC 203C:02, DEC 203C:03 (T31-07).
    for request in ["2F05160000000000", "2305160110004060", "2305160210023C20", "2305160310033C20",
                    "2F05160003000000"]:
        sdo(dump, f"604#{request}", f"584#60{request[2:8]}00000000")
    sdo(dump, "604#2305140104030000", "584#6005140100000000")  # 1405:01 = 0x304, valid
    start_node(dump)
    dump.expect(0x284, "4006000000000000")  # 8 bytes, as the manual's T31-06
    cansend("304#00000A001400")  # T31-07 with CMDD 0: ACC 1 s, DEC 2 s
    dump.expect(0x304)
    sdo(dump, "604#403C200200000000", "584#4B3C20020A000000")
    sdo(dump, "604#403C200300000000", "584#4B3C200314000000")
    cansend("304#06000A001400")  # shutdown, ramps unchanged
    dump.expect(0x284, "2106000000000000")


def test_tpdo6_sync_cyclic(dump, drive):
    sdo(dump, "604#2F05180201000000", "584#6005180200000000")  # 1805:02 = 1: every SYNC
    sdo(dump, "604#2305180184020000", "584#6005180100000000")  # valid, default mapping 6041 6044
    start_node(dump)
    dump.expect_none(0x284, 0.3)  # synchronous: nothing without SYNC
    for _ in range(5):
        cansend("080#")
        sync = dump.expect(0x080)
        pdo = dump.expect(0x284, "40060000")
        assert pdo.timestamp - sync.timestamp < 0.050
        dump.expect_none(0x284, 0.15)  # exactly one per SYNC


def test_cia402_power_sequence_status_words(dump, drive):
    start_node(dump)
    dump.expect(0x184, "4006")  # 0x0640 Switch on disabled, remote, target reached
    steps = [("0600", "2106"),  # shutdown -> 0x0621 Ready to switch on
             ("0700", "2306"),  # switch on -> 0x0623 Switched on
             ("0F00", "2706"),  # enable operation -> 0x0627 Operation enabled (speed 0 reached)
             ("0700", "2306"),  # disable operation -> Switched on
             ("0000", "4006")]  # disable voltage -> Switch on disabled
    for control, status in steps:
        cansend(f"204#{control}")
        dump.expect(0x184, status)
    sdo(dump, "604#4041600000000000", "584#4B41600040060000")


def test_life_guarding_fault_and_fault_reset(dump, drive):
    sdo(dump, "604#2B0C100064000000", "584#600C100000000000")  # guard time 100 ms
    sdo(dump, "604#2F0D100002000000", "584#600D100000000000")  # life time factor 2: 200 ms
    start_node(dump)
    cansend("704#R")  # the first guarding request arms life guarding
    dump.expect(0x704, "05")
    emcy = dump.expect(0x084, timeout=1.0)  # no more requests: life guarding event
    assert emcy.data[0:2] == bytes.fromhex("3081"), f"EMCY {emcy}: want code 0x8130"
    assert emcy.data[2] == 0x01, f"EMCY {emcy}: error register must be 1, the manual's \"=1 (error)\""
    assert len(emcy.data) == 8
    sdo(dump, "604#403F600000000000", "584#4B3F600030810000")  # 603F = 0x8130
    cansend("604#4041600000000000")
    status = dump.expect(0x584)
    assert status.data[0:4] == bytes.fromhex("4B416000") and status.data[4] & 0x4F == 0x08, f"not Fault: {status}"
    sdo(dump, "604#2F0D100000000000", "584#600D100000000000")  # stop life guarding
    mark = dump.mark()
    sdo(dump, "604#2B40600080000000", "584#6040600000000000")  # fault reset (bit 7 rising edge)
    reset = dump.expect(0x084, since=mark)  # may come before the SDO reply
    assert reset.data[0:3] == bytes(3), f"want the EMCY error reset (code 0, register 0), got {reset}"
    sdo(dump, "604#4041600000000000", "584#4B41600040060000")  # Switch on disabled again


def test_heartbeat_consumer_timeout_faults_the_drive(dump, drive):
    # 1016:01 = producer node 0x10, 200 ms. Armed by the first heartbeat of node 0x10 (CiA 301).
    sdo(dump, "604#23161001C8001000", "584#6016100100000000")
    start_node(dump)
    dump.expect(0x184, "4006")
    cansend("710#05")
    sent = dump.expect(0x710, "05")
    emcy = dump.expect(0x084, timeout=1.0)
    assert emcy.data[0:2] == bytes.fromhex("3081") and emcy.data[2] == 0x01, f"EMCY {emcy}"
    assert 0.195 <= emcy.timestamp - sent.timestamp <= 0.260, f"{emcy.timestamp - sent.timestamp:.3f} s"
    fault = dump.expect(0x184)
    assert int.from_bytes(fault.data[0:2], "little") & 0x4F == 0x08, f"not Fault: {fault}"
