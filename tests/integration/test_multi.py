# SPDX-License-Identifier: Apache-2.0
"""Several drives in one atv312d process (one loop, one socket): each boots and answers on its own
node-id, as a bench of drives for testing a master (docs/decisions.md, D-SEVERAL-DRIVES)."""

import pytest

from conftest import Frame

DEVICE_TYPE = bytes.fromhex("92010100")  # 1000h = 0x00010192


def read_request(node, index, sub):
    return Frame(0x600 + node, bytes([0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0]))


@pytest.mark.parametrize(
    "args, nodes",
    [(["--node-id", "4-6"], [4, 5, 6]),
     (["--node-id", "4", "--node-id", "9"], [4, 9]),
     (["--node-id", "7,5"], [5, 7]),
     (["--node-id", "4-5", "--model", "atv312", "--node-id", "6"], [4, 5, 6])],
    ids=["range", "repeated", "list", "models"],
)
def test_each_drive_boots_and_answers_sdo_on_its_own_id(bus, start_daemon, args, nodes):
    start_daemon(bus, *args, boot_ids=nodes)
    for node in nodes:
        reply = bus.request(read_request(node, 0x1000, 0), 0x580 + node)
        assert reply.data == bytes([0x43, 0x00, 0x10, 0x00]) + DEVICE_TYPE
        assert bus.sdo_read(node, 0x100B, 0) == node
        assert bus.sdo_read(node, 0x1200, 1) == 0x600 + node
    others = [n for n in range(1, 12) if n not in nodes]
    bus.send(read_request(others[0], 0x1000, 0))
    bus.expect_none(0x580 + others[0], 0.3)


def test_start_line_names_the_model_of_each_drive(bus, start_daemon):
    d = start_daemon(bus, "--node-id", "4-5", "--model=atv312", "--node-id", "6")
    assert "3 drive(s), node-id 4,5,6 (atv312)" in d.log(), d.log()


def upload_device_name(bus, node):
    """1008h by segmented upload, as raw frames: the initiate reply gives the size, one segment of
    up to 7 bytes the name (both models' names are shorter)."""
    reply = bus.request(read_request(node, 0x1008, 0), 0x580 + node)
    assert reply.data[:4] == bytes([0x41, 0x08, 0x10, 0x00]), reply
    size = int.from_bytes(reply.data[4:8], "little")
    segment = bus.request(Frame(0x600 + node, bytes([0x60]) + bytes(7)), 0x580 + node)
    assert segment.data[0] == 0x01 | (7 - size) << 1, segment  # last segment, 7 - size unused
    return segment.data[1:1 + size].decode()


def test_mixed_bench_of_atv312_and_atv31(bus, start_daemon):
    d = start_daemon(bus, "--node-id", "4", "--model", "atv312", "--node-id", "5", "--model", "atv31",
                     "--node-id", "6", "--model", "atv31-v1.1")
    assert "3 drive(s), node-id 4 (atv312), 5 (atv31), 6 (atv31-v1.1)" in d.log(), d.log()
    assert [upload_device_name(bus, node) for node in (4, 5, 6)] == ["ATV312", "ATV31", "ATV31"]
    # Heartbeat from the ATV31 of firmware V1.2 on; the one before has no 1017h.
    bus.sdo_write(5, 0x1017, 0, 100, 2)
    bus.expect(0x705, "7F")
    assert bus.sdo_abort_code(6, "2B17100064000000") == 0x06020000  # object does not exist
    # The three run the same drive: each answers its own RPDO1 with its TPDO1.
    bus.nmt(0x01, 0)
    for node in (4, 5, 6):
        bus.expect(0x180 + node, "4006")
    bus.send("205#0600")
    bus.expect(0x185, "2106")
    assert bus.sdo_read(4, 0x6041, 0) == 0x0640
    assert bus.sdo_read(6, 0x6041, 0) == 0x0640


def test_broadcast_nmt_reaches_every_drive_and_a_single_one_only_its_own(bus, start_daemon):
    start_daemon(bus, "--node-id", "4-6")
    bus.nmt(0x01, 5)  # start node 5 only
    bus.expect(0x185, "4006")
    frames = bus.collect(0.35)
    assert {f.can_id for f in frames if 0x180 <= f.can_id < 0x200} == {0x185}
    bus.nmt(0x01, 0)  # start all
    for node in (4, 6):
        bus.expect(0x180 + node, "4006")


def test_drives_are_independent(bus, start_daemon):
    start_daemon(bus, "--node-id", "4-5")
    bus.sdo_write(4, 0x203C, 2, 55, 2)
    assert bus.sdo_read(4, 0x203C, 2) == 55
    assert bus.sdo_read(5, 0x203C, 2) == 30  # the other drive keeps its default
    bus.nmt(0x01, 0)
    bus.send("204#0600")  # shutdown to drive 4 only
    bus.expect(0x184, "2106")
    assert bus.sdo_read(5, 0x6041, 0) == 0x0640
