# SPDX-License-Identifier: Apache-2.0
"""A large network booted and supervised by `comaster run` (issue 31): run inside tools/vcan-run by
bench/netmaster.

    netmaster.py ATV312D COMASTER [--drives 21] [--io 21] [--plc300 21] [--sync 10] [--seconds 10]

Starts ATV312D with node-ids 1.. as Altivar 312 drives, then CiA 401 I/O nodes, then PLC300
slaves (63 together by default, the PLC300 master's limit), and `comaster run` on a nodelist whose
DCFs are the models' EDS files (their default PDOs make the process image), with SYNC every
--sync ms. Measures the boot time, from the run's start to the master's init-finished line, and
over --seconds the cycle: the SYNC period (mean, worst) and, after each SYNC, the time until the
last output PDO of the master (its cycle's burst) and the frames of the cycle. Prints one JSON
object."""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import can

IFACE = "vcan0"
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = (("drives", "atv312", "ATV312.eds", "drive"), ("io", "io", "IO401.eds", "io"),
          ("plc300", "plc300", "PLC300.eds", "plc"))


def network(tmp, counts, sync_ms):
    nodes = []
    for (key, model, eds, prefix) in MODELS:
        shutil.copy(os.path.join(ROOT, "eds", eds), tmp)
        first = len(nodes) + 1
        nodes += [(n, model, eds, prefix) for n in range(first, first + counts[key])]
    with open(os.path.join(tmp, "net.cpj"), "w") as f:
        f.write(f"[Topology]\nNetName=large\nNodes=0x{len(nodes):02X}\n")
        for n, _, eds, prefix in nodes:
            f.write(f"Node{n}Present=0x01\nNode{n}Name={prefix}{n}\nNode{n}DCFName={eds}\n")
    with open(os.path.join(tmp, "net.ini"), "w") as f:
        f.write(f"[Master]\ncpj = net.cpj\ninterface = {IFACE}\nsdo_timeout = 500\nboot_time = 1000\n"
                f"retry_delay = 1000\nstart = each\nsync_period = {sync_ms}\n")
    return nodes


def daemon_args(nodes):
    args = []
    for n, model, _, _ in nodes:
        args += ["--node-id", str(n), "--model", model]
    return args


def main():
    p = argparse.ArgumentParser()
    p.add_argument("atv312d")
    p.add_argument("comaster")
    p.add_argument("--drives", type=int, default=21)
    p.add_argument("--io", type=int, default=21)
    p.add_argument("--plc300", type=int, default=21)
    p.add_argument("--sync", type=int, default=10)
    p.add_argument("--seconds", type=float, default=10.0)
    a = p.parse_args()
    counts = {"drives": a.drives, "io": a.io, "plc300": a.plc300}
    tmp = tempfile.mkdtemp()
    nodes = network(tmp, counts, a.sync)
    daemon = subprocess.Popen([a.atv312d, IFACE] + daemon_args(nodes), stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    time.sleep(0.5)
    start = time.monotonic()
    run = subprocess.Popen([a.comaster, "run", os.path.join(tmp, "net.ini"), "--control",
                            os.path.join(tmp, "control.sock")], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
    boot = None
    for line in run.stdout:
        if line.startswith("master: status 0x000F") and "init-finished" in line:
            boot = time.monotonic() - start
            break
    if boot is None:
        sys.exit("netmaster.py: the run ended before its network booted")
    bus = can.Bus(interface="socketcan", channel=IFACE)
    frames = []
    end = time.monotonic() + a.seconds
    while time.monotonic() < end:
        m = bus.recv(0.5)
        if m is not None:
            frames.append((m.timestamp, m.arbitration_id))
    bus.shutdown()
    status = subprocess.run([a.comaster, "--json", "status", "--control", os.path.join(tmp, "control.sock")],
                            capture_output=True, text=True).stdout
    run.terminate()
    daemon.terminate()
    run.wait()
    daemon.wait()
    shutil.rmtree(tmp)
    # The master's outputs: RPDOs 200h..5FFh + node of the slaves (their own TPDOs are 180h.. 480h +
    # node, which a node-id alone cannot tell apart; the RPDOs are the only frames after SYNC with
    # a 2xx/3xx/4xx/5xx CAN-ID the master sends).
    outputs = {base + n for n, _, _, _ in nodes for base in (0x200, 0x300, 0x400, 0x500)}
    syncs = [t for t, cid in frames if cid == 0x080]
    periods = [(b - c) * 1000 for c, b in zip(syncs, syncs[1:])]
    bursts, per_cycle = [], []
    for s, nxt in zip(syncs, syncs[1:]):
        inside = [(t, cid) for t, cid in frames if s < t < nxt]
        out = [t for t, cid in inside if cid in outputs]
        if out:
            bursts.append((max(out) - s) * 1000)
        per_cycle.append(len(inside) + 1)
    slaves = json.loads(status)["slaves"] if status else []
    print(json.dumps({
        "nodes": len(nodes), **counts, "sync_ms": a.sync, "seconds": a.seconds,
        "boot_ms": round(boot * 1000),
        "operational": sum(1 for s in slaves if s["step"] == "operational"),
        "sync_period_ms": {"mean": round(statistics.mean(periods), 3), "max": round(max(periods), 3),
                           "min": round(min(periods), 3)},
        "outputs_after_sync_ms": {"median": round(statistics.median(bursts), 3),
                                  "max": round(max(bursts), 3)} if bursts else None,
        "frames_per_cycle": round(statistics.mean(per_cycle), 1),
        "cycles": len(periods)}))


if __name__ == "__main__":
    main()
