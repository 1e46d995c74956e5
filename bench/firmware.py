#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Timing of the firmware on the emulated board (examples/cortex-m4, mps2-an386 in QEMU), printed as
the section "## The firmware on the emulated board" of docs/benchmarks.md (bench/firmware runs it).

    firmware.py --iface slcan0   inside tools/vcan-run + tools/slcan-node: through Linux's slcan
    firmware.py --pty FIRMWARE   on the host: QEMU started here, slcan lines written to its pty

Heartbeat: 1017h = 100 ms, 101 beats, the kernel's (or, with --pty, the reader's) receive times.
SDO: expedited uploads of 1000h one at a time, then bursts of 30 at once.
"""
import argparse
import os
import re
import select
import statistics
import subprocess
import sys
import time
import tty

NODE = 16
BEATS = 101
ROUND_TRIPS = 300
BURST = 30
LINE_BYTES = 22  # "t6108" + 16 data digits + CR: an 8-byte frame in either direction


class SocketCan:
    def __init__(self, iface):
        import can
        self.bus = can.Bus(interface="socketcan", channel=iface)

    def send(self, can_id, data):
        import can
        self.bus.send(can.Message(arbitration_id=can_id, is_extended_id=False, data=data), timeout=5)

    def close(self):
        self.bus.shutdown()

    def recv(self, timeout):
        msg = self.bus.recv(timeout)
        return None if msg is None else (msg.arbitration_id, bytes(msg.data), msg.timestamp)


class Pty:
    """The firmware's UART without Linux's slcan: QEMU's pty, spoken to in slcan lines."""

    def __init__(self, firmware):
        self.qemu = subprocess.Popen(["qemu-system-arm", "-M", "mps2-an386", "-nographic", "-monitor", "none",
                                      "-serial", "pty", "-kernel", firmware], stdout=subprocess.PIPE, text=True)
        pty = re.search(r"(/dev/pts/\d+)", self.qemu.stdout.readline()).group(1)
        self.fd = os.open(pty, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self.fd)
        self.pending = b""

    def close(self):
        os.close(self.fd)
        self.qemu.terminate()
        self.qemu.wait()

    def send(self, can_id, data):
        os.write(self.fd, f"t{can_id:03X}{len(data)}{data.hex().upper()}\r".encode())

    def recv(self, timeout):
        deadline = time.monotonic() + timeout
        while b"\r" not in self.pending:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self.fd], [], [], left)[0]:
                return None
            self.pending += os.read(self.fd, 4096)
        stamp = time.time()
        line, _, self.pending = self.pending.partition(b"\r")
        if not line.startswith(b"t"):
            return self.recv(max(0.0, deadline - time.monotonic()))
        n = int(line[4:5])
        return int(line[1:4], 16), bytes.fromhex(line[5:5 + 2 * n].decode()), stamp


def expect(link, can_id, timeout=5.0):
    deadline = time.monotonic() + timeout
    while True:
        frame = link.recv(max(0.0, deadline - time.monotonic()))
        if frame is None:
            sys.exit(f"firmware.py: no {can_id:03X} within {timeout} s")
        if frame[0] == can_id:
            return frame


def percentile(values, p):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(p / 100 * (len(values) - 1))))]


def main():
    parser = argparse.ArgumentParser()
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--iface")
    group.add_argument("--pty", metavar="FIRMWARE")
    args = parser.parse_args()
    link = SocketCan(args.iface) if args.iface else Pty(args.pty)
    if args.pty:
        expect(link, 0x700 + NODE)  # its boot-up
    sdo_request, sdo_reply = 0x600 + NODE, 0x580 + NODE
    link.send(sdo_request, bytes.fromhex("2B17100064000000"))  # 1017h = 100 ms
    expect(link, sdo_reply)
    beats = [expect(link, 0x700 + NODE)[2] for _ in range(BEATS)]
    link.send(sdo_request, bytes.fromhex("2B17100000000000"))
    expect(link, sdo_reply)
    time.sleep(0.2)
    gaps = [(b - a) * 1e3 for a, b in zip(beats, beats[1:])]
    offsets = [(t - k * 0.1) * 1e3 for k, t in enumerate(beats)]
    rtts = []
    for _ in range(ROUND_TRIPS):
        start = time.perf_counter()
        link.send(sdo_request, bytes.fromhex("4000100000000000"))
        expect(link, sdo_reply)
        rtts.append((time.perf_counter() - start) * 1e3)
    start = time.perf_counter()
    for _ in range(BURST):
        link.send(sdo_request, bytes.fromhex("4000100000000000"))
    for _ in range(BURST):
        expect(link, sdo_reply)
    burst_s = time.perf_counter() - start
    where = (f"through Linux's slcan on {args.iface} in User-Mode Linux" if args.iface
             else "on the host, slcan lines written straight to QEMU's pty")
    print(f"| {where} | {statistics.mean(gaps):.2f} ms ({(statistics.mean(gaps) - 100) * 1e4:+.0f} ppm) | "
          f"{min(gaps):.1f} / {max(gaps):.1f} ms | {max(offsets) - min(offsets):.1f} ms | "
          f"{statistics.median(rtts):.2f} ms | {percentile(rtts, 99):.2f} ms | {max(rtts):.2f} ms | "
          f"{2 * LINE_BYTES * BURST / burst_s:.0f} B/s |")
    link.close()


if __name__ == "__main__":
    main()
