# SPDX-License-Identifier: Apache-2.0
"""The report of bench/sdo-throughput: durations of the SDO transfers in a candump -L log, each
delimited by a marker frame on 7FFh and named by a line of the labels file, as a markdown section;
or (--replace FILE) that section, read from standard input, put into FILE between its markers.
Standard library only."""
import argparse
import datetime
import os
import platform
import re
import statistics
import sys

MARKER_ID = 0x7FF
BEGIN = "<!-- bench/sdo-throughput: begin (generated, do not edit) -->"
END = "<!-- bench/sdo-throughput: end -->"
LINE = re.compile(r"^\((\d+\.\d+)\) \S+ ([0-9A-Fa-f]{3})#([0-9A-Fa-f]*)$")

# label -> (what, bytes per transfer, client, frames). The frames of a transfer without loss:
# 102400 bytes are 14629 segments, in 116 sub-blocks of at most 127; 1024 bytes 147 segments.
TRANSFERS = {
    "block-download-100k": ("block download, 100 kB (2100h)", 102400, "write --block",
                            2 + 14629 + 116 + 2),
    "block-upload-100k": ("block upload, 100 kB (2100h)", 102400, "read --block",
                          3 + 14629 + 116 + 2),
    "segmented-download-1k": ("segmented download, 1 kB (2101h)", 1024, "write", 2 + 2 * 147),
    "segmented-upload-1k": ("segmented upload, 1 kB (2101h)", 1024, "read", 2 + 2 * 147),
    "segmented-download-100k": ("segmented download, 100 kB (2100h)", 102400, "write",
                                2 + 2 * 14629),
    "segmented-upload-100k": ("segmented upload, 100 kB (2100h)", 102400, "read", 2 + 2 * 14629),
    "expedited-upload": ("expedited upload, 4 bytes (1000h)", 4, "read ... u32", 2),
}


def read_transfers(log_path, labels_path, node):
    """Returns {label: [(seconds, frames), ...]} in log order."""
    with open(labels_path, encoding="ascii") as f:
        labels = f.read().split()
    ids = {0x600 + node, 0x580 + node}
    transfers = []  # [first, last, frames] per marker
    with open(log_path, encoding="ascii") as f:
        for line in f:
            m = LINE.match(line.strip())
            if not m:
                continue
            at, can_id = float(m.group(1)), int(m.group(2), 16)
            if can_id == MARKER_ID:
                transfers.append([None, None, 0])
            elif can_id in ids and transfers:
                t = transfers[-1]
                t[0] = at if t[0] is None else t[0]
                t[1] = at
                t[2] += 1
    if len(transfers) != len(labels):
        sys.exit("sdo_throughput_report: %d markers in %s for %d labels"
                 % (len(transfers), log_path, len(labels)))
    result = {}
    for label, (first, last, frames) in zip(labels, transfers):
        if frames != TRANSFERS[label][3]:
            sys.exit("sdo_throughput_report: %s: %d frames in the log, %d expected: the log "
                     "lost frames or the transfer was repeated" % (label, frames,
                                                                   TRANSFERS[label][3]))
        result.setdefault(label, []).append((last - first, frames))
    return result


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def rate(size, seconds):
    return size / seconds


def report(args):
    results = read_transfers(args.log, args.labels, args.node)
    runs = len(results["block-download-100k"])
    out = [BEGIN, "## SDO throughput over SocketCAN (`bench/sdo-throughput`)", ""]
    out.append("Made by `%s` on %s: %d cores (%s), %s; the sandbox (`tools/vcan-run`, kernel `%s`) "
               "pinned to CPU %d with `taskset`; %d s in all."
               % (args.command, datetime.date.today().isoformat(), os.cpu_count(), cpu_model(),
                  platform.machine(), args.kernel, args.cpu, args.elapsed))
    out.append("Client: `comaster` (the core's SDO client) on `vcan0`; server: `bench/sdo_device`, "
               "node %d, whose 2100h (100 kB) and 2101h (1 kB) are streamed DOMAINs in its memory. "
               "Each transfer is timed on the bus, from its first to its last frame (candump -L "
               "timestamps), so comaster's start-up is not counted; every upload was compared with "
               "the bytes written. Medians of %d runs (expedited: of %d uploads)."
               % (args.node, runs, len(results["expedited-upload"])))
    out.append("")
    out.append("| transfer | comaster | bytes | frames | median ms | min ms | max ms | bytes/s |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|")
    medians = {}
    for label, (what, size, client, _) in TRANSFERS.items():
        times = [t for t, _ in results[label]]
        frames = statistics.median(f for _, f in results[label])
        median = statistics.median(times)
        medians[label] = median
        out.append("| %s | `%s` | %d | %d | %.2f | %.2f | %.2f | %.0f |"
                   % (what, client, size, frames, median * 1e3, min(times) * 1e3,
                      max(times) * 1e3, rate(size, median)))
    out.append("")
    expedited = medians["expedited-upload"]
    out.append("Expedited rate: %.0f uploads/s for one client that waits for each answer (1 / the "
               "median request-to-response time of %.2f ms)." % (1 / expedited, expedited * 1e3))
    out.append("")

    def ratio(block, segmented):
        return (rate(TRANSFERS[block][1], medians[block])
                / rate(TRANSFERS[segmented][1], medians[segmented]))

    out.append("Block / segmented, in bytes/s (goal of issue 8: at least 2):")
    out.append("")
    out.append("| block | segmented | ratio |")
    out.append("|---|---|---:|")
    for block, segmented in (("block-download-100k", "segmented-download-1k"),
                             ("block-upload-100k", "segmented-upload-1k"),
                             ("block-download-100k", "segmented-download-100k"),
                             ("block-upload-100k", "segmented-upload-100k")):
        out.append("| %s | %s | %.1f |" % (TRANSFERS[block][0], TRANSFERS[segmented][0],
                                            ratio(block, segmented)))
    out.append(END)
    print("\n".join(out))


def replace(path):
    section = sys.stdin.read().strip()
    if not (section.startswith(BEGIN) and section.endswith(END)):
        sys.exit("sdo_throughput_report: standard input is not a generated section")
    with open(path, encoding="utf-8") as f:
        text = f.read()
    start, end = text.find(BEGIN), text.find(END)
    if start >= 0 and end > start:
        text = text[:start] + section + text[end + len(END):]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("log", nargs="?")
    parser.add_argument("labels", nargs="?")
    parser.add_argument("--node", type=int, default=10)
    parser.add_argument("--command", default="bench/sdo-throughput")
    parser.add_argument("--cpu", type=int, default=0)
    parser.add_argument("--elapsed", type=int, default=0)
    parser.add_argument("--kernel", default="unknown")
    parser.add_argument("--replace", metavar="FILE")
    args = parser.parse_args()
    if args.replace:
        replace(args.replace)
    elif args.log and args.labels:
        report(args)
    else:
        parser.error("give LOG and LABELS, or --replace FILE")


if __name__ == "__main__":
    main()
