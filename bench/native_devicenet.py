# SPDX-License-Identifier: Apache-2.0
"""DeviceNet on the native kernel (issue 18): what bench/devicenet measures inside User-Mode Linux,
with a vDSO clock and native system calls. Run by bench/native-devicenet.

    native_devicenet.py measure RESPONDER NODE GENERATOR POLL_BUS [--rounds 10] [--passes 10]
                        [--count 5000] [--drives 63] [--period-ms 25] [--seconds 30] [--cpu 0]
    native_devicenet.py report RESULTS.json COMMAND REVISION   the section of docs/benchmarks.md

The kernel here has no vcan, so the bus is an AF_UNIX SOCK_SEQPACKET socketpair carrying one
struct can_frame per datagram (as bench/native). The daemon's side is NODE (bench/native_dn_node.c:
atv312d's DeviceNet drives, hosted as `atv312d --devicenet` hosts them, on the runtime loop).

1. Poll round trip of one drive (MAC ID 63) against the floor: the floor (RESPONDER --poll), the
   floor reading the clock at each wake-up (RESPONDER --clock --poll) and the drive, each on its
   own socketpair; the drive's explicit and polled connections are allocated by POLL_BUS (the
   scanner library, bench/dn_poll_bus.c) with an expected packet rate of 10000 ms, which is then
   stopped, before GENERATOR --poll (bench/sdo_rtt.c) times COUNT polls one at a time. Rounds and
   passes as in bench/native.py (ABC CBA, pairs, median with its 95% interval); CPU of the
   answering program from /proc/PID/schedstat, system calls per poll by strace -c -f -p.
2. DRIVES drives in one NODE process polled every PERIOD_MS by POLL_BUS, twice: "burst", the
   scan cycle's polls written at once (the socketpair hands them over in one read), and
   "spread", one poll every PERIOD_MS / DRIVES (as the frames follow one another on a real bus:
   every poll wakes the daemon). The daemon pinned to CPU, the scanner to another CPU (a scanner
   is another machine). Over SECONDS in six windows: the daemon's CPU (/proc/PID/schedstat), its
   wake-ups (voluntary context switches), VmRSS and VmHWM, the polls sent, answered and missed
   (POLL_BUS's counts, SIGUSR1), then its system calls over 5 s (strace -c -f -p) and, at the
   end, its own counters (frames received, calls into the cards). Fails unless every drive comes
   online and is polled and answers.
Prints one JSON object."""

import argparse
import datetime
import json
import os
import select
import signal
import statistics
import subprocess
import sys
import time

from benchproc import proc_status, syscalls
import native
from native import (STRACE_COUNT, calls_per_transaction, machine, median_interval, pinned,
                    quartiles, run_time_ns, timed)

MAC_ID = 63
# The single drive's polled connection: a watchdog of 40 s, longer than the pauses of its polls
# while the floors are timed.
ROUND_TRIP_EPR_MS = 10000
WINDOWS = 6
SETTLE_S = 2.0
STRACE_S = 5
PROGRAMS = ("floor", "floor_clock", "daemon")
NAMES = {"floor": "floor (`responder --poll`)",
         "floor_clock": "floor + clock_gettime (`responder --clock --poll`)",
         "daemon": "the daemon's drive on the runtime loop (bench/native_dn_node.c)"}
MODES = {"burst": [], "spread": ["--spread"]}


def read_line(proc, timeout):
    ready, _, _ = select.select([proc.stdout], [], [], timeout)
    return proc.stdout.readline().strip() if ready else ""


def other_cpu(cpu):
    return (cpu + 1) % os.cpu_count()


