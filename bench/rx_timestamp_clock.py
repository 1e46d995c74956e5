# SPDX-License-Identifier: Apache-2.0
"""Which clock the kernel's receive timestamp of a CAN frame (SO_TIMESTAMPNS) follows, before and
after a step of the wall clock (clock_settime + 1 h, put back at the end): the evidence of
docs/runtime.md, "Why the clock is read per wake-up". Needs root and vcan0:

    tools/vcan-run .venv/bin/python bench/rx_timestamp_clock.py
"""
import socket, struct, time
SO_TIMESTAMPNS = 35
tx = socket.socket(socket.PF_CAN, socket.SOCK_RAW, socket.CAN_RAW); tx.bind(("vcan0",))
rx = socket.socket(socket.PF_CAN, socket.SOCK_RAW, socket.CAN_RAW); rx.bind(("vcan0",))
rx.setsockopt(socket.SOL_SOCKET, SO_TIMESTAMPNS, 1)
def one(label):
    mono0, real0 = time.clock_gettime(time.CLOCK_MONOTONIC), time.clock_gettime(time.CLOCK_REALTIME)
    tx.send(struct.pack("=IB3x8s", 0x604, 8, bytes(8)))
    data, anc, flags, addr = rx.recvmsg(16, 1024)
    sec, nsec = struct.unpack("qq", anc[0][2][:16])
    stamp = sec + nsec / 1e9
    print(f"{label}: rx stamp - CLOCK_REALTIME {stamp - real0:+.6f} s, rx stamp - CLOCK_MONOTONIC {stamp - mono0:+.3f} s, "
          f"REALTIME - MONOTONIC {real0 - mono0:.3f} s")
one("before the step")
time.clock_settime(time.CLOCK_REALTIME, time.clock_gettime(time.CLOCK_REALTIME) + 3600)
one("after +1 h step ")
time.clock_settime(time.CLOCK_REALTIME, time.clock_gettime(time.CLOCK_REALTIME) - 3600)
