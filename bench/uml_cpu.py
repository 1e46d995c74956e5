# SPDX-License-Identifier: Apache-2.0
"""The host's view of the CPU time a User-Mode Linux guest spends between marks the guest sets:

    uml_cpu.py MARK_DIR COMMAND...

Runs COMMAND (taskset ... tools/vcan-run ...), passing its stdout through. A program in the guest
sets a mark by creating MARK_DIR/NAME (the guest's root is the host's filesystem) and waiting for
MARK_DIR/NAME.ack; meanwhile this reads the CPU time (utime + stime, with that of reaped children)
of every host process below COMMAND, so the UML kernel, every guest program and what UML charges
to nobody in the guest, and acknowledges. Writes {NAME: host CPU seconds at the mark} to
MARK_DIR/host_cpu.json and exits with COMMAND's status. The guest side is mark() below."""

import json
import os
import subprocess
import sys
import time

POLL_S = 0.005
ACK_TIMEOUT_S = 10.0
CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def mark(mark_dir, name):
    """Guest side: stops until the host has read its CPU time at this point."""
    if not mark_dir:
        return
    open(os.path.join(mark_dir, name), "w").close()
    ack = os.path.join(mark_dir, name + ".ack")
    deadline = time.monotonic() + ACK_TIMEOUT_S
    while not os.path.exists(ack):
        if time.monotonic() > deadline:
            sys.exit(f"uml_cpu.py: the host did not acknowledge mark {name}")
        time.sleep(POLL_S)


def tree_cpu(root):
    """Seconds of CPU time of `root` and every process below it, reaped children included."""
    parents, cpu = {}, {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            fields = open(f"/proc/{entry}/stat").read().rsplit(")", 1)[1].split()
        except OSError:
            continue  # it exited meanwhile
        pid = int(entry)
        parents[pid] = int(fields[1])
        cpu[pid] = sum(int(f) for f in fields[11:15]) / CLOCK_TICKS
    total = 0.0
    for pid, seconds in cpu.items():
        ancestor = pid
        while ancestor not in (root, 0, 1) and ancestor in parents:
            ancestor = parents[ancestor]
        if ancestor == root:
            total += seconds
    return total


def main():
    mark_dir, command = sys.argv[1], sys.argv[2:]
    child = subprocess.Popen(command)
    marks = {}
    while child.poll() is None:
        for name in os.listdir(mark_dir):
            if name.endswith(".ack") or name in marks or name == "host_cpu.json":
                continue
            marks[name] = tree_cpu(child.pid)
            open(os.path.join(mark_dir, name + ".ack"), "w").close()
        time.sleep(POLL_S)
    with open(os.path.join(mark_dir, "host_cpu.json"), "w") as out:
        json.dump(marks, out)
    sys.exit(child.returncode)


if __name__ == "__main__":
    main()