class Answering(native.Answering):
    """bench/native.py's answering program, with the DeviceNet steps: online, polled."""

    def wait_online(self, drives):
        line = read_line(self.proc, 10.0)
        if line != f"online {drives}":
            sys.exit(f"native_devicenet.py: the drives are not online: {line!r}")

    def scanner(self, poll_bus, first, last, period_ms, cpu, options=()):
        """POLL_BUS on the bus's end, once it polls every drive."""
        fd = self.bus.fileno()
        scanner = subprocess.Popen(pinned(cpu, [poll_bus, *options, f"--fd={fd}", f"{first}-{last}",
                                                str(period_ms)]),
                                   pass_fds=[fd], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True)
        line = read_line(scanner, 20.0)
        if line != f"polling {last - first + 1}":
            scanner.kill()
            sys.exit(f"native_devicenet.py: the scanner does not poll all drives: {line!r} "
                     f"{scanner.stderr.read().strip()}")
        return scanner

    def establish_poll(self, poll_bus, cpu):
        """The drive's connections allocated and its polled one established by the scanner,
        which then stops; what is left on the bus (its last poll's response) is drained."""
        scanner = self.scanner(poll_bus, MAC_ID, MAC_ID, ROUND_TRIP_EPR_MS, cpu)
        scanner.send_signal(signal.SIGTERM)
        scanner.communicate(timeout=10)
        time.sleep(0.05)
        self.bus.setblocking(False)  # the peer's loop made the shared descriptor non-blocking
        try:
            while self.bus.recv(64):
                pass
        except BlockingIOError:
            pass

    def generate(self, generator, count, cpu, options=()):
        return self.run_generator(generator, cpu,
                                  [*options, "--poll", "--fd={fd}", str(MAC_ID), str(count)])

    def close(self):
        """Hangs up: the program ends; returns its last line."""
        out = super().close().strip()
        return out.splitlines()[-1] if out else ""


def start_answering(key, args):
    """One answering program, ready: it has answered a poll."""
    argv = {"floor": [args.responder, "--poll", "--fd={fd}", str(MAC_ID)],
            "floor_clock": [args.responder, "--clock", "--poll", "--fd={fd}", str(MAC_ID)],
            "daemon": [args.node, "{fd}", f"{MAC_ID}-{MAC_ID}"]}[key]
    program = Answering(argv, args.cpu)
    if key == "daemon":
        program.wait_online(1)
        program.establish_poll(args.poll_bus, args.cpu)
    program.generate(args.generator, 1, args.cpu)
    return program


def round_trip_programs(args):
    return {key: start_answering(key, args) for key in PROGRAMS}


def round_trips(args):
    result = {key: [] for key in PROGRAMS}
    result["loop"] = []
    for _ in range(args.rounds):
        programs = round_trip_programs(args)
        for turn in range(args.passes):
            for key in PROGRAMS if turn % 2 == 0 else reversed(PROGRAMS):
                result[key].append(timed(programs[key], args.generator, args.count, args.cpu))
        result["loop"].append(json.loads(programs["daemon"].close()))
        programs["floor"].close()
        programs["floor_clock"].close()
    programs = round_trip_programs(args)
    for key in PROGRAMS:
        result[f"{key}_calls"] = calls_per_transaction(programs[key], args.generator, args.cpu)
        programs[key].close()
    return result


def paced(args):
    """The floors and the one drive answering polls paced as the bus's (one every PERIOD_MS /
    DRIVES), the generator on another CPU: the CPU a wake-up per poll costs each."""
    interval_us = args.period_ms * 1000 // args.drives
    count = int(args.paced_seconds * 1e6 / interval_us)
    result = {"interval_us": interval_us, "count": count}
    for key in PROGRAMS:
        program = start_answering(key, args)
        pid = program.proc.pid
        before, wake0, t0 = run_time_ns(pid), proc_status(pid, "voluntary_ctxt_switches"), \
            time.monotonic()
        run = program.generate(args.generator, count, other_cpu(args.cpu),
                               [f"--every={interval_us}"])
        elapsed = time.monotonic() - t0
        run["cpu_percent"] = round(100 * (run_time_ns(pid) - before) / 1e9 / elapsed, 3)
        run["wakeups_per_s"] = round((proc_status(pid, "voluntary_ctxt_switches") - wake0) /
                                     elapsed, 1)
        result[key] = run
        program.close()
    return result


def counts(scanner):
    scanner.send_signal(signal.SIGUSR1)
    line = read_line(scanner, 5.0)
    if not line.startswith("{"):
        sys.exit(f"native_devicenet.py: the scanner's counts: {line!r}")
    return json.loads(line)


