#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Prints the footprint of the linked example from its linker map and symbols: the flash (text and
read-only data) each part of the firmware keeps after --gc-sections, file by file for the core,
and the RAM of the node beside its dictionary's variables and the SDO buffer.
    footprint.py blinky.map blinky.elf"""
import re
import subprocess
import sys
from collections import defaultdict

def linked_sizes(map_path):
    """Bytes of the input sections kept in the image, by object file and kind (flash / ram)."""
    # A long section name is on its own line, its address, size and object file on the next.
    text = open(map_path).read().replace("\n                ", " ")
    kept = text.index("Memory Configuration")  # the discarded input sections come before it
    pattern = re.compile(r"^ (\.[\w.]+)\s+0x([0-9a-f]+)\s+0x([0-9a-f]+) (\S+)", re.M)
    sizes = defaultdict(lambda: defaultdict(int))
    for m in pattern.finditer(text, kept):
        name, size, obj = m.group(1), int(m.group(3), 16), m.group(4)
        if not name.startswith((".text", ".rodata", ".data", ".bss")):
            continue  # debug information and attributes: not in the target's memory
        kind = "ram" if name.startswith((".data", ".bss")) else "flash"
        sizes[obj][kind] += size
    return sizes

def main():
    map_path, elf = sys.argv[1:3]
    sizes = linked_sizes(map_path)
    core = {re.sub(r".*/src/canopen/([\w/]+)\.c\.obj$", r"\1.c", o): s
            for o, s in sizes.items() if "/src/canopen/" in o}
    print("flash of the core after --gc-sections (text + rodata, bytes):")
    for name in sorted(core):
        print(f"  {name:24} {core[name]['flash']:6}")
    total = sum(s["flash"] for s in core.values())
    print(f"  {'core total':24} {total:6}")
    print("flash of the rest, by object file or library member:")
    for obj in sorted(o for o in sizes if "/src/canopen/" not in o and sizes[o]["flash"]):
        print(f"  {re.sub(r'.*/', '', obj):40} {sizes[obj]['flash']:6}")
    rest = sum(s["flash"] for o, s in sizes.items() if "/src/canopen/" not in o)
    print(f"  {'everything else':24} {rest:6} (startup, board, storage, dictionary, newlib)")
    print("RAM of the whole firmware, by object file (data + bss, bytes):")
    for obj in sorted(o for o in sizes if sizes[o]["ram"]):
        print(f"  {re.sub(r'.*/', '', obj):40} {sizes[obj]['ram']:6}")
    nm = subprocess.run(["arm-none-eabi-nm", "-S", "-t", "d", elf], check=True,
                        capture_output=True, text=True).stdout
    symbol = {f[3]: int(f[1]) for f in (l.split() for l in nm.splitlines()) if len(f) == 4}
    print("RAM of one node (bytes):")
    print(f"  co_node_t        {symbol['node']:6}")
    print(f"  dictionary data  {symbol['od_data']:6} (BLINKY_OD_DATA_SIZE)")
    print(f"  per node         {symbol['node'] + symbol['od_data']:6}")
    print(f"  SDO buffer       {symbol['sdo_data']:6} (the application's, shareable by its nodes)")

main()
