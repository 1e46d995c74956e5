# SPDX-License-Identifier: Apache-2.0
"""A bench of unconfigured CiA 401 I/O nodes to commission (docs/io.md, docs/lss.md): `atv312d
--model io --unconfigured N` puts N nodes without node-id on vcan0, silent but for LSS, each with
its own serial number; `comaster lss fastscan` and python canopen's LssMaster find them, number
them and store their node-ids; the daemon's control surface follows each node to its node-id, and
a restart with the same --store brings each back with the node-id LSS stored for it."""

import json
import os
import subprocess
import time

import pytest

from conftest import IFACE, ROOT, Bus
from test_control import ctl

COMASTER = os.environ.get("COMASTER") or str(ROOT / "build" / "apps" / "comaster" / "comaster")
# D-IO401-IDENTITY: the k-th unconfigured node's serial number is 40100000h + 80h + k.
SERIAL_FIRST = 0x40100081
IO_VENDOR, IO_PRODUCT, IO_REVISION = 0, 401, 0x00010000


def nodes(sock):
    """The daemon's nodes as `state --json` lists them, once its control socket answers."""
    deadline = time.monotonic() + 5
    while True:
        status, reply = ctl(sock, "--json", "state")
        if status == 0:
            return json.loads(reply)["nodes"]
        assert time.monotonic() < deadline, reply
        time.sleep(0.05)


def booted(sock, node_id, serial):
    """Waits until the daemon shows the node of that serial number booted with node_id (`bus`
    lags behind the scan's frames: the daemon's view is the deadline's witness)."""
    deadline = time.monotonic() + 5
    while (node_id, "Pre-operational", serial) not in \
            [(n["node"], n["nmt"], n["serial"]) for n in nodes(sock)]:
        assert time.monotonic() < deadline, nodes(sock)
        time.sleep(0.05)


def identity(serial):
    return (f"vendor-ID 0x{IO_VENDOR:08X} product code 0x{IO_PRODUCT:08X} "
            f"revision 0x{IO_REVISION:08X} serial 0x{serial:08X}")


def test_comaster_fastscan_numbers_twenty_unconfigured_io_nodes(bus, start_daemon, tmp_path):
    sock, store = tmp_path / "atv312d.sock", tmp_path / "bench.store"
    args = ("--model", "io", "--unconfigured", 20, "--control", sock, "--store", store)
    d = start_daemon(bus, *args, boot_ids=[])
    before = nodes(sock)
    assert [(n["node"], n["nmt"], n["serial"]) for n in before] == \
        [(None, "Initialising", SERIAL_FIRST + k) for k in range(20)]
    status, reply = ctl(sock, "state", 255)
    assert status == 0 and reply.startswith(
        f"ok node unconfigured, serial {SERIAL_FIRST:08X}h: nmt Initialising, model io"), reply
    # Without a node-id none of them may boot up: no 701h..77Fh since the bus was opened, nor
    # within 0.3 s more (collect() adds what it sees to bus.seen).
    bus.collect(0.3)
    assert [str(f) for f in bus.seen if 0x701 <= f.can_id <= 0x77F] == []
    started = time.monotonic()
    # The known parts of the address take one frame each: 20 x 37 frames instead of 20 x 133,
    # and four inquiries of the address found; after the reset, a frame waits twice the slowest
    # answer, at least 5 ms, at most --frame-ms (docs/decisions.md, D-LSS-FASTSCAN-WAIT).
    # 50 ms a frame: inside User-Mode Linux on a loaded host answers come later than the default
    # 20 ms often enough that comaster's three scans a slave now and then all lost it.
    done = subprocess.run([COMASTER, "-i", IFACE, "lss", "fastscan", "30", "--store", "--frame-ms",
                           "50", "--vendor",
                           str(IO_VENDOR), "--product", str(IO_PRODUCT), "--revision",
                           str(IO_REVISION)], capture_output=True, text=True, timeout=300)
    elapsed = time.monotonic() - started
    print(f"comaster lss fastscan of 20 io nodes: {elapsed:.1f} s")
    assert (done.returncode, done.stderr) == (0, ""), done.stderr
    lines = done.stdout.splitlines()
    assert lines[-1] == "20 slaves configured"
    # comaster saw each boot-up; each slave once, numbered in the order found: the lowest address first, unless an answer
    # later than the frame wait made comaster scan again.
    given = {}
    for line in lines[:-1]:
        address, _, node_id = line.partition(": node-id ")
        given[address] = int(node_id)
    assert sorted(given) == sorted(identity(SERIAL_FIRST + k) for k in range(20))
    assert sorted(given.values()) == list(range(30, 50))
    after = nodes(sock)
    assert sorted((n["node"], n["nmt"], n["serial"]) for n in after) == \
        sorted((given[identity(n["serial"])], "Pre-operational", n["serial"]) for n in after)
    assert d.stop() == 0
    # A watcher of its own: `bus` still holds the scan's thousands of frames.
    restart = Bus()
    try:
        start_daemon(restart, *args, boot_ids=list(range(30, 50)))
        assert restart.sdo_read(49, 0x1018, 4) in range(SERIAL_FIRST, SERIAL_FIRST + 20)
    finally:
        restart.close()
    assert [(n["node"], n["serial"]) for n in nodes(sock)] == \
        [(given[identity(n["serial"])], n["serial"]) for n in nodes(sock)]


def test_python_canopen_lss_master_fast_scan(bus, start_daemon, tmp_path):
    """python canopen's LssMaster (fast_scan, configure_node_id, store_configuration, switch
    global) finds each of two unconfigured nodes in turn and boots it with its node-id."""
    import canopen
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--model", "io", "--unconfigured", 2, "--control", sock,
                 "--store", tmp_path / "bench.store", boot_ids=[])
    nodes(sock)
    network = canopen.Network()
    network.connect(channel=IFACE, interface="socketcan")
    try:
        lss = network.lss
        for k, node_id in enumerate((20, 21)):
            found, address = lss.fast_scan()
            assert found and address == [IO_VENDOR, IO_PRODUCT, IO_REVISION, SERIAL_FIRST + k]
            lss.configure_node_id(node_id)
            lss.store_configuration()
            lss.send_switch_state_global(lss.WAITING_STATE)
            booted(sock, node_id, SERIAL_FIRST + k)
        found, _ = lss.fast_scan()
        assert not found  # every node has its node-id now
    finally:
        network.disconnect()
    assert [(n["node"], n["serial"]) for n in nodes(sock)] == [(20, SERIAL_FIRST), (21, SERIAL_FIRST + 1)]