def polled_bus(args, options):
    drives = args.drives
    daemon = Answering([args.node, "{fd}", f"1-{drives}"], args.cpu)
    daemon.wait_online(drives)
    scanner = daemon.scanner(args.poll_bus, 1, drives, args.period_ms, other_cpu(args.cpu), options)
    result = {}
    time.sleep(SETTLE_S)
    before = counts(scanner)
    pid = daemon.proc.pid
    scanner_cpu0 = run_time_ns(scanner.pid)
    wake0, t0 = proc_status(pid, "voluntary_ctxt_switches"), time.monotonic()
    shares = []
    for _ in range(WINDOWS):
        cpu0, w0 = run_time_ns(pid), time.monotonic()
        time.sleep(args.seconds / WINDOWS)
        shares.append(round(100 * (run_time_ns(pid) - cpu0) / 1e9 / (time.monotonic() - w0), 3))
    elapsed = time.monotonic() - t0
    result["wakeups_per_s"] = round((proc_status(pid, "voluntary_ctxt_switches") - wake0) / elapsed, 1)
    result["cpu_percent"] = shares
    result["scanner_cpu_percent"] = round(100 * (run_time_ns(scanner.pid) - scanner_cpu0) / 1e9 /
                                          elapsed, 3)
    after = counts(scanner)
    result["window"] = {key: after[key] - before[key] for key in ("polls", "responses", "missed")}
    result["vm_rss_kib"] = proc_status(pid, "VmRSS")
    result["vm_hwm_kib"] = proc_status(pid, "VmHWM")
    result["syscalls_5s"] = syscalls(pid, STRACE_S)
    # The daemon first, so that the scanner's last polls do not meet a closed socket.
    daemon.proc.send_signal(signal.SIGTERM)
    result["loop"] = json.loads(daemon.close())
    scanner.send_signal(signal.SIGTERM)
    out, err = scanner.communicate(timeout=10)
    result["scanner_end"] = json.loads(out.strip().splitlines()[-1])
    if scanner.returncode != 0 or result["scanner_end"]["fewest_responses"] == 0:
        sys.exit(f"native_devicenet.py: a drive was not polled or never answered: {out} {err}")
    return result


def measure(args):
    result = {"rounds": args.rounds, "passes": args.passes, "count": args.count, "cpu": args.cpu,
              "drives": args.drives, "period_ms": args.period_ms, "seconds": args.seconds,
              "round_trip": round_trips(args), "paced": paced(args)}
    result["bus"] = {mode: polled_bus(args, options) for mode, options in MODES.items()}
    print(json.dumps(result))


RATIO_GOAL, CPU_GOAL, MEMORY_GOAL_MB = 0.95, 2.0, 4.0
PACED_CAVEAT = ("The paced and bus runs are one run of each program after the other, not pairs: "
                "the load of the shared machine moves them by up to a third from one run of the "
                "bench to the next, but the floor's share stays over 2 % with nothing to do. ")


