# SPDX-License-Identifier: Apache-2.0
"""The time of an LSS fastscan of a bench of unconfigured nodes (issue 30): run inside
tools/vcan-run by bench/lss-fastscan.

    lss_fastscan.py DAEMON COMASTER [--nodes 20] [--frame-ms 20,5]

For each frame wait, starts DAEMON on vcan0 with `--model io --unconfigured N`, runs `COMASTER lss
fastscan 1` twice over fresh daemons, with the I/O node's vendor-ID, product code and revision
given (one frame each) and without (32 frames each), and times each scan until every node has
booted with its node-id (comaster waits for each boot-up). Prints one JSON object a scan."""

import argparse
import json
import subprocess
import sys
import tempfile
import time

IFACE = "vcan0"
IO_PARTS = ["--vendor", "0", "--product", "401", "--revision", "0x10000"]


def scan(daemon, comaster, nodes, frame_ms, known):
    with tempfile.TemporaryDirectory() as tmp:
        log = open(f"{tmp}/atv312d.log", "wb")
        proc = subprocess.Popen([daemon, IFACE, "--model", "io", "--unconfigured", str(nodes)],
                                stdout=log, stderr=subprocess.STDOUT)
        try:
            time.sleep(0.5)  # the daemon's socket open: no boot-up to wait for
            args = [comaster, "-i", IFACE, "lss", "fastscan", "1", "--frame-ms", str(frame_ms)]
            started = time.monotonic()
            done = subprocess.run(args + (IO_PARTS if known else []), capture_output=True,
                                  text=True, timeout=900)
            elapsed = time.monotonic() - started
        finally:
            proc.terminate()
            proc.wait(timeout=10)
    last = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else done.stderr.strip()
    return {"nodes": nodes, "frame_ms": frame_ms, "known_parts": known, "seconds": round(elapsed, 2),
            "exit": done.returncode, "result": last}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("daemon")
    parser.add_argument("comaster")
    parser.add_argument("--nodes", type=int, default=20)
    parser.add_argument("--frame-ms", default="20,5")
    args = parser.parse_args()
    for frame_ms in [int(v) for v in args.frame_ms.split(",")]:
        for known in (True, False):
            print(json.dumps(scan(args.daemon, args.comaster, args.nodes, frame_ms, known)),
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
