# SPDX-License-Identifier: Apache-2.0
"""What a PLC relies on, on the running daemon over SocketCAN: how the motor stops on each way out
of Operation enabled and Quick stop active, and what storage keeps across a restart
(docs/decisions.md, D-STOPS and D-STORE-PARAMETERS)."""

import time
import zlib

from conftest import Frame

NODE = 4
SAVE = 0x65766173  # "save" (CiA 301 1010h)
LOAD = 0x64616F6C  # "load" (CiA 301 1011h)
SWITCH_ON_DISABLED = 0x0640  # with bit 9 (remote) and bit 10 (target reached)


def wait_for_speed(bus, rpm, timeout=3.0):
    """Reads 6044h until it equals rpm; fails with the last value after the deadline."""
    deadline = time.monotonic() + timeout
    while True:
        speed = bus.sdo_read(NODE, 0x6044, 0)
        if speed == rpm or time.monotonic() > deadline:
            assert speed == rpm, f"6044h = {speed} rpm after {timeout} s, want {rpm}"
            return
        time.sleep(0.02)


def run_at_1500_with_slow_dec(bus):
    bus.sdo_write(NODE, 0x203C, 2, 5, 2)  # ACC 0.5 s
    bus.sdo_write(NODE, 0x203C, 3, 40, 2)  # DEC 4.0 s: the fast ramp is 1.0 s
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    wait_for_speed(bus, 1500)


def assert_coasting(bus):
    assert bus.sdo_read(NODE, 0x6041, 0) == SWITCH_ON_DISABLED
    assert bus.sdo_read(NODE, 0x6044, 0) == 0
    assert bus.sdo_read(NODE, 0x2002, 4) == 0  # LCR: no current
    assert bus.sdo_read(NODE, 0x2002, 9) == 0  # OTR: no torque


def test_disable_voltage_after_quick_stop_cuts_the_output(bus, drive):
    run_at_1500_with_slow_dec(bus)
    # The frames: quick stop, then disable voltage.
    bus.request(Frame.parse("604#2B40600002000000"), 0x584, "6040600000000000")
    assert bus.sdo_read(NODE, 0x6041, 0) & 0x006F == 0x0007  # Quick stop active
    bus.request(Frame.parse("604#2B40600000000000"), 0x584, "6040600000000000")
    assert_coasting(bus)


def test_disable_voltage_after_disable_operation_cuts_the_output(bus, drive):
    run_at_1500_with_slow_dec(bus)
    bus.sdo_write(NODE, 0x6040, 0, 0x0007, 2)
    # Disable operation ramps on DEC (4 s) in Operation enabled, output on.
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0227
    assert bus.sdo_read(NODE, 0x2002, 4) > 0
    bus.sdo_write(NODE, 0x6040, 0, 0x0000, 2)
    assert_coasting(bus)



def restart(d, bus, start_daemon, store):
    assert d.stop() == 0
    return start_daemon(bus, "--node-id", NODE, "--store", store)


def test_process_data_never_come_back_from_storage(bus, start_daemon, tmp_path):
    store = tmp_path / "drives.dat"
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x6042, 0, 1200, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    wait_for_speed(bus, 1200)
    bus.request(Frame.parse("604#2310100173617665"), 0x584, "6010100100000000")  # save all
    d = restart(d, bus, start_daemon, store)
    assert bus.sdo_read(NODE, 0x6040, 0) == 0
    assert bus.sdo_read(NODE, 0x2037, 2) == 0
    assert bus.sdo_read(NODE, 0x6042, 0) == 0
    assert bus.sdo_read(NODE, 0x6041, 0) == SWITCH_ON_DISABLED
    for control in (0x0006, 0x0007, 0x000F):
        bus.sdo_write(NODE, 0x6040, 0, control, 2)
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0627  # enabled, at its target: 0 rpm
    assert bus.sdo_read(NODE, 0x6044, 0) == 0


def test_profile_area_keeps_and_restores_what_its_views_stand_for(bus, start_daemon, tmp_path):
    store = tmp_path / "drives.dat"
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x6046, 2, 1200, 4)
    bus.sdo_write(NODE, 0x1010, 3, SAVE, 4)
    d = restart(d, bus, start_daemon, store)
    assert bus.sdo_read(NODE, 0x6046, 2) == 1200
    assert bus.sdo_read(NODE, 0x2001, 5) == 400  # HSP 40.0 Hz
    bus.sdo_write(NODE, 0x1010, 1, SAVE, 4)
    bus.sdo_write(NODE, 0x1011, 3, LOAD, 4)
    bus.nmt(0x81, NODE)  # reset node
    bus.expect(0x700 + NODE, "00")
    assert bus.sdo_read(NODE, 0x6046, 2) == 1500
    assert bus.sdo_read(NODE, 0x2001, 5) == 500


def image_records(image):
    """(offset of the value, index, sub, length) of each record of a core image (co_store.h)."""
    offset = 9
    while offset < len(image):
        index, sub, length = int.from_bytes(image[offset:offset + 2], "little"), image[offset + 2], \
            int.from_bytes(image[offset + 3:offset + 5], "little")
        yield offset + 5, index, sub, length
        offset += 5 + length


def set_stored_value(store, node, area, index, sub, value):
    """Rewrites one stored value in a store file (docs/atv312d.md), CRC-32 recomputed."""
    content = bytearray(store.read_bytes())
    offset = 12
    while offset < len(content) - 4:
        rec_node, rec_area, length = content[offset], content[offset + 1], \
            int.from_bytes(content[offset + 4:offset + 8], "little")
        image = offset + 8
        if (rec_node, rec_area) == (node, area):
            for at, i, s, size in image_records(content[image:image + length]):
                if (i, s) == (index, sub):
                    content[image + at:image + at + size] = value.to_bytes(size, "little")
                    content[-4:] = zlib.crc32(bytes(content[:-4])).to_bytes(4, "little")
                    store.write_bytes(bytes(content))
                    return
        offset = image + length
    raise AssertionError(f"no stored {index:04X}:{sub:02X} for node {node} area {area}")


def test_stored_value_outside_its_limits_is_reported_and_skipped(bus, start_daemon, tmp_path):
    store = tmp_path / "drives.dat"
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    bus.sdo_write(NODE, 0x203C, 2, 50, 2)
    bus.sdo_write(NODE, 0x1010, 1, SAVE, 4)
    assert d.stop() == 0
    set_stored_value(store, NODE, 4, 0x2042, 5, 0)  # NSP = 0, limits 1..32767
    d = start_daemon(bus, "--node-id", NODE, "--store", store)
    assert bus.sdo_read(NODE, 0x2042, 5) == 1500
    assert bus.sdo_read(NODE, 0x203C, 2) == 50  # the rest of the image applies
    bus.request(Frame.parse("604#2B48600201000000"), 0x584, "6048600200000000")
    assert d.running()
    assert "stored 2042h:05 (NSP nominal motor speed (rpm)) = 0x0000 refused (SDO abort 0x06090032" \
        in d.log(), d.log()
