"""What a PLC relies on, on the running daemon over SocketCAN: how the motor stops on each way out
of Operation enabled and Quick stop active, and what storage keeps across a restart (SPEC.md
section 3, "Stops" and "Storage")."""

import time

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

