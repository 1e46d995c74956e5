# SPDX-License-Identifier: Apache-2.0
"""The programs of bench/socketcan (docs/benchmarks.md, "SDO over SocketCAN"): the floor
bench/responder.c answers exactly an expedited upload, and the load generator bench/sdo_rtt.c
measures what it claims (every transaction answered, a synchronous TPDO really configured) and
fails loudly when nobody answers. $BENCH_RESPONDER and $BENCH_SDO_RTT are set by ctest."""

import json
import os
import subprocess
import time

import pytest

from conftest import IFACE

RESPONDER = os.environ.get("BENCH_RESPONDER", "")
SDO_RTT = os.environ.get("BENCH_SDO_RTT", "")


@pytest.fixture
def responder(bus):
    if not os.access(RESPONDER, os.X_OK):
        pytest.fail(f"bench/responder.c is not built: set BENCH_RESPONDER (got {RESPONDER!r})")
    started = []

    def start(*args):
        proc = subprocess.Popen([RESPONDER, *args], stderr=subprocess.PIPE, text=True)
        started.append(proc)
        return proc

    yield start
    for proc in started:
        proc.terminate()
        proc.wait(timeout=5)


def sdo_rtt(*args):
    if not os.access(SDO_RTT, os.X_OK):
        pytest.fail(f"bench/sdo_rtt.c is not built: set BENCH_SDO_RTT (got {SDO_RTT!r})")
    return subprocess.run([SDO_RTT, *args], capture_output=True, text=True, timeout=60)


def answered(bus, frame, reply_id, reply):
    """The responder binds its socket after it starts: asks until it answers (deadline)."""
    deadline = time.monotonic() + 5.0
    while True:
        try:
            return bus.request(frame, reply_id, reply, timeout=0.2)
        except AssertionError:
            if time.monotonic() > deadline:
                raise


@pytest.mark.parametrize("clock", [[], ["--clock"]], ids=["plain", "clock"])
def test_responder_answers_an_expedited_upload_with_index_and_subindex(bus, responder, clock):
    responder(*clock, IFACE, "5")
    answered(bus, "605#4018100300000000", 0x585, "4318100300000000")
    bus.request("605#4000100000000000", 0x585, "4300100000000000")
    bus.expect_none(0x584, 0.1)


def test_responder_refuses_a_bad_node_id(responder):
    proc = responder(IFACE, "128")
    assert proc.wait(timeout=5) == 64
    assert "usage: responder" in proc.stderr.read()


def test_sdo_rtt_times_every_round_trip_to_the_daemon(bus, start_daemon):
    start_daemon(bus, "--node-id", 4)
    run = sdo_rtt(IFACE, "4", "50")
    assert run.returncode == 0, run.stderr
    result = json.loads(run.stdout)
    assert result["mode"] == "sdo_upload" and result["count"] == 50
    assert 0 < result["p50_us"] <= result["p99_us"] <= result["max_us"]
    assert result["per_s"] > 0


def test_sdo_rtt_sync_mode_makes_tpdo6_synchronous_and_times_it(bus, start_daemon):
    start_daemon(bus, "--node-id", 4)
    run = sdo_rtt("--sync", IFACE, "4", "20")
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["mode"] == "sync_tpdo"
    # The generator's downloads, as the bus saw them: COB-ID invalid, type 1, COB-ID valid.
    for sub in (1, 2, 1):
        bus.expect(0x584, f"6005180{sub}00000000")
    assert bus.sdo_read(4, 0x1805, 2) == 1
    assert bus.sdo_read(4, 0x1805, 1) == 0x284
    bus.send("080#")
    bus.expect(0x284)


def test_sdo_rtt_fails_loudly_when_nobody_answers():
    run = sdo_rtt(IFACE, "9", "10")
    assert run.returncode == 1
    assert "no frame on 589 from node 9 within 1000 ms" in run.stderr