def report(args):
    r = json.loads(open(args.results).read())
    rt = r["round_trip"]

    def med(key, field):
        return statistics.median(run[field] for run in rt[key])

    def calls(key):
        c = rt[f"{key}_calls"]
        return sum(c.values()), ", ".join(f"{n:g} {name}" for name, n in
                                          sorted(c.items(), key=lambda kv: -kv[1]))

    pairs = r["rounds"] * r["passes"]
    print("<!-- bench/native-devicenet: begin (generated, do not edit) -->")
    print("## DeviceNet on the native kernel (`bench/native-devicenet`)\n")
    print(f"Made by `{args.command}` on {datetime.date.today()} ({args.revision}): {machine()}; "
          "2 cores shared with other work. What bench/devicenet measures inside User-Mode Linux, "
          "on this machine's own kernel: the clock read through the vDSO, native system calls. "
          "This kernel has no vcan nor CAN_RAW, so the bus is an AF_UNIX SOCK_SEQPACKET "
          "socketpair carrying one `struct can_frame` per datagram, as in bench/native. The "
          "daemon's side is bench/native_dn_node.c: atv312d's ATV312 drives behind their "
          "DeviceNet cards with the daemon's device operations (`atv312d --devicenet`: one "
          "device of the runtime loop per card, routed by the card's CAN-IDs, the LEDs and the "
          "drive state compared after each call; no store, no control or status surface) on "
          "`co_linux_loop_run`, opened on the socket by `co_linux_loop_open_fd` (Release). The "
          "scanner is bench/dn_poll_bus.c (the scanner library on the runtime loop) on the "
          f"other end. Targets (issue 18): the poll round trip at {RATIO_GOAL} of the floor's or "
          f"better; 63 drives polled every 25 ms: the daemon under {CPU_GOAL:g} % of a core and "
          f"{MEMORY_GOAL_MB:g} MB.\n")
    print("### Poll I/O round trip of one drive against the floor\n")
    print(f"MAC ID {MAC_ID}, its explicit and polled connections allocated and the polled "
          f"connection's expected packet rate set ({ROUND_TRIP_EPR_MS} ms) by the scanner, which "
          "then stops; default assemblies 21/71. The generator bench/sdo_rtt.c `--poll` sends "
          "poll commands of 4 bytes of zeros one at a time, "
          f"{r['count']} per run after 100 not timed; the floors are bench/responder.c `--poll` "
          "(epoll_wait, read, write) and `--clock --poll` (and clock_gettime). Generator and "
          f"answering program pinned to CPU {r['cpu']}. Pairs as in bench/native: "
          f"{r['rounds']} rounds, each starting the three afresh, of {r['passes']} passes (floor, "
          "floor + clock, daemon and back); the ratio of a pass is one of "
          f"{pairs} pairs; median, 95% interval (order statistics), quartiles. *CPU*: "
          "/proc/PID/schedstat of the answering program per 10,000 polls. *System calls*: strace "
          f"-c -f -p over {STRACE_COUNT} (+100) polls.\n")
    print("| program | round trips/s | p50 | p99 | max | system calls / poll | CPU / 10,000 |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for key in PROGRAMS:
        print(f"| {NAMES[key]} | {med(key, 'per_s'):.0f} | {med(key, 'p50_us'):.1f} us | "
              f"{med(key, 'p99_us'):.1f} us | {max(run['max_us'] for run in rt[key]):.1f} us | "
              f"{calls(key)[0]:g} | {med(key, 'cpu_ms_per_10k'):.1f} ms |")
    print("\n| daemon / | pairs | round trips/s: median | 95% interval | quartiles | CPU per "
          "poll: median | 95% interval |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    verdicts = []
    for floor, name in (("floor", "floor"), ("floor_clock", "floor + clock_gettime")):
        ratios = [d["per_s"] / f["per_s"] for f, d in zip(rt[floor], rt["daemon"])]
        cpu = [d["cpu_ms_per_10k"] / f["cpu_ms_per_10k"] for f, d in zip(rt[floor], rt["daemon"])]
        middle, low, high = median_interval(ratios)
        c_mid, c_low, c_high = median_interval(cpu)
        print(f"| {name} | {pairs} | **{middle:.3f}** | {low:.3f}-{high:.3f} | "
              "{:.3f}-{:.3f} | ".format(*quartiles(ratios)) +
              f"{c_mid:.3f} | {c_low:.3f}-{c_high:.3f} |")
        verdicts.append((name, middle, low, high))
    extra = [(d["cpu_ms_per_10k"] - f["cpu_ms_per_10k"]) * 100
             for f, d in zip(rt["floor"], rt["daemon"])]
    middle, low, high = median_interval(extra)
    print(f"\nCPU per poll, daemon's drive minus floor: {middle:.0f} ns ({low:.0f}-{high:.0f}).")
    for name, middle, low, high in verdicts:
        if low >= RATIO_GOAL:
            verdict = f"meets the goal of {RATIO_GOAL} or better, the whole 95% interval above it"
        elif middle >= RATIO_GOAL:
            verdict = f"meets the goal of {RATIO_GOAL} at the median, its 95% interval reaching below"
        else:
            verdict = f"does not meet the goal of {RATIO_GOAL} or better"
        print(f"\nDaemon / {name}, round trips per second: {middle:.3f} ({low:.3f}-{high:.3f}): "
              f"{verdict}.")
    for key, name in (("floor", "Floor"), ("floor_clock", "Floor + clock_gettime"),
                      ("daemon", "Daemon's drive")):
        print(f"\n{name}, system calls per poll: {calls(key)[1]}.", end="")
    loop = rt["loop"]
    print(" Per poll the loop woke "
          f"{statistics.median(run['wakeups'] / run['rx'] for run in loop):.3f} times and called "
          f"the card's process {statistics.median(run['processes'] / run['rx'] for run in loop):.3f}"
          " times (its own counters).\n")

    p = r["paced"]
    print(f"### A poll every {p['interval_us']} us: what a wake-up per poll costs\n")
    print(f"The same three programs answering {p['count']} polls paced as the bus's below (one "
          f"every {p['interval_us']} us, `sdo_rtt --every={p['interval_us']}`), the generator on "
          "the other CPU, so that the answering program sleeps between polls and every poll "
          "wakes it, as on a real bus: its CPU over the run (/proc/PID/schedstat).\n")
    print("| program | CPU (% of a core) | wake-ups/s | p50 | p99 |")
    print("|---|---:|---:|---:|---:|")
    for key in PROGRAMS:
        run = p[key]
        print(f"| {NAMES[key]} | {run['cpu_percent']:.2f} % | {run['wakeups_per_s']:g} | "
              f"{run['p50_us']:.1f} us | {run['p99_us']:.1f} us |")
    print()

    drives, period = r["drives"], r["period_ms"]
    print(f"### {drives} drives polled every {period} ms\n")
    print(f"One bench/native_dn_node.c process hosts MAC IDs 1-{drives} (each online after its "
          "duplicate MAC ID check); bench/dn_poll_bus.c (MAC ID 0) allocates every drive's "
          f"explicit and polled connections, sets each polled connection's expected packet rate to "
          f"{period} ms (watchdog {4 * period} ms) and polls all {drives} every {period} ms with 4 "
          f"bytes of zeros: {drives * 1000 // period} poll commands and as many responses per "
          f"second. The daemon is pinned to CPU {r['cpu']}, the scanner to the other (a scanner is "
          "another machine). Two ways to put the polls on the socketpair: *burst*, the scan "
          "cycle as the scanner library makes it, its 63 poll commands written at once, which the "
          "socketpair hands over at once (one wake-up and one recvmmsg for the cycle); *spread*, "
          f"one poll every {period * 1000 // drives} us (`dn_poll_bus --spread`), as the frames "
          "of a scan cycle follow one another on a real 500 kbit/s bus, where each poll wakes the "
          f"daemon: the case the target is about. Over {r['seconds']:g} s in {WINDOWS} windows "
          "after the scanner polls every drive (the bench fails otherwise): the daemon's CPU "
          "(/proc/PID/schedstat), its wake-ups (voluntary context switches), VmRSS and VmHWM at "
          "the end, the polls the scanner sent, got answered and missed (no response before the "
          "next poll) in the windows; its system calls over 5 s after them (strace, which slows "
          "it); the daemon's own counters over its whole run.\n")
    print("| polls | daemon CPU (% of a core) | windows | wake-ups/s | system calls/s (strace) | "
          "VmRSS | VmHWM | polls sent | answered | missed | fewest answered by a drive | "
          "card process calls / frame received | scanner CPU |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for mode, bus in r["bus"].items():
        share = statistics.median(bus["cpu_percent"])
        w, loop = bus["window"], bus["loop"]
        print(f"| {mode} | **{share:.2f} %** | {min(bus['cpu_percent']):.2f}-"
              f"{max(bus['cpu_percent']):.2f} | {bus['wakeups_per_s']:g} | "
              f"{sum(bus['syscalls_5s'].values()) / STRACE_S:.0f} | "
              f"{bus['vm_rss_kib'] / 1024:.1f} MB | {bus['vm_hwm_kib'] / 1024:.1f} MB | "
              f"{w['polls']} | {w['responses']} | {w['missed']} | "
              f"{bus['scanner_end']['fewest_responses']} | "
              f"{loop['processes'] / loop['rx']:.3f} | {bus['scanner_cpu_percent']:.2f} % |")
    for mode, bus in r["bus"].items():
        print(f"\n{mode.capitalize()}, system calls of the daemon in {STRACE_S} s: " +
              ", ".join(f"{n} {name}" for name, n in
                        sorted(bus["syscalls_5s"].items(), key=lambda kv: -kv[1])) + ".", end="")
    print("\n")
    for mode, bus in r["bus"].items():
        share = statistics.median(bus["cpu_percent"])
        per_wakeup = share / 100 * 1e6 / bus["wakeups_per_s"] if bus["wakeups_per_s"] else 0
        cpu_verdict = "meets" if share < CPU_GOAL else "does not meet"
        mem_verdict = "meets" if bus["vm_hwm_kib"] / 1024 < MEMORY_GOAL_MB else "does not meet"
        print(f"{mode.capitalize()}: {share:.2f} % of a core ({per_wakeup:.1f} us per wake-up), "
              f"which {cpu_verdict} the goal of under {CPU_GOAL:g} %; {bus['vm_hwm_kib'] / 1024:.1f}"
              f" MB at the peak, which {mem_verdict} the goal of under {MEMORY_GOAL_MB:g} MB.\n")
    floor, daemon = p["floor"]["cpu_percent"], p["daemon"]["cpu_percent"]
    spread = statistics.median(r["bus"]["spread"]["cpu_percent"])
    floor_us = floor / 100 * 1e6 / p["floor"]["wakeups_per_s"]
    print(f"Interpretation. Natively the drive answers a poll at {verdicts[0][1]:.3f} of the floor's "
          "pace with the floor's three system calls (the clock is the vDSO's), the card's process "
          "once per frame and only the addressed card's: the extra is a few hundred nanoseconds "
          "of its own work per poll. The CPU share of 63 drives polled every 25 ms is a matter "
          "of wake-ups, not of the drives: when each poll wakes the daemon, as on a real bus, "
          f"even the floor, which does nothing but epoll_wait, read and write, costs {floor:.2f} % "
          f"of a core on this machine ({floor_us:.0f} us of kernel time per wake-up: waking a "
          f"sleeping process), the daemon's one drive {daemon:.2f} % and its 63 drives "
          f"{spread:.2f} %, the same: routing and the cards add nothing that grows with their "
          f"number. {PACED_CAVEAT}So the aim of 2 % is not met with a wake-up per poll and cannot be by any "
          "program that answers each frame when it arrives, on this machine; it is met when the "
          "polls arrive together (burst), where a wake-up reads the whole cycle with recvmmsg "
          "and answers it with one sendmmsg. Getting under 2 % with spread polls would take "
          "fewer wake-ups than frames (answering later than the frame), a trade of the poll "
          "response's latency that the project has not made. Memory is met either way.\n")
    print("<!-- bench/native-devicenet: end -->")


def main():
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="what", required=True)
    m = sub.add_parser("measure")
    for name in ("responder", "node", "generator", "poll_bus"):
        m.add_argument(name)
    m.add_argument("--rounds", type=int, default=10)
    m.add_argument("--passes", type=int, default=10)
    m.add_argument("--count", type=int, default=5000)
    m.add_argument("--drives", type=int, default=63)
    m.add_argument("--period-ms", type=int, default=25)
    m.add_argument("--seconds", type=float, default=30.0)
    m.add_argument("--paced-seconds", type=float, default=10.0)
    m.add_argument("--cpu", type=int, default=0)
    r = sub.add_parser("report")
    r.add_argument("results")
    r.add_argument("command")
    r.add_argument("revision")
    args = parser.parse_args()
    (measure if args.what == "measure" else report)(args)


if __name__ == "__main__":
    main()
