# SPDX-License-Identifier: Apache-2.0
"""Routing and the receive filter (docs/runtime.md, "Routing and the receive filter"): a frame no
drive consumes never wakes the daemon, a changed COB-ID object changes what reaches the drives, and
the frames of one wake-up leave in one sendmmsg. The counters come from the daemon's last log line."""

import re

import can

from conftest import EX_OK, IFACE

EMCY_COMMUNICATION = "3081010000000000"  # EMCY 0x8130, error register 0x01


def stopped_counters(daemon):
    """{'wake-ups': n, 'frames received': n, 'sent': n, 'received for no drive': n,
    'sendmmsg calls': n, 'receive filters set': n} from the daemon's last log line."""
    line = daemon.log().strip().splitlines()[-1]
    names = "wake-ups|frames received|sent|received for no drive|sendmmsg calls|receive filters set"
    return {name: int(n) for n, name in re.findall(rf"(\d+) ({names})", line)}


# Frames for nobody on a bench of nodes 4-8: other nodes' SDO, RPDO, guarding and heartbeat
# COB-IDs, a TPDO's COB-ID as data (only its RTR is consumed), a free CAN-ID, a 29-bit frame.
FOR_NOBODY = ["609#4000100000000000", "209#0600", "709#R", "720#05", "184#0000", "123#11", "604#R"]


def send_for_nobody(rounds):
    with can.Bus(interface="socketcan", channel=IFACE) as raw:
        for _ in range(rounds):
            for text in FOR_NOBODY:
                ident, _, payload = text.partition("#")
                if payload == "R":
                    msg = can.Message(arbitration_id=int(ident, 16), is_extended_id=False, is_remote_frame=True)
                else:
                    msg = can.Message(arbitration_id=int(ident, 16), is_extended_id=False, data=bytes.fromhex(payload))
                raw.send(msg, timeout=1.0)
            raw.send(can.Message(arbitration_id=0x1234567, is_extended_id=True, data=b"\x01"), timeout=1.0)


def test_frames_for_no_drive_do_not_wake_the_daemon(bus, start_daemon):
    d = start_daemon(bus, "--node-id", "4-8")
    bus.expect_none(0x704, 0.2)  # settled: nothing is due
    before = d.proc_status("voluntary_ctxt_switches")
    send_for_nobody(50)
    bus.collect(0.3)
    woke = d.proc_status("voluntary_ctxt_switches") - before
    assert woke == 0, f"{woke} wake-ups for {50 * (len(FOR_NOBODY) + 1)} frames addressed to nobody"
    assert bus.sdo_read(8, 0x1000, 0) == 0x00010192  # what a drive consumes still reaches it
    assert d.stop() == EX_OK
    counters = stopped_counters(d)
    assert counters["frames received"] == 1, counters
    assert counters["received for no drive"] == 0, counters


def test_a_trace_sees_the_whole_bus_but_frames_for_nobody_reach_no_drive(bus, start_daemon, tmp_path):
    trace = tmp_path / "trace.log"
    d = start_daemon(bus, "--node-id", "4-8", "--trace", trace)
    send_for_nobody(2)
    assert bus.sdo_read(4, 0x1000, 0) == 0x00010192
    assert d.stop() == EX_OK
    frames = [line.split(" ", 2)[2] for line in trace.read_text().splitlines()]
    assert frames.count("123#11") == 2 and frames.count("01234567#01") == 2
    counters = stopped_counters(d)
    assert counters["received for no drive"] == 2 * (len(FOR_NOBODY) + 1), counters
    assert counters["frames received"] == 2 * (len(FOR_NOBODY) + 1) + 1, counters


def test_a_heartbeat_consumer_written_by_sdo_is_routed_from_the_bus_and_from_a_local_drive(bus, start_daemon):
    d = start_daemon(bus, "--node-id", "4-5")
    # Before node 4 monitors producer 0x20, its heartbeats are filtered out.
    bus.send("720#05")
    bus.sdo_write(4, 0x1016, 1, (0x20 << 16) | 200, 4)
    bus.send("720#05")  # now consumed: starts monitoring, the loss follows 200 ms after
    bus.expect(0x84, EMCY_COMMUNICATION, timeout=1.0)
    # Node 5 monitors node 4, a drive of the same process: its heartbeat is routed locally.
    bus.sdo_write(5, 0x1016, 1, (4 << 16) | 300, 4)
    bus.sdo_write(4, 0x1017, 0, 100, 2)
    bus.expect(0x704, "7F")
    bus.expect_none(0x85, 0.6)  # monitored and alive
    bus.sdo_write(4, 0x1017, 0, 0, 2)
    bus.expect(0x85, EMCY_COMMUNICATION, timeout=1.0)
    assert d.stop() == EX_OK
    counters = stopped_counters(d)
    # 4 SDO requests and the second 720h heartbeat: the first one was for nobody and never read.
    assert counters["frames received"] == 5, counters


def test_the_frames_of_one_wake_up_leave_in_one_sendmmsg(bus, start_daemon):
    d = start_daemon(bus, "--node-id", "4-11")
    for _ in range(5):
        mark = bus.mark()
        bus.nmt(0x82, 0)  # reset communication, broadcast: 8 boot-ups in one wake-up
        for node in range(4, 12):
            bus.expect(0x700 + node, "00", since=mark)
    assert d.stop() == EX_OK
    counters = stopped_counters(d)
    assert counters["sent"] == 6 * 8, counters
    assert counters["sendmmsg calls"] == 6, counters


def test_above_the_kernel_filter_limit_every_11_bit_frame_is_read_and_still_routed(bus, start_daemon):
    # 127 ATV312s consume 4 COB-IDs each (SDO, guarding RTR, RPDO1, TPDO1 RTR), plus NMT and
    # SYNC: 510 filters, CAN_RAW_FILTER_MAX is 512. Three heartbeat consumers make it 513.
    d = start_daemon(bus, "--node-id", "1-127")
    bus.send("123#11")  # still filtered out
    for node, producer in ((1, 127), (2, 126), (3, 125)):
        bus.sdo_write(node, 0x1016, 1, (producer << 16) | 300, 4)
    bus.send("123#11")  # read now, and routed to nobody
    bus.sdo_write(127, 0x1017, 0, 100, 2)  # node 1 monitors it: local routing
    bus.expect(0x77F, "7F")
    bus.expect_none(0x81, 0.5)
    bus.sdo_write(127, 0x1017, 0, 0, 2)
    bus.expect(0x81, EMCY_COMMUNICATION, timeout=1.0)
    assert bus.sdo_read(127, 0x1000, 0) == 0x00010192
    assert d.stop() == EX_OK
    counters = stopped_counters(d)
    assert counters["received for no drive"] == 1, counters
    assert counters["receive filters set"] == 4, counters  # 510, 511, 512, then every 11-bit frame
