#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Records tests/cotrace/atv312.log, the trace cotrace's tool test decodes: atv312d --trace while
a master plays every kind of frame cotrace knows at node 4. Run it where vcan0 exists:

  tools/vcan-run .venv/bin/python tests/cotrace/record_trace.py build/apps/atv312d/atv312d \\
      tests/cotrace/atv312.log

then regenerate the expected text and review the difference before committing both:

  build/apps/cotrace/cotrace --eds eds/ATV312.eds --node 4 tests/cotrace/atv312.log \\
      > tests/cotrace/atv312.expected

The sequence: boot-up; expedited, segmented and block uploads; expedited, segmented and block
downloads; server aborts and a client abort; heartbeat on and off; node guarding with toggle;
NMT start; SYNC with a wrong length (EMCY 8240h); TIME; PDO6 enabled and the CiA 402 state
machine walked to a speed and back; life guarding lost (EMCY 8130h) and a fault reset (EMCY
0000h); NMT stop, pre-operational, reset communication.
"""

import subprocess
import sys
import time

import can

NODE = 4
SDO_RX, SDO_TX, EMCY, NMT_EC = 0x600 + NODE, 0x580 + NODE, 0x080 + NODE, 0x700 + NODE


class Master:
    def __init__(self, bus):
        self.bus = bus

    def send(self, can_id, data=b"", remote=False):
        self.bus.send(can.Message(arbitration_id=can_id, data=data, is_extended_id=False,
                                  is_remote_frame=remote, dlc=len(data)))

    def expect(self, can_id, timeout=2.0, data=None):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            msg = self.bus.recv(deadline - time.monotonic())
            if msg and msg.arbitration_id == can_id and (data is None or bytes(msg.data) == data):
                return bytes(msg.data)
        sys.exit(f"record_trace: no frame {can_id:03X}#{'' if data is None else data.hex()} "
                 f"within {timeout} s")

    def sdo(self, request):
        self.send(SDO_RX, bytes(request))
        return self.expect(SDO_TX)

    def segmented_upload(self, index, sub):
        reply = self.sdo([0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0])
        toggle = 0
        while True:
            reply = self.sdo([0x60 | toggle, 0, 0, 0, 0, 0, 0, 0])
            toggle ^= 0x10
            if reply[0] & 0x01:
                return

    def block_upload(self, index, sub):
        self.sdo([0xA4, index & 0xFF, index >> 8, sub, 127, 0, 0, 0])
        self.send(SDO_RX, bytes([0xA3, 0, 0, 0, 0, 0, 0, 0]))
        seq = 0
        while True:
            segment = self.expect(SDO_TX)
            seq = segment[0] & 0x7F
            if segment[0] & 0x80:
                break
        end = self.sdo([0xA2, seq, 127, 0, 0, 0, 0, 0])
        assert end[0] & 0xE3 == 0xC1, end.hex()
        self.send(SDO_RX, bytes([0xA1, 0, 0, 0, 0, 0, 0, 0]))

    def write_u32(self, index, sub, value):
        self.sdo([0x23, index & 0xFF, index >> 8, sub] + list(value.to_bytes(4, "little")))

    def write_u16(self, index, sub, value):
        self.sdo([0x2B, index & 0xFF, index >> 8, sub] + list(value.to_bytes(2, "little")) + [0, 0])


def crc16_ccitt(data):
    crc = 0
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = (crc << 1 ^ 0x1021 if crc & 0x8000 else crc << 1) & 0xFFFF
    return crc


def play(m):
    m.expect(NMT_EC, 5.0, b"\x00")  # boot-up
    m.sdo([0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0])  # expedited upload of 1000h
    m.segmented_upload(0x1008, 0)  # "ATV312", segmented
    m.block_upload(0x1008, 0)
    m.write_u16(0x203C, 2, 10)  # ACC = 1.0 s, expedited
    # 6046:02 (maximum speed) = 1500 rpm, segmented then by block (4 bytes each)
    value = (1500).to_bytes(4, "little")
    m.sdo([0x21, 0x46, 0x60, 0x02, 4, 0, 0, 0])
    m.sdo([0x07] + list(value) + [0, 0, 0])
    m.sdo([0xC6, 0x46, 0x60, 0x02, 4, 0, 0, 0])
    m.send(SDO_RX, bytes([0x81]) + value + bytes(3))
    m.expect(SDO_TX)
    crc = crc16_ccitt(value)
    m.sdo([0xC1 | 3 << 2, crc & 0xFF, crc >> 8, 0, 0, 0, 0, 0])
    m.sdo([0x40, 0x34, 0x12, 0x00, 0, 0, 0, 0])  # abort: no such object
    m.write_u32(0x1000, 0, 0)  # abort: read only
    m.sdo([0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0])  # a segmented upload the client aborts
    m.send(SDO_RX, bytes([0x80, 0x08, 0x10, 0x00, 0x00, 0x00, 0x04, 0x05]))
    m.write_u16(0x1017, 0, 100)  # heartbeat every 100 ms
    m.expect(NMT_EC, 1.0, b"\x7f")
    m.expect(NMT_EC, 1.0, b"\x7f")
    m.write_u16(0x1017, 0, 0)
    m.write_u16(0x100C, 0, 200)  # guard time 200 ms, life time factor 3
    m.sdo([0x2F, 0x0D, 0x10, 0x00, 3, 0, 0, 0])
    for _ in range(2):
        m.send(NMT_EC, remote=True)
        m.expect(NMT_EC)
    m.send(0x000, bytes([0x01, NODE]))  # NMT start
    m.send(NMT_EC, remote=True)
    m.expect(NMT_EC)
    m.send(0x080)  # SYNC
    m.send(0x080, bytes([1]))  # a counter the drive does not expect (1019h = 0)
    m.expect(EMCY)
    m.send(0x080)
    m.expect(EMCY)  # the good SYNC ends the error
    m.send(0x100, bytes.fromhex("80EE3603A515"))  # TIME 1999-03-04 14:58:51.648
    m.send(NMT_EC, remote=True)
    m.expect(NMT_EC)
    # PDO6: control word + speed reference in, status word + speed out
    m.sdo([0x23, 0x05, 0x14, 0x01, 0x04, 0x03, 0x00, 0x00])
    m.sdo([0x23, 0x05, 0x18, 0x01, 0x84, 0x02, 0x00, 0x00])
    for control, reference, status in [(0x0006, 0, 0x21), (0x0007, 0, 0x23),
                                       (0x000F, 300, 0x27)]:
        m.send(0x300 + NODE, control.to_bytes(2, "little") + reference.to_bytes(2, "little"))
        deadline = time.monotonic() + 2
        while (int.from_bytes(m.expect(0x280 + NODE), "little") & 0x6F) != status:
            assert time.monotonic() < deadline
    m.send(NMT_EC, remote=True)
    m.expect(NMT_EC)
    while int.from_bytes(m.expect(0x280 + NODE)[2:4], "little") != 300:
        pass
    # no more guarding: life guarding lost, the drive faults (EMCY 8130h)
    m.expect(EMCY, 2.0)
    m.send(0x300 + NODE, (0x0080).to_bytes(2, "little") + bytes(2))  # fault reset
    m.expect(EMCY, 2.0)
    m.send(0x000, bytes([0x02, NODE]))  # NMT stop
    m.send(0x000, bytes([0x80, 0]))  # all nodes to pre-operational
    m.write_u16(0x100C, 0, 0)
    m.send(0x000, bytes([0x82, NODE]))  # reset communication
    m.expect(NMT_EC, 2.0, b"\x00")


def main():
    daemon_path, log_path = sys.argv[1], sys.argv[2]
    bus = can.Bus(interface="socketcan", channel="vcan0")
    daemon = subprocess.Popen([daemon_path, "vcan0", "--node-id", str(NODE), "--trace", log_path])
    try:
        play(Master(bus))
        time.sleep(0.05)
    finally:
        daemon.terminate()
        daemon.wait(5)
        bus.shutdown()


if __name__ == "__main__":
    main()
