# SPDX-License-Identifier: Apache-2.0
"""DeviceNet over SocketCAN (issue 18): run inside tools/vcan-run by bench/devicenet.

    devicenet.py RESPONDER DAEMON GENERATOR DNSCAN POLL_BUS [--rounds 5] [--count 5000]
                 [--mac-id 63] [--drives 63] [--period-ms 25] [--seconds 30]

1. The poll I/O round trip of one drive against the floor of bench/socketcan: in each round the
   floor (RESPONDER --poll, bench/responder.c), the floor reading the clock at each wake-up
   (RESPONDER --clock --poll) and the daemon (DAEMON --devicenet --mac-id MAC, one drive) are
   started in turn on vcan0 and GENERATOR --poll (bench/sdo_rtt.c) times COUNT poll commands
   against each, one at a time. The daemon's polled connection is allocated and established
   first by DNSCAN (allocate, then the expected packet rate); the floor answers polls without
   one. Around each run, the CPU time of the answering program (/proc/PID/stat); once each, its
   system calls per transaction (strace -c -f -p).
2. DRIVES drives in one daemon (MAC IDs 1..DRIVES), polled every PERIOD_MS by POLL_BUS
   (bench/dn_poll_bus.c, the scanner library): the daemon's CPU (utime + stime) in six windows
   over SECONDS, its wake-ups (voluntary context switches), its resident memory (VmRSS, VmHWM),
   its system calls over 5 s (strace -c, after the windows), the scanner's CPU, and the polls
   answered and missed in the windows (POLL_BUS's counts, asked with SIGUSR1). First the same
   daemon idle (every drive online, no connection) over 10 s. The measurement starts only when
   POLL_BUS polls every drive; it fails otherwise.
Prints one JSON object for bench/devicenet."""

import argparse
import json
import os
import select
import signal
import subprocess
import sys
import tempfile
import time

from benchproc import CLOCK_TICKS, proc_stat_cpu, proc_status, syscalls
from socketcan import IFACE, calls_per_transaction, start, stop, timed_run, wait_ready

POLLED_EPR_MS = 1000  # the single drive's polled connection: its watchdog (4 s) never fires
WINDOWS = 6
IDLE_S = 10.0
SETTLE_S = 2.0
STRACE_S = 5


def dnscan(tool, *args, timeout_ms=300):
    return subprocess.run([tool, "-i", IFACE, "--no-check", "--timeout", str(timeout_ms), *args],
                          capture_output=True, text=True)


def establish_poll(tool, mac_id):
    """Allocates the drive's explicit and polled connections (retried until the drive is online,
    after its duplicate MAC ID check) and sets the polled connection's expected packet rate."""
    deadline = time.monotonic() + 15
    while dnscan(tool, "allocate", str(mac_id), "0x03").returncode != 0:
        if time.monotonic() > deadline:
            sys.exit(f"devicenet.py: MAC ID {mac_id} never allocated its connections")
        time.sleep(0.1)
    rate = dnscan(tool, "set", str(mac_id), "5", "2", "9", f"u16:{POLLED_EPR_MS}")
    if rate.returncode != 0:
        sys.exit(f"devicenet.py: MAC ID {mac_id}, expected packet rate: {rate.stderr.strip()}")


def round_trips(args):
    mac = str(args.mac_id)
    programs = (("floor", [args.responder, "--poll", IFACE, mac]),
                ("floor_clock", [args.responder, "--clock", "--poll", IFACE, mac]),
                ("daemon", [args.daemon, IFACE, "--devicenet", "--mac-id", mac]))

    def ready(key):
        if key == "daemon":
            establish_poll(args.dnscan, args.mac_id)
        wait_ready(args.generator, args.mac_id, "--poll")

    result = {key: [] for key, _ in programs}
    for _ in range(args.rounds):
        for key, command in programs:
            proc = start(command)
            ready(key)
            result[key].append(timed_run(proc.pid, args.generator, args.mac_id, args.count, "--poll"))
            stop(proc)
    for key, command in programs:
        proc = start(command)
        ready(key)
        result[f"{key}_calls"] = calls_per_transaction(proc.pid, args.generator, args.mac_id, "--poll")
        stop(proc)
    return result


def wait_online(tool, drives):
    """Until a scan finds every drive (each is online after its duplicate MAC ID check)."""
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        scan = dnscan(tool, "--json", "scan")
        found = sum(1 for line in scan.stdout.splitlines() if '"vendor"' in line)
        if found == drives:
            return
        time.sleep(0.5)
    sys.exit(f"devicenet.py: {found} of {drives} drives online")


def read_line(proc, timeout):
    ready, _, _ = select.select([proc.stdout], [], [], timeout)
    return proc.stdout.readline().strip() if ready else ""


