# SPDX-License-Identifier: Apache-2.0
"""Helpers the benchmarks inside User-Mode Linux share (bench/scale.py, bench/socketcan.py): the
daemon's CPU time, wake-ups and system calls read from inside the guest, and SDO requests from a
python-can client."""

import os
import subprocess
import sys
import time

import can

CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def proc_stat_cpu(pid):
    """Seconds of CPU time (utime + stime) the process has used."""
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / CLOCK_TICKS


def proc_status(pid, key):
    """A numeric field of /proc/PID/status, e.g. voluntary_ctxt_switches (the wake-ups)."""
    for line in open(f"/proc/{pid}/status"):
        name, _, value = line.partition(":")
        if name == key:
            return int(value.split()[0])
    raise KeyError(key)


def strace_counts(stderr):
    """{syscall: calls} from the table strace -c prints."""
    calls = {}
    for line in stderr.splitlines():
        fields = line.split()
        if len(fields) >= 5 and fields[0][0].isdigit() and fields[-1] != "total":
            calls[fields[-1]] = int(fields[3])
    return calls


def syscalls(pid, seconds):
    """{syscall: calls} of the process over `seconds`, by strace -c."""
    run = subprocess.run(["timeout", "-s", "INT", str(seconds), "strace", "-c", "-p", str(pid)],
                         capture_output=True, text=True)
    return strace_counts(run.stderr)


def wait_for(bus, predicate, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        msg = bus.recv(timeout=max(0.0, deadline - time.monotonic()))
        if msg is not None and not msg.is_error_frame and predicate(msg):
            return msg
    return None


def sdo_request(bus, node, data, who):
    """Sends one SDO request to `node` and returns its reply; exits naming `who` when there is
    none or the node aborts."""
    bus.send(can.Message(arbitration_id=0x600 + node, is_extended_id=False, data=data))
    reply = wait_for(bus, lambda m: m.arbitration_id == 0x580 + node, 5.0)
    if reply is None:
        sys.exit(f"{who}: no SDO reply from node {node}")
    if reply.data[0] == 0x80:
        sys.exit(f"{who}: node {node} aborted {data.hex()}: {bytes(reply.data).hex()}")
    return reply
