# SPDX-License-Identifier: Apache-2.0
"""The cost of many drives in one atv312d (issue 10): run inside tools/vcan-run by bench/scale.

    scale.py DAEMON LABEL [--nodes 127] [--seconds 20] [--round-trips 300]

Starts DAEMON on vcan0 with drives 1..N and a store file. While the drives are idle it sends 1000
frames no drive consumes and counts the wake-ups and CPU time they cost. Then it gives each drive
a 100 ms heartbeat (1017h by SDO, one drive after the other: without the heartbeat grid the
periods start at different times, "spread") and saves it (1010h:02), and measures from /proc/PID the CPU time (utime +
stime) and the wake-ups (voluntary context switches) over SECONDS. It restarts the daemon on the
store, so that every heartbeat starts at the boot-up ("aligned"), measures again, reads the
resident memory and times SDO round trips (expedited upload of 1000h) to drive 1 and drive N,
alternated, over the same bus load. In both runs it counts the daemon's system calls over 5 s
(strace -c), which the machine's load does not change. Prints one JSON object for bench/scale."""

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import can

import benchproc
from benchproc import CLOCK_TICKS, proc_stat_cpu, proc_status, syscalls, wait_for

IFACE = "vcan0"
# A free CAN-ID, the last drive's TPDO1 as data (only its RTR is consumed), its SDO reply, its
# heartbeat (nobody monitors it), LSS.
FOR_NOBODY = [0x123, 0x1FF, 0x5FF, 0x77F, 0x7E5]


def sdo_request(bus, node, data):
    return benchproc.sdo_request(bus, node, data, "scale.py")


def round_trip(bus, node):
    started = time.perf_counter()
    sdo_request(bus, node, bytes([0x40, 0x00, 0x10, 0, 0, 0, 0, 0]))
    return (time.perf_counter() - started) * 1e6


def start_daemon(daemon, last, store, log_path):
    with open(log_path, "wb") as log:
        return subprocess.Popen([daemon, IFACE, "--node-id", f"1-{last}", "--store", store],
                                stdout=log, stderr=subprocess.STDOUT)


def stop_daemon(daemon, log_path):
    daemon.send_signal(signal.SIGTERM)
    daemon.wait(timeout=10)
    return open(log_path).read().strip().splitlines()[-1]


def wait_boot(bus, last):
    booted = set()
    while len(booted) < last:
        msg = wait_for(bus, lambda m: 0x701 <= m.arbitration_id <= 0x77F and bytes(m.data) == b"\0", 10.0)
        if msg is None:
            sys.exit(f"scale.py: {len(booted)} of {last} drives booted")
        booted.add(msg.arbitration_id)


WINDOWS = 4


def measure(pid, seconds):
    """CPU (% of a core) in each of WINDOWS equal windows of `seconds`, and the wake-ups per
    second over all of them. A window whose guest was preempted by the loaded host shows more CPU
    than the daemon used: bench/scale reports the median window."""
    shares = []
    wake0 = proc_status(pid, "voluntary_ctxt_switches")
    t0 = time.monotonic()
    for _ in range(WINDOWS):
        cpu0, w0 = proc_stat_cpu(pid), time.monotonic()
        time.sleep(seconds / WINDOWS)
        shares.append(round(100 * (proc_stat_cpu(pid) - cpu0) / (time.monotonic() - w0), 2))
    wakeups = proc_status(pid, "voluntary_ctxt_switches") - wake0
    return shares, round(wakeups / (time.monotonic() - t0), 1)


def frames_for_nobody(bus, pid):
    """Wake-ups and CPU milliseconds of the idle daemon while 1000 frames for nobody pass."""
    time.sleep(0.5)
    wake0, cpu0 = proc_status(pid, "voluntary_ctxt_switches"), proc_stat_cpu(pid)
    for _ in range(200):
        for can_id in FOR_NOBODY:
            bus.send(can.Message(arbitration_id=can_id, is_extended_id=False, data=b"\x01"))
    time.sleep(0.5)
    return proc_status(pid, "voluntary_ctxt_switches") - wake0, round((proc_stat_cpu(pid) - cpu0) * 1000)


