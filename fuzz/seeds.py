#!/usr/bin/env python3
"""Writes the seed corpus of the harnesses, fuzz/corpus/<harness>/<name>, from readable frames
(the encoding is in fuzz_frames.c) and storage files (docs/atv312d.md, "Storage file"). The
committed corpus is these seeds plus what a fuzzing run added, minimised (docs/fuzzing.md): run
this again only to change the seeds."""
import pathlib
import struct
import zlib

CORPUS = pathlib.Path(__file__).resolve().parent / "corpus"
SAVE = "73617665"  # 1010h signature "save"
LOAD = "6C6F6164"  # 1011h signature "load"
# The drive is node 4; its master sends on 604h and reads 584h.
ENABLE = ["000#0104", "204#0600", "204#0700", "204#0F00"]

FRAMES = {
    "sdo-expedited": ["604#4000100000000000", "604#2B17100064000000", "604#4017100000000000",
                      "604#2B01200533010000", "604#8000100000000000"],
    "sdo-segmented-upload": ["604#4008100000000000", "604#6000000000000000",
                             "604#7000000000000000"],
    "sdo-segmented-download": ["604#2117100002000000", "604#0B64000000000000"],
    "sdo-block-download": ["604#C217100002000000", "604#8164000000000000",
                           "604#D500000000000000"],
    "sdo-block-upload": ["604#A00010007F000000", "604#A300000000000000",
                         "604#A2017F0000000000", "604#A100000000000000"],
    "sdo-timeout": ["604#2117100002000000", "+2000ms", "604#0B64000000000000"],
    "nmt": ["000#0104", "000#0204", "000#8004", "000#0100", "000#8204", "000#8104", "000#81"],
    "rpdo1-enable": ENABLE + ["+1000ms", "204#0700", "+500ms"],
    "rpdo6-run": ["604#2305140104030000"] + ENABLE + ["304#0F00B004", "+3000ms", "304#0F10B004",
                                                      "+3000ms", "304#0F18B004", "+2000ms"],
    "sync-tpdo": ["604#2F00180101000000", "000#0104", "080#", "+10ms", "080#", "080#01"],
    "guarding": ["604#2B0C100064000000", "604#2F0D100003000000", "704#R", "+100ms", "704#R",
                 "+1000ms", "704#R"],
    "heartbeat": ["604#2B17100064000000", "604#2316100164000100", "701#05", "+50ms", "701#05",
                  "+1000ms"],
    "store-save-reset": ["604#2B01200533010000", "604#23101001" + SAVE, "000#8104",
                         "604#4001200500000000", "604#23111004" + LOAD, "000#8104"],
}


def frames_input(steps):
    out = bytearray()
    for step in steps:
        if step.startswith("+"):
            us = int(step[1:-2]) * 1000
            shift = 0
            while us >> shift > 0xFFFF:
                shift += 1
            out += bytes([0xF0 | shift]) + struct.pack("<H", us >> shift)
            continue
        can_id, data = step.split("#")
        can_id = int(can_id, 16)
        rtr = data == "R"
        payload = b"" if rtr else bytes.fromhex(data)
        out += bytes([len(payload) << 4 | (0x08 if rtr else 0) | can_id >> 8, can_id & 0xFF])
        out += payload
    return bytes(out)


def image(sequence, kind, records):
    body = b"COS\x02" + struct.pack("<IB", sequence, kind)
    for index, sub, value in records:
        body += struct.pack("<HBH", index, sub, len(value)) + value
    return body


def store_file(records):
    body = b"".join(struct.pack("<BBHI", node, area, 0, len(img)) + img
                    for node, area, img in records)
    head = b"CoSF" + struct.pack("<HHI", 1, len(records), len(body)) + body
    return head + struct.pack("<I", zlib.crc32(head))


u16 = lambda v: struct.pack("<H", v)
STORES = {
    "empty": store_file([]),
    "node4-hsp-heartbeat": store_file([
        (4, 2, image(1, 0, [(0x1017, 0, u16(100))])),
        (4, 4, image(2, 0, [(0x2001, 5, u16(400)), (0x2001, 6, u16(50))])),
    ]),
    "node4-defaults": store_file([(4, 3, image(3, 1, []))]),
    "node4-refused": store_file([(4, 4, image(1, 0, [(0x2001, 5, u16(9999)),
                                                     (0x7FFF, 0, u16(1))]))]),
    "node9-version1": store_file([(9, 2, b"COS\x01" + struct.pack("<HBH", 0x1017, 0, 2)
                                   + u16(250))]),
}


def main():
    for harness, seeds in (("frames", {k: frames_input(v) for k, v in FRAMES.items()}),
                           ("store", STORES)):
        folder = CORPUS / harness
        folder.mkdir(parents=True, exist_ok=True)
        for name, data in seeds.items():
            (folder / name).write_bytes(data)


if __name__ == "__main__":
    main()
