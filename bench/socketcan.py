# SPDX-License-Identifier: Apache-2.0
"""SDO round trips over SocketCAN, the daemon against the floor (issue 10 section 3): run inside
tools/vcan-run by bench/socketcan.

    socketcan.py RESPONDER DAEMON GENERATOR [--rounds 5] [--count 5000] [--node-id 4]

In each round, the floor (RESPONDER, bench/responder.c), the floor reading the clock at each
wake-up (RESPONDER --clock) and the daemon (DAEMON, one drive) are started in turn on vcan0 and
GENERATOR (bench/sdo_rtt.c) times COUNT expedited uploads of 1000h against each; the daemon's
turn also times COUNT SYNC -> synchronous TPDO latencies. The rounds interleave the programs so
that a change of the machine's load hits all of them. Around each run of the generator, the CPU
time (utime + stime, /proc/PID/stat) of the answering program is read; with --host-marks, also
the host's CPU time of the whole guest (bench/uml_cpu.py). Then, once each: the system calls per
transaction (strace -c -f -p on the answering program over one run of the generator, divided by
its transactions), and the daemon's wake-ups per second (voluntary context switches,
/proc/PID/status) idle and with a 100 ms heartbeat (1017h by SDO), each over WAKE_WINDOW_S.
Prints one JSON object for bench/socketcan."""

import argparse
import json
import signal
import subprocess
import sys
import time

import can

import benchproc
from benchproc import proc_stat_cpu, proc_status, strace_counts
from uml_cpu import mark

IFACE = "vcan0"
WARM_UP = 100  # transactions the generator makes before it times (bench/sdo_rtt.c)
WAKE_WINDOW_S = 5.0
STRACE_COUNT = 2000


def start(command):
    proc = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    return proc


def stop(proc):
    proc.send_signal(signal.SIGTERM)
    proc.wait(timeout=10)


def wait_ready(generator, node, mode=None):
    """Until the program answers the generator's transaction (it has bound its socket)."""
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        command = [generator] + ([mode] if mode else []) + [IFACE, str(node), "1"]
        if subprocess.run(command, capture_output=True).returncode == 0:
            return
        time.sleep(0.05)
    sys.exit("socketcan.py: the program under test never answered")


def generate(generator, node, count, mode=None):
    """The generator's JSON line; mode: None (SDO uploads), "--sync" or "--poll" (bench/sdo_rtt.c)."""
    command = [generator] + ([mode] if mode else []) + [IFACE, str(node), str(count)]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"socketcan.py: {' '.join(command)}: {run.stderr.strip()}")
    return json.loads(run.stdout)


def timed_run(pid, generator, node, count, mode=None):
    """The generator's figures, with the CPU milliseconds the answering program spent per 10,000
    transactions (warm-up included in both)."""
    cpu0 = proc_stat_cpu(pid)
    result = generate(generator, node, count, mode)
    result["cpu_ms_per_10k"] = round((proc_stat_cpu(pid) - cpu0) * 1e3 * 10000 / (count + WARM_UP), 1)
    return result


def calls_per_transaction(pid, generator, node, mode=None):
    """{syscall: calls per transaction} of the program while the generator makes STRACE_COUNT
    (+ warm-up) transactions, by strace -c -f -p: every thread, counted by the kernel's ptrace
    stops, not sampled."""
    tracer = subprocess.Popen(["strace", "-c", "-f", "-p", str(pid)], stderr=subprocess.PIPE, text=True)
    time.sleep(0.5)  # strace has attached
    generate(generator, node, STRACE_COUNT, mode)
    tracer.send_signal(signal.SIGINT)
    _, stderr = tracer.communicate(timeout=10)
    transactions = STRACE_COUNT + WARM_UP
    return {name: round(calls / transactions, 2) for name, calls in strace_counts(stderr).items()}


def wakeups_per_second(pid):
    w0, t0 = proc_status(pid, "voluntary_ctxt_switches"), time.monotonic()
    time.sleep(WAKE_WINDOW_S)
    return round((proc_status(pid, "voluntary_ctxt_switches") - w0) / (time.monotonic() - t0), 1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("responder")
    parser.add_argument("daemon")
    parser.add_argument("generator")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--count", type=int, default=5000)
    parser.add_argument("--node-id", type=int, default=4)
    parser.add_argument("--host-marks", help="directory of bench/uml_cpu.py's marks")
    args = parser.parse_args()
    node = args.node_id
    programs = (("floor", [args.responder, IFACE, str(node)]),
                ("floor_clock", [args.responder, "--clock", IFACE, str(node)]),
                ("daemon", [args.daemon, IFACE, "--node-id", str(node)]))
    result = {"floor": [], "floor_clock": [], "daemon": [], "sync": [], "rounds": args.rounds,
              "count": args.count}
    for round_ in range(args.rounds):
        for key, command in programs:
            proc = start(command)
            wait_ready(args.generator, node)
            mark(args.host_marks, f"{key}-{round_}-start")
            result[key].append(timed_run(proc.pid, args.generator, node, args.count))
            mark(args.host_marks, f"{key}-{round_}-end")
            if key == "daemon":
                result["sync"].append(timed_run(proc.pid, args.generator, node, args.count, "--sync"))
            stop(proc)

    for key, command in programs:
        proc = start(command)
        wait_ready(args.generator, node)
        result[f"{key}_calls"] = calls_per_transaction(proc.pid, args.generator, node)
        if key == "daemon":
            time.sleep(1.0)
            result["idle_wakeups_per_s"] = wakeups_per_second(proc.pid)
            bus = can.Bus(interface="socketcan", channel=IFACE, receive_own_messages=False)
            try:
                benchproc.sdo_request(bus, node, bytes([0x2B, 0x17, 0x10, 0x00, 100, 0, 0, 0]),
                                      "socketcan.py")
            finally:
                bus.shutdown()
            time.sleep(1.0)
            result["heartbeat_wakeups_per_s"] = wakeups_per_second(proc.pid)
        stop(proc)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
