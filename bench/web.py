# SPDX-License-Identifier: Apache-2.0
"""The cost of the web surface (issue 20): run inside tools/vcan-run by bench/web.

    web.py DAEMON [--nodes 127] [--seconds 20]

Starts DAEMON on vcan0 with drives 1..N, idle (no heartbeat: every wake-up left is the web's),
three times: without --http; with --http and no client; with --http and one page open, that is
the requests a browser makes for it (the page, /api/bench, /api/state) and then the event stream,
read as it comes. Each time it measures from /proc/PID the CPU time (utime + stime) and the
wake-ups (voluntary context switches) over SECONDS, and the system calls over 5 s (strace -c).
Prints one JSON object per run for bench/web."""

import argparse
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time

import can

from benchproc import CLOCK_TICKS, proc_status, syscalls
from scale import WINDOWS, measure, wait_boot

IFACE = "vcan0"
LISTENING = re.compile(r"http: listening on http://\S+:(\d+)/")


def http_port(log_path):
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        m = LISTENING.search(open(log_path).read())
        if m:
            return int(m.group(1))
        time.sleep(0.05)
    raise SystemExit("web.py: the daemon does not say where it listens")


def get(port, path):
    """One GET on its own connection, read to the end (Connection: close)."""
    with socket.create_connection(("127.0.0.1", port), timeout=5) as sock:
        sock.sendall(f"GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n".encode())
        answer = b""
        while chunk := sock.recv(65536):
            answer += chunk
    if not answer.startswith(b"HTTP/1.1 200 "):
        raise SystemExit(f"web.py: GET {path}: {answer[:80]!r}")
    return len(answer)


class Page:
    """A browser's worth of requests, then the event stream read in a thread until stopped."""

    def __init__(self, port):
        for path in ("/", "/api/bench", "/api/state"):
            get(port, path)
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=5)
        self.sock.sendall(b"GET /api/events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        self.events = 0
        self.bytes = 0
        self.running = True
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        while self.running:
            try:
                chunk = self.sock.recv(65536)
            except socket.timeout:
                continue
            except OSError:  # closed by close()
                return
            if not chunk:
                return
            self.bytes += len(chunk)
            self.events += chunk.count(b"event: state\n")

    def close(self):
        self.running = False
        self.sock.shutdown(socket.SHUT_RDWR)
        self.thread.join(timeout=5)
        self.sock.close()


def run(daemon, nodes, seconds, label, http, page):
    workdir = tempfile.mkdtemp(prefix="web-")
    log_path = os.path.join(workdir, "atv312d.log")
    args = [daemon, IFACE, "--node-id", f"1-{nodes}"] + (["--http", "0"] if http else [])
    bus = can.Bus(interface="socketcan", channel=IFACE, receive_own_messages=False)
    client = None
    try:
        with open(log_path, "wb") as log:
            proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT)
        wait_boot(bus, nodes)
        bus.shutdown()
        bus = None
        if page:
            client = Page(http_port(log_path))
        time.sleep(1.0)
        result = {"label": label, "window_s": seconds / WINDOWS, "tick_s": 1 / CLOCK_TICKS}
        events0, bytes0, t0 = (client.events, client.bytes, time.monotonic()) if client else (0, 0, 0)
        result["cpu_percent"], result["wakeups_per_s"] = measure(proc.pid, seconds)
        if client:
            elapsed = time.monotonic() - t0
            result["events_per_s"] = round((client.events - events0) / elapsed, 2)
            result["kbytes_per_s"] = round((client.bytes - bytes0) / elapsed / 1000, 1)
        result["syscalls_5s"] = syscalls(proc.pid, 5)
        result["rss_kib"] = proc_status(proc.pid, "VmRSS")
        if client:
            client.close()
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=10)
        result["stopped"] = open(log_path).read().strip().splitlines()[-1]
        return result
    finally:
        if bus:
            bus.shutdown()
        shutil.rmtree(workdir, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("daemon")
    parser.add_argument("--nodes", type=int, default=127)
    parser.add_argument("--seconds", type=float, default=20.0)
    args = parser.parse_args()
    for label, http, page in (("no --http", False, False), ("--http, no client", True, False),
                              ("--http, one page open", True, True)):
        print(json.dumps(run(args.daemon, args.nodes, args.seconds, label, http, page)), flush=True)


if __name__ == "__main__":
    main()