def counts(scanner):
    scanner.send_signal(signal.SIGUSR1)
    line = read_line(scanner, 5.0)
    if not line.startswith("{"):
        sys.exit(f"devicenet.py: the scanner's counts: {line!r}")
    return json.loads(line)


def cpu_windows(pid, seconds):
    """CPU (% of a core) in each of WINDOWS windows over `seconds`, and wake-ups per second."""
    shares = []
    wake0, t0 = proc_status(pid, "voluntary_ctxt_switches"), time.monotonic()
    for _ in range(WINDOWS):
        cpu0, w0 = proc_stat_cpu(pid), time.monotonic()
        time.sleep(seconds / WINDOWS)
        shares.append(round(100 * (proc_stat_cpu(pid) - cpu0) / (time.monotonic() - w0), 2))
    wakeups = proc_status(pid, "voluntary_ctxt_switches") - wake0
    return shares, round(wakeups / (time.monotonic() - t0), 1)


def polled_bus(args):
    drives = args.drives
    workdir = tempfile.mkdtemp(prefix="devicenet-")
    log_path = os.path.join(workdir, "atv312d.log")
    result = {"drives": drives, "period_ms": args.period_ms, "seconds": args.seconds,
              "tick_s": 1 / CLOCK_TICKS}
    with open(log_path, "wb") as log:
        daemon = subprocess.Popen([args.daemon, IFACE, "--devicenet", "--mac-id", f"1-{drives}"],
                                  stdout=log, stderr=subprocess.STDOUT)
    try:
        wait_online(args.dnscan, drives)
        time.sleep(1.0)
        cpu0, t0 = proc_stat_cpu(daemon.pid), time.monotonic()
        wake0 = proc_status(daemon.pid, "voluntary_ctxt_switches")
        time.sleep(IDLE_S)
        elapsed = time.monotonic() - t0
        result["idle_cpu_percent"] = round(100 * (proc_stat_cpu(daemon.pid) - cpu0) / elapsed, 2)
        result["idle_wakeups_per_s"] = round(
            (proc_status(daemon.pid, "voluntary_ctxt_switches") - wake0) / elapsed, 1)

        scanner = subprocess.Popen([args.poll_bus, IFACE, f"1-{drives}", str(args.period_ms)],
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = read_line(scanner, 20.0)
        if line != f"polling {drives}":
            scanner.kill()
            sys.exit(f"devicenet.py: the scanner does not poll all {drives} drives: {line!r} "
                     f"{scanner.stderr.read().strip()}")
        time.sleep(SETTLE_S)
        before = counts(scanner)
        scanner_cpu0 = proc_stat_cpu(scanner.pid)
        result["cpu_percent"], result["wakeups_per_s"] = cpu_windows(daemon.pid, args.seconds)
        result["scanner_cpu_percent"] = round(100 * (proc_stat_cpu(scanner.pid) - scanner_cpu0)
                                              / args.seconds, 2)
        after = counts(scanner)
        result["window"] = {key: after[key] - before[key] for key in ("polls", "responses", "missed")}
        result["vm_rss_kib"] = proc_status(daemon.pid, "VmRSS")
        result["vm_hwm_kib"] = proc_status(daemon.pid, "VmHWM")
        result["syscalls_5s"] = syscalls(daemon.pid, STRACE_S)
        scanner.send_signal(signal.SIGTERM)
        out, err = scanner.communicate(timeout=10)
        if scanner.returncode != 0:
            sys.exit(f"devicenet.py: the scanner: {err.strip()}")
        result["scanner_end"] = json.loads(out.strip().splitlines()[-1])
        if result["scanner_end"]["fewest_responses"] == 0:
            sys.exit("devicenet.py: a drive never answered a poll")
    finally:
        daemon.send_signal(signal.SIGTERM)
        daemon.wait(timeout=10)
    result["stopped"] = open(log_path).read().strip().splitlines()[-1]
    return result


def main():
    parser = argparse.ArgumentParser()
    for name in ("responder", "daemon", "generator", "dnscan", "poll_bus"):
        parser.add_argument(name)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--count", type=int, default=5000)
    parser.add_argument("--mac-id", type=int, default=63)
    parser.add_argument("--drives", type=int, default=63)
    parser.add_argument("--period-ms", type=int, default=25)
    parser.add_argument("--seconds", type=float, default=30.0)
    args = parser.parse_args()
    result = {"rounds": args.rounds, "count": args.count, "mac_id": args.mac_id,
              "round_trip": round_trips(args), "bus": polled_bus(args)}
    print(json.dumps(result))


if __name__ == "__main__":
    main()