def syscalls(pid, seconds):
    """{syscall: calls} of the daemon over `seconds`, by strace -c."""
    run = subprocess.run(["timeout", "-s", "INT", str(seconds), "strace", "-c", "-p", str(pid)],
                         capture_output=True, text=True)
    calls = {}
    for line in run.stderr.splitlines():
        fields = line.split()
        if len(fields) >= 5 and fields[0][0].isdigit() and fields[-1] != "total":
            calls[fields[-1]] = int(fields[3])
    return calls


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("daemon")
    parser.add_argument("label")
    parser.add_argument("--nodes", type=int, default=127)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--round-trips", type=int, default=300)
    args = parser.parse_args()
    last = args.nodes
    # A new directory for each run: the guest's process ids repeat from one boot to the next, and
    # a store file left by an earlier run would start every heartbeat at the boot-up.
    workdir = tempfile.mkdtemp(prefix="scale-")
    store = os.path.join(workdir, "drives.store")
    log_path = os.path.join(workdir, "atv312d.log")
    result = {"label": args.label, "nodes": last, "window_s": args.seconds / WINDOWS, "tick_s": 1 / CLOCK_TICKS}
    bus = can.Bus(interface="socketcan", channel=IFACE, receive_own_messages=False)
    try:
        # 1. Idle drives: the cost of frames for nobody. Then heartbeats written by SDO one drive
        #    after the other, each starting its period at its write (or at the next multiple of
        #    the period on the heartbeat grid): without the grid the phases are spread.
        daemon = start_daemon(args.daemon, last, store, log_path)
        wait_boot(bus, last)
        result["nobody_wakeups"], result["nobody_cpu_ms"] = frames_for_nobody(bus, daemon.pid)
        for node in range(1, last + 1):
            sdo_request(bus, node, bytes([0x2B, 0x17, 0x10, 0x00, 100, 0, 0, 0]))
            sdo_request(bus, node, bytes([0x23, 0x10, 0x10, 0x02]) + b"save")
        # Our own socket would be woken by every heartbeat: filter it to the SDO replies.
        bus.set_filters([{"can_id": 0x580, "can_mask": 0x780, "extended": False}])
        time.sleep(1.0)
        result["spread_cpu_percent"], result["spread_wakeups_per_s"] = measure(daemon.pid, args.seconds)
        result["spread_syscalls_5s"] = syscalls(daemon.pid, 5)
        result["spread_stopped"] = stop_daemon(daemon, log_path)

        # 2. The same drives restarted with their stored 1017h: every heartbeat on one period.
        bus.set_filters([{"can_id": 0x700, "can_mask": 0x780, "extended": False},
                         {"can_id": 0x580, "can_mask": 0x780, "extended": False}])
        daemon = start_daemon(args.daemon, last, store, log_path)
        wait_boot(bus, last)
        bus.set_filters([{"can_id": 0x580, "can_mask": 0x780, "extended": False}])
        time.sleep(1.0)
        result["aligned_cpu_percent"], result["aligned_wakeups_per_s"] = measure(daemon.pid, args.seconds)
        result["rss_kib"] = proc_status(daemon.pid, "VmRSS")
        result["aligned_syscalls_5s"] = syscalls(daemon.pid, 5)
        first, far = [], []
        for _ in range(args.round_trips):
            first.append(round_trip(bus, 1))
            far.append(round_trip(bus, last))
        result["sdo_first_median_us"] = round(statistics.median(first))
        result["sdo_last_median_us"] = round(statistics.median(far))
        result["aligned_stopped"] = stop_daemon(daemon, log_path)
    finally:
        bus.shutdown()
        shutil.rmtree(workdir, ignore_errors=True)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
