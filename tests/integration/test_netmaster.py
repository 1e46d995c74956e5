# SPDX-License-Identifier: Apache-2.0
"""comaster run and boot, the network master, against atv312d drives 4-6 configured by the DCFs of
examples/netmaster: the exact step and status lines (the PLC300's status bits), the configuration
read back with python canopen, an output set from another comaster reaching the drive by RPDO, a
drive killed (SIGKILL) and started again that the master boots and reconfigures, an identity
mismatch, CiA 302-2's boot errors and boot time 1F89h. Every wait is deadline based."""

import json
import os
import queue
import re
import signal
import subprocess
import threading
import time

import canopen
import pytest

from conftest import BOOT_TIMEOUT, EDS, EX_USAGE, IFACE, LOCAL_NODE, PERIODIC_LATENESS, ROOT, assert_periodic

COMASTER = os.environ.get("COMASTER") or str(ROOT / "build" / "apps" / "comaster" / "comaster")
NET = ROOT / "examples" / "netmaster"
EX_UNAVAILABLE, EX_CANTCREAT = 69, 73
EXIT_REFUSED, EXIT_TIMEOUT = 1, 2  # the run's refusal (its "error:" reply) is 1, as an SDO abort

BOOTED = "status 0x000F contacted configured error-control-started initialised"
MASTER_BOOTED = "master: status 0x000F all-contacted all-configured all-error-control-started init-finished"


def comaster(*args):
    p = subprocess.run([COMASTER, "-i", IFACE, *[str(a) for a in args]], capture_output=True, text=True,
                       timeout=30)
    return p.returncode, p.stdout, p.stderr


class Run:
    """`comaster run NETWORK` in the background, its output lines read as they come."""

    def __init__(self, network, control):
        self.control = str(control)
        self.proc = subprocess.Popen([COMASTER, "-i", IFACE, "run", str(network), "--control", self.control],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1)
        self.lines = queue.Queue()
        self.seen = []
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def expect(self, text, timeout=BOOT_TIMEOUT):
        """Waits for the next line that is exactly text; returns the lines passed on the way."""
        deadline = time.monotonic() + timeout
        passed = []
        while True:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise AssertionError(f"no line {text!r} within {timeout} s; saw:\n" + "\n".join(self.seen[-40:]))
            if line is None:
                raise AssertionError(f"comaster run exited {self.proc.wait()} before {text!r}; saw:\n"
                                     + "\n".join(self.seen[-40:]))
            self.seen.append(line)
            if line == text:
                return passed
            passed.append(line)

    def expect_all(self, texts, timeout=BOOT_TIMEOUT):
        """Waits until every line of texts came, in any order (slaves of two daemons boot in the
        order their boot-ups reach the master)."""
        deadline = time.monotonic() + timeout
        missing = list(texts)
        while missing:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise AssertionError(f"no lines {missing} within {timeout} s; saw:\n" + "\n".join(self.seen[-40:]))
            if line is None:
                raise AssertionError(f"comaster run exited {self.proc.wait()}; saw:\n" + "\n".join(self.seen[-40:]))
            self.seen.append(line)
            if line in missing:
                missing.remove(line)

    def request(self, *args):
        return comaster(*args, "--control", self.control)

    def stop(self):
        """SIGTERM, the normal end of a run; returns its exit status once all its output is read."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            self.proc.wait(timeout=5)
        while (line := self.lines.get(timeout=5)) is not None:
            self.seen.append(line)
        return self.proc.returncode


@pytest.fixture
def run(tmp_path):
    runs = []

    def start(network=NET / "bench.ini"):
        r = Run(network, tmp_path / "control.sock")
        runs.append(r)
        return r

    yield start
    for r in runs:
        assert r.stop() == 0, "comaster run did not exit 0 on SIGTERM"
        assert not [line for line in r.seen if line.startswith("comaster: ") and "control socket" not in line
                    and not line.startswith(f"comaster: warn: interface {IFACE} is down")], \
            "SIGTERM, the normal end of a run, was reported as an error"
        assert not os.path.exists(r.control), "the control socket was left behind"
        print("--- comaster run ---\n" + "\n".join(r.seen))


@pytest.fixture
def remote():
    """Factory: remote(node_id), a python canopen node on a network connected now, so that its SDO
    client sees no reply of the master's own transfers from before."""
    networks = []

    def connect(node_id):
        net = canopen.Network()
        net.connect(interface="socketcan", channel=IFACE)
        networks.append(net)
        node = canopen.RemoteNode(node_id, str(EDS))
        net.add_node(node)
        return node

    yield connect
    for net in networks:
        net.disconnect()


def expect_booted(r, nodes=(4, 5, 6)):
    r.expect_all([f"node {node} drive{node}: {BOOTED}" for node in nodes] + [MASTER_BOOTED])


def test_run_boots_drives_4_to_6_from_their_dcfs(bus, start_daemon, run, remote):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    passed = r.expect(f"node 4 drive4: {BOOTED}")
    assert passed[1:] == [
        "node 4 drive4: wait boot-up", "node 5 drive5: wait boot-up", "node 6 drive6: wait boot-up",
        "node 4 drive4: read device type", "node 4 drive4: read identity",
        "node 4 drive4: status 0x0001 contacted",
        "node 4 drive4: download configuration", "node 4 drive4: status 0x0003 contacted configured",
        "node 4 drive4: status 0x0007 contacted configured error-control-started",
        "master: protocol 3 error control enabled",  # the PLC300's %SB3180: heartbeats consumed
    ], passed
    expect_booted(r, (5, 6))
    for node_id in (4, 5, 6):
        bus.expect(0x700 + node_id, "05", timeout=1.0)  # heartbeat 100 ms, operational
        node = remote(node_id)
        assert node.sdo[0x1017].raw == 100
        assert node.sdo[0x1405][1].raw == 0x300 + node_id
        assert node.sdo[0x1805][1].raw == 0x280 + node_id
        assert node.sdo[0x203C][2].raw == 20
        assert node.sdo[0x203C][3].raw == 20
    rc, out, _ = r.request("status")
    assert rc == 0
    assert out.splitlines() == [
        "master 0x000F all-contacted all-configured all-error-control-started init-finished",
        "protocol 3 error control enabled", "node 4 drive4 0x000F operational", "node 5 drive5 0x000F operational",
        "node 6 drive6 0x000F operational", "last SDO error: none", "last EMCY: none"]
    rc, out, _ = r.request("--json", "status")
    assert rc == 0
    assert json.loads(out) == {
        "status": "0x000F", "protocol_state": {"code": 3, "text": "error control enabled"},
        "boot_time": {"ms": 0, "over": False},
        "slaves": [{"node": n, "name": f"drive{n}", "assignment": assignment,
                    "expected": {"1F84h": "0x00010192", "1F85h": "0x0000005F"}, "status": "0x000F",
                    "step": "operational", "failure": None, "boot_error": None, "error_control_error": None}
                   for n, assignment in ((4, "0x0000000D"), (5, "0x00000005"), (6, "0x00000005"))],
        "last_sdo_error": None, "last_emcy": None}


def test_set_speed_reaches_the_drive_by_rpdo(bus, start_daemon, run, remote):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    for control in (6, 7, 15):  # shutdown, switch on, enable operation
        assert r.request("set", 4, "control", control) == (0, "ok\n", "")
        bus.expect(0x304, bytes([control, 0, 0, 0]))
    assert r.request("set", 4, "speed", 1200) == (0, "ok\n", "")
    bus.expect(0x304, "0F00B004")  # control 0x000F, speed 1200 = 0x04B0
    assert remote(4).sdo[0x6042].raw == 1200
    # The drive's TPDO6 (status word, actual speed) feeds the inputs: it runs up to 1200 rpm.
    deadline = time.monotonic() + 10
    while True:
        frame = bus.expect(0x284, timeout=1.0)
        if int.from_bytes(frame.data[2:4], "little", signed=True) == 1200:
            break
        assert time.monotonic() < deadline, f"the drive did not reach 1200 rpm: {frame}"
    bus.expect(0x284, timeout=1.0)  # one more TPDO6 after the master had the last one
    assert r.request("get", 4, "actual_speed") == (0, "1200\n", "")
    assert r.request("get", 4, "status")[1] == "1575\n"  # 0x0627: operation enabled, at speed
    assert r.request("get", 4, "speed") == (0, "1200\n", "")
    assert r.request("--json", "get", 4, "actual_speed") == (0, '{"node": 4, "name": "actual_speed", "value": 1200}\n', "")
    assert r.request("--json", "set", 5, "speed", "0x10") == (0, '{"node": 5, "name": "speed", "value": 16}\n', "")
    assert r.request("get", 5, "actual_speed") == (0, "0\n", "")


def test_image_by_the_plc300_markers(bus, start_daemon, run):
    """The process image as the PLC300 manual's network markers (5.4, 7.2): bytes from 2000, in
    the order of the slaves and their PDOs (node 4's RPDO1 control at %QB2000..2001, its RPDO6
    control and speed at %QB2002..2005; its TPDO1 status at %IB2000..2001, its TPDO6 status and
    actual speed at %IB2002..2005), byte, word and double word over the same bytes, least
    significant first (docs/decisions.md, D-IMAGE-ADDRESS)."""
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    # One double word over two PDOs: shutdown in RPDO1, then switch on in RPDO6.
    assert r.request("set", "%QD2000", "0x00070006") == (0, "ok\n", "")
    bus.expect(0x204, "0600")
    bus.expect(0x304, "07000000")
    assert r.request("set", "%QW2002", 15) == (0, "ok\n", "")  # enable operation
    bus.expect(0x304, "0F000000")
    assert r.request("set", "%QW2004", 1200) == (0, "ok\n", "")
    bus.expect(0x304, "0F00B004")
    assert r.request("get", 4, "speed") == (0, "1200\n", "")
    assert r.request("get", "%QW2004") == (0, "1200\n", "")
    assert r.request("get", "%QB2004") == (0, "176\n", "")  # 0xB0, the low byte first
    assert r.request("get", "%QB2005") == (0, "4\n", "")
    assert r.request("get", "%QD2000") == (0, f"{0x000F0006}\n", "")
    assert r.request("--json", "set", "%QB2005", 5) == (0, '{"address": "%QB2005", "value": 5}\n', "")
    bus.expect(0x304, "0F00B005")  # speed 0x05B0 = 1456
    assert r.request("set", "%QW2004", 1200) == (0, "ok\n", "")
    bus.expect(0x304, "0F00B004")
    deadline = time.monotonic() + 10
    while True:
        frame = bus.expect(0x284, timeout=1.0)
        if int.from_bytes(frame.data[2:4], "little", signed=True) == 1200:
            break
        assert time.monotonic() < deadline, f"the drive did not reach 1200 rpm: {frame}"
    bus.expect(0x284, timeout=1.0)  # one more TPDO6 and TPDO1 after the master had the last ones
    bus.expect(0x184, "2706", timeout=1.0)
    assert r.request("get", "%IW2004") == (0, "1200\n", "")
    assert r.request("get", "%IW2002") == (0, "1575\n", "")  # 0x0627: operation enabled, at speed
    assert r.request("get", "%ID2000") == (0, f"{0x06270627}\n", "")  # TPDO1's and TPDO6's status
    assert r.request("--json", "get", "%iw2004") == (0, '{"address": "%iw2004", "value": 1200}\n', "")
    assert r.request("get", "%IB2511") == (0, "0\n", "")  # past the PDOs, inside the 512 bytes
    # Refused by the run (exit 1): an input to set, a value wider than the marker.
    assert r.request("set", "%IW2000", 1) == (EXIT_REFUSED, "", "comaster: error: %IW2000 is an input "
                                               "(the slaves' TPDOs write it): get it\n")
    rc, _, err = r.request("set", "%QB2000", 256)
    assert rc == EXIT_REFUSED and err.startswith("comaster: error: %QB2000: "), err
    # Not a marker (exit 64, before the run is asked): misaligned, outside the image, a node too.
    for args in (("get", "%IW2001"), ("get", "%ID2002"), ("get", "%QB2512"), ("set", "%QB1999", 1)):
        rc, _, err = r.request(*args)
        assert rc == EX_USAGE and f"'{args[1]}' is not a process image address" in err, (args, err)
    rc, _, err = r.request("get", "%IW2000", 4)
    assert rc == EX_USAGE and "too many arguments from '4'" in err, err
    rc, out, _ = r.request("status")
    assert "node 4 drive4 0x000F operational" in out


def test_bad_requests_are_refused(bus, start_daemon, run):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    rc, _, err = r.request("set", 4, "status", 5)
    assert rc == EXIT_REFUSED and "is an input" in err, err
    rc, _, err = r.request("set", 4, "ACC", 5)
    assert (rc, err) == (EXIT_REFUSED, "comaster: error: node 4: 203Ch:02 (ACC) is in none of its PDOs\n")
    rc, _, err = r.request("set", 4, "speed", 40000)
    assert rc == EXIT_REFUSED and "speed" in err, err
    rc, _, err = r.request("get", 9, "speed")
    assert (rc, err) == (EXIT_REFUSED, "comaster: error: node 9 is not a slave of the network\n")
    rc, _, err = comaster("status", "--control", "/nonexistent/control.sock")
    assert rc == EX_UNAVAILABLE and err.startswith("comaster: error: no comaster run answers"), err
    # A second run on the socket of the first: it cannot have it, and sends nothing.
    mark = time.time()
    assert comaster("run", NET / "bench.ini", "--control", r.control) == (
        EX_CANTCREAT, "", f"comaster: error: another comaster run answers on {r.control}: stop it, or give "
        "--control PATH\n")
    assert [f for f in bus.collect(0.3) if f.timestamp > mark and f.can_id == 0x000] == []


def test_drive_killed_and_restarted_is_rebooted_and_reconfigured(bus, start_daemon, run, remote):
    drive4 = start_daemon(bus, "--node-id", "4")
    start_daemon(bus, "--node-id", "5-6")
    r = run()
    expect_booted(r)
    drive4.proc.kill()
    drive4.proc.wait()
    r.expect("node 4 drive4: status 0x0020 error-control-error (heartbeat error)", timeout=2.0)
    r.expect("master: status 0x0028 init-finished error-control-error", timeout=1.0)
    start_daemon(bus, "--node-id", "4")
    r.expect(f"node 4 drive4: {BOOTED}", timeout=10.0)
    r.expect(MASTER_BOOTED, timeout=1.0)
    node = remote(4)
    assert node.sdo[0x203C][2].raw == 20  # the new process started from ACC 30
    assert node.sdo[0x1017].raw == 100
    bus.expect(0x704, "05", timeout=1.0)


def guarded_bench(tmp_path):
    """The bench with drive 5 under node guarding (100 ms, life time factor 3: its 100Ch and 100Dh
    written by the boot, 1017h left 0 since a heartbeat producer ignores guarding requests) and
    drives 4 and 6 under heartbeat (300 ms); drives 4 and 5 lost are only reported."""
    for name in ("bench.cpj", "drive4.dcf", "drive6.dcf"):
        (tmp_path / name).write_text((NET / name).read_text())
    dcf = configured(configured((NET / "drive5.dcf").read_text(), "100C", "100"), "100D", "3")
    start = dcf.index("[1017]\n")
    end = dcf.index("\n\n", start)
    dcf = dcf[:start] + dcf[start:end].replace("ParameterValue=100", "ParameterValue=0") + dcf[end:]
    (tmp_path / "drive5.dcf").write_text(dcf)
    (tmp_path / "guarded.ini").write_text(
        "[Master]\ncpj = bench.cpj\nsdo_timeout = 500\nboot_time = 1000\nretry_delay = 1000\n"
        "[Node4]\nheartbeat = 300\non_error = report\n"
        "[Node5]\nguard_time = 100\nlife_time_factor = 3\non_error = report\n"
        "[Node6]\nheartbeat = 300\n")
    return tmp_path / "guarded.ini"


def test_node_guarding_error_told_from_heartbeat_error(bus, start_daemon, run, tmp_path):
    """The PLC300's status bit 5 is one for both error controls; its CANopen protocol state
    (%SB3180: 4 node guarding error, 5 heartbeat error) and the slave's record tell them apart:
    drive 5, guarded, killed, misses the master's guarding requests; drive 4, a heartbeat
    producer, killed, stops beating."""
    drive4 = start_daemon(bus, "--node-id", "4")
    drive5 = start_daemon(bus, "--node-id", "5")
    start_daemon(bus, "--node-id", "6")
    r = run(guarded_bench(tmp_path))
    expect_booted(r)
    assert r.request("status")[1].splitlines()[1] == "protocol 3 error control enabled"
    bus.expect(0x705, rtr=True, timeout=1.0)  # the master guards drive 5, which answers
    assert bus.expect(0x705, timeout=1.0).data in (b"\x05", b"\x85")

    killed = time.time()
    drive5.proc.kill()
    drive5.proc.wait()
    r.expect("node 5 drive5: status 0x002F contacted configured error-control-started initialised "
             "error-control-error (node guarding error)", timeout=2.0)
    r.expect("master: protocol 4 node guarding error", timeout=1.0)
    guarding = [f for f in bus.collect(0.3, 0x705) if f.timestamp > killed]
    assert len(guarding) >= 4 and all(f.rtr for f in guarding), guarding  # asked on, no reply

    killed = time.time()
    drive4.proc.kill()
    drive4.proc.wait()
    r.expect("node 4 drive4: status 0x002F contacted configured error-control-started initialised "
             "error-control-error (heartbeat error)", timeout=2.0)
    r.expect("master: protocol 5 heartbeat error", timeout=1.0)  # node 4 comes first in the table
    assert [f for f in bus.collect(0.3, 0x704) if f.timestamp > killed] == []  # no beat, no request

    rc, out, _ = r.request("status")
    assert out.splitlines()[:5] == [
        "master 0x002F all-contacted all-configured all-error-control-started init-finished "
        "error-control-error", "protocol 5 heartbeat error",
        "node 4 drive4 0x002F error control lost (heartbeat error)",
        "node 5 drive5 0x002F error control lost (node guarding error)", "node 6 drive6 0x000F operational"]
    state = json.loads(r.request("--json", "status")[1])
    assert state["protocol_state"] == {"code": 5, "text": "heartbeat error"}
    assert [s["error_control_error"] for s in state["slaves"]] == ["heartbeat error", "node guarding error", None]

    start_daemon(bus, "--node-id", "5")  # its boot-up: booted again, bit 5 and its kind cleared
    r.expect(f"node 5 drive5: {BOOTED}", timeout=10.0)
    state = json.loads(r.request("--json", "status")[1])
    assert [s["error_control_error"] for s in state["slaves"]] == ["heartbeat error", None, None]
    assert state["protocol_state"]["code"] == 5


def test_identity_mismatch_is_an_init_error(bus, start_daemon, run, tmp_path):
    start_daemon(bus, "--node-id", "4-6")
    ini = tmp_path / "bench.ini"
    ini.write_text(f"[Master]\ncpj = {NET / 'bench.cpj'}\nretry_delay = 60000\n[Node6]\nvendor = 0x99\n")
    r = run(ini)
    failure = "identity mismatch (read 0x0000005F), CiA 302 error D: vendor-ID differs from 1F85h"
    r.expect(f"node 6 drive6: init error: {failure}")
    r.expect("master: status 0x0018 init-finished init-error")
    rc, out, _ = r.request("status")
    assert rc == 0
    assert f"node 6 drive6 0x0010 init error: {failure}" in out.splitlines(), out


def test_boot_time_1f89_and_the_boot_errors_of_cia_302(bus, start_daemon, run, tmp_path):
    """CiA 302-2's boot time 1F89h ([Master] network_boot_time) and expected identity 1F84h
    ([NodeN] device_type): drive 4, mandatory, is not on the bus (error B, no answer to 1000h),
    drive 5 is expected to be another device (error C); at 1.5 s the run tells that the mandatory
    drive is missing (status bit 7); drive 4, started later, is booted and the bit stays."""
    start_daemon(bus, "--node-id", "5-6")
    ini = tmp_path / "bench.ini"
    ini.write_text(f"[Master]\ncpj = {NET / 'bench.cpj'}\nboot_time = 200\nretry_delay = 500\n"
                   "network_boot_time = 1500\n[Node4]\nmandatory = yes\n[Node5]\ndevice_type = 0x00020192\n")
    r = run(ini)
    begun = time.monotonic()
    r.expect_all(["node 4 drive4: init error: SDO error, CiA 302 error B: no answer to the read of 1000h",
                  "node 5 drive5: init error: device type mismatch (read 0x00010192), CiA 302 error C: "
                  "device type differs from 1F84h"])
    r.expect("network: boot time 1F89h (1500 ms) over, a mandatory slave not configured", timeout=3.0)
    assert time.monotonic() - begun > 1.2
    state = json.loads(r.request("--json", "status")[1])
    assert state["boot_time"] == {"ms": 1500, "over": True}
    assert int(state["status"], 16) & 0x80
    slaves = {s["node"]: s for s in state["slaves"]}
    assert slaves[4]["boot_error"] == {"code": "B", "text": "no answer to the read of 1000h"}
    assert slaves[5]["boot_error"] == {"code": "C", "text": "device type differs from 1F84h"}
    assert slaves[5]["expected"] == {"1F84h": "0x00020192", "1F85h": "0x0000005F"}
    assert slaves[6]["boot_error"] is None
    start_daemon(bus, "--node-id", "4")
    r.expect(f"node 4 drive4: {BOOTED}", timeout=10.0)
    state = json.loads(r.request("--json", "status")[1])
    assert {s["node"]: s["boot_error"] for s in state["slaves"]} == {
        4: None, 5: {"code": "C", "text": "device type differs from 1F84h"}, 6: None}
    assert state["boot_time"]["over"] is True


def test_configuration_request_1f25_configures_again(bus, start_daemon, run, remote):
    """CiA 302-2's 1F25h through the run (comaster configure): drive 5's 1017h changed behind the
    master's back; configure 5 resets it (000#8205) and downloads its concise DCF again (1017h =
    100 back), the others untouched; configure all resets each slave; node 9 is refused."""
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    remote(5).sdo[0x1017].raw = 250
    bus.collect(0.2)
    rc, out, err = r.request("configure", 5)
    assert (rc, out, err) == (0, "ok\n", "")
    bus.expect(0x000, "8205", timeout=1.0)
    r.expect(f"node 5 drive5: {BOOTED}", timeout=10.0)
    assert remote(5).sdo[0x1017].raw == 100
    assert [f for f in bus.collect(0.3, 0x000) if f.data[0] == 0x82] == []
    rc, out, _ = r.request("--json", "configure", "all")
    assert (rc, json.loads(out)) == (0, {"node": "all", "configuration_request": "0x666E6F63"})
    for node_id in (4, 5, 6):
        bus.expect(0x000, f"82{node_id:02X}", timeout=1.0)
    r.expect_all([f"node {node} drive{node}: {BOOTED}" for node in (4, 5, 6)], timeout=10.0)
    rc, _, err = r.request("configure", 9)
    assert (rc, err) == (EXIT_REFUSED, "comaster: error: configure: node 9 is not a slave of the run\n")
    # A node-id written in hexadecimal is answered as the number it is, valid JSON.
    rc, out, _ = r.request("--json", "configure", "0x05")
    assert (rc, json.loads(out)) == (0, {"node": 5, "configuration_request": "0x666E6F63"})
    bus.expect(0x000, "8205", timeout=1.0)


def configured(dcf, section, value):
    """The DCF text with the DefaultValue of [section] turned into a ParameterValue of value."""
    start = dcf.index(f"[{section}]\n")
    end = dcf.index("\n\n", start)
    block = re.sub(r"(?m)^DefaultValue=.*$", f"ParameterValue={value}", dcf[start:end])
    return dcf[:start] + block + dcf[end:]


def test_boot_signed_values_and_valid_pdos(bus, start_daemon, remote, tmp_path):
    """A DCF as configuration tools write it (issue 19): 6042h = -1234 (INTEGER16), TPDO1's inhibit
    time and TPDO6's mapping while both PDOs are valid, which the drive refuses (0x06090030,
    0x06010000) unless the master invalidates them first, as it does."""
    text = (NET / "drive4.dcf").read_text()
    for section, value in (("6042", "-1234"), ("1800sub3", "200"), ("1A05sub0", "1")):
        text = configured(text, section, value)
    dcf = tmp_path / "drive4.dcf"
    dcf.write_text(text)
    start_daemon(bus, "--node-id", "4")
    rc, out, err = comaster("boot", 4, dcf)
    assert rc == 0, out + err
    for request in ("2300180184010080", "2B001803C8000000", "2300180184010000",
                    "2305180184020080", "2F051A0000000000", "2F051A0001000000", "2305180184020000",
                    "2B4260002EFB0000"):
        bus.expect(0x604, request)  # in this order
    assert remote(4).sdo[0x6042].raw == -1234
    assert remote(4).sdo[0x1800][3].raw == 200
    assert remote(4).sdo[0x1A05][0].raw == 1


def test_boot_dcf_of_the_manuals_tpdo_records(bus, start_daemon, remote, tmp_path):
    """A DCF that writes TPDO1's and TPDO6's records as the ATV312 manual's object table prints them
    (issue 31): 1800h:03 = 30 (unit 1 ms, D-INHIBIT-TIME) and the reserved RW U8 sub-index 4 of
    1800h and 1805h, which the drive lacked, so the boot failed. All are taken, in the record's
    order, TPDO1 invalidated around its inhibit time."""
    text = (NET / "drive4.dcf").read_text()
    for section, value in (("1800sub3", "30"), ("1800sub4", "7"), ("1805sub4", "9")):
        text = configured(text, section, value)
    dcf = tmp_path / "drive4.dcf"
    dcf.write_text(text)
    start_daemon(bus, "--node-id", "4")
    rc, out, err = comaster("boot", 4, dcf)
    assert rc == 0, out + err
    for request in ("2300180184010080", "2B0018031E000000", "2F00180407000000", "2300180184010000",
                    "2F05180409000000"):
        bus.expect(0x604, request)  # in this order
    assert remote(4).sdo[0x1800][3].raw == 30
    assert remote(4).sdo[0x1800][4].raw == 7
    assert remote(4).sdo[0x1805][4].raw == 9


def test_boot_one_slave(bus, start_daemon, remote):
    start_daemon(bus, "--node-id", "4")
    rc, out, err = comaster("boot", 4, NET / "drive4.dcf")
    assert rc == 0, out + err
    assert out.splitlines()[-3:] == [f"node 4 node4: {BOOTED}", MASTER_BOOTED, "node 4 node4: operational"]
    assert remote(4).sdo[0x203C][2].raw == 20
    bus.expect(0x704, "05", timeout=1.0)
    rc, out, err = comaster("boot", 7, NET / "drive4.dcf")
    assert rc == EXIT_TIMEOUT, out + err
    assert "SDO error: node 7 read 1000h:00 abort 0x05040000 (SDO protocol timed out)" in out.splitlines(), out


def test_boot_new_can_id_of_a_valid_pdo(bus, start_daemon, remote, tmp_path):
    """A DCF that changes only the COB-ID of TPDO1, valid on the drive (issue 19): the drive refuses
    a new CAN-ID of a valid PDO (0x06090030), so the master writes the old COB-ID (the DCF's
    DefaultValue) with bit 31 set first, then the new one."""
    text = (NET / "drive4.dcf").read_text()
    text = text.replace("[1800sub1]\n", "[1800sub1]\nParameterValue=$NODEID+0x190\n", 1)
    dcf = tmp_path / "drive4.dcf"
    dcf.write_text(text)
    start_daemon(bus, "--node-id", "4")
    rc, out, err = comaster("boot", 4, dcf)
    assert rc == 0, out + err
    bus.expect(0x604, "2300180184010080")
    bus.expect(0x604, "2300180194010000")
    assert remote(4).sdo[0x1800][1].raw == 0x194


# ---- the master's own heartbeat and the requests of comaster run's control socket --------------

MASTER_HEARTBEAT_MS = 100
DRIVE4_CONSUMES_MS = 300  # drive 4's 1016h:01 consumes node 1's heartbeat


def supervised_bench(tmp_path):
    """The bench with the master's heartbeat (node 1, 100 ms) and drive 4 consuming it (1016h:01 =
    node 1, 300 ms), as a PLC300 network whose drives supervise the master."""
    for name in ("bench.cpj", "drive5.dcf", "drive6.dcf"):
        (tmp_path / name).write_text((NET / name).read_text())
    dcf = (NET / "drive4.dcf").read_text()
    dcf = dcf.replace("[1016sub1]\n", f"[1016sub1]\nParameterValue=0x{(1 << 16) | DRIVE4_CONSUMES_MS:08X}\n", 1)
    (tmp_path / "drive4.dcf").write_text(dcf)
    ini = (NET / "bench.ini").read_text().replace("[Master]\n", f"[Master]\nnode_id = 1\nheartbeat = {MASTER_HEARTBEAT_MS}\n", 1)
    (tmp_path / "bench.ini").write_text(ini)
    return tmp_path / "bench.ini"


def test_drive_supervises_the_master_heartbeat_until_it_stops(bus, start_daemon, run, tmp_path):
    """The PLC300 produces a heartbeat (its 1017h, [Master] heartbeat): drive 4, configured to consume
    it, does not fault while the master beats, and does (EMCY 8130h) once the master's
    communication is disabled and its heartbeat stops."""
    start_daemon(bus, "--node-id", "4-6")
    r = run(supervised_bench(tmp_path))
    expect_booted(r)
    # The beats from here on: the first one, queued since the start, leaves in the master's first
    # wake-up with the boot's burst, after a fresh process's first touches of its memory (each a
    # host round trip under User-Mode Linux), and may be late while its schedule is not.
    bus.collect(0.0)
    beats = bus.collect_n(0x701, 10, timeout=2.0)
    assert all(f.data == bytes([0x05]) for f in beats)
    assert_periodic(beats, MASTER_HEARTBEAT_MS / 1000, "the master's heartbeat")
    bus.expect_none(0x084, 0.5)  # several consumer times: drive 4 is content
    rc, out, _ = r.request("disable")
    assert (rc, out) == (0, "master 0x8000 disabled\n")
    stopped = time.monotonic()
    bus.expect(0x084, "3081010000000000", timeout=1.0)  # heartbeat error, error register 01
    assert time.monotonic() - stopped >= DRIVE4_CONSUMES_MS / 1000 - 0.1 - PERIODIC_LATENESS
    bus.expect_none(0x701, 0.3)


def test_nmt_through_the_run_is_confirmed_by_the_state(bus, start_daemon, run):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    mark = bus.mark()
    assert r.request("nmt", "stop", 5, "--run") == (0, "node 5: Stopped\n", "")
    bus.expect(0x000, "0205", since=mark)
    bus.expect(0x705, "04")
    rc, out, _ = r.request("--json", "nmt", "preop", "all", "--run")
    assert rc == 0
    assert json.loads(out) == {"node": "all", "command": "preop", "state": "Pre-operational",
                               "confirmed": [4, 5, 6]}
    assert r.request("nmt", "start", "all", "--run") == (0, "all: Operational (nodes 4 5 6)\n", "")
    rc, out, err = r.request("--timeout", 300, "nmt", "start", 9, "--run")
    assert (rc, out) == (EXIT_TIMEOUT, "")
    assert err == "comaster: error: node 9: no Operational reported within 300 ms after start: is the node on vcan0?\n"
    assert r.request("nmt", "reset-node", 6, "--run") == (0, "node 6: boot-up\n", "")
    r.expect(f"node 6 drive6: {BOOTED}")  # booted again by the master
    rc, out, _ = r.request("status")  # five commands: bit 8 (the NMT toggle feedback) is set
    assert out.splitlines()[0] == ("master 0x010F all-contacted all-configured all-error-control-started "
                                   "init-finished nmt-toggle")


def test_sdo_through_the_run_shares_its_client(bus, start_daemon, run, remote):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    assert r.request("read", 4, "ACC", "--run") == (0, "20\n", "")
    bus.expect(0x604, "403C200200000000")  # the master's own client: 604h, the only one
    assert r.request("write", 4, "ACC", 50, "--run") == (0, "ok\n", "")
    assert remote(4).sdo[0x203C][2].raw == 50
    rc, out, _ = r.request("--json", "read", 5, "0x1008", "string", "--run")
    assert rc == 0
    assert json.loads(out) == {"node": 5, "index": "0x1008", "subindex": 0, "name": "Manufacturer device name",
                               "type": "VISIBLE_STRING", "value": "ATV312"}
    rc, _, err = r.request("read", 4, "0x1234:0", "u8", "--run")
    assert (rc, err) == (EXIT_REFUSED, "comaster: error: node 4, 1234:00: SDO abort 0x06020000: object does not exist in the "
                            "object dictionary\n")
    rc, _, err = r.request("read", 9, "0x1000", "u32", "--run")
    assert (rc, err) == (EXIT_TIMEOUT, "comaster: error: node 9, 1000:00: no answer within 500 ms (the run's sdo_timeout)\n")
    rc, out, _ = r.request("status")
    assert "last SDO error: node 9 read 1000h:00 abort 0x05040000 (SDO protocol timed out)" in out.splitlines()


def test_sdo_text_of_control_characters_stays_json(bus, start_daemon, run, local_node):
    """A device's VISIBLE_STRING may hold any byte: the run's JSON reply carries the longest one it
    reads (256 bytes, RUN_SDO_VALUE_MAX) whole, each control character as \\u00XX (6 bytes)."""
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    text = "\x01" * 255 + "\x1f"
    assert comaster("write", LOCAL_NODE, "0x2001", "string", text)[0] == 0
    rc, out, err = r.request("--json", "read", LOCAL_NODE, "0x2001", "string", "--run")
    assert (rc, err) == (0, "")
    assert json.loads(out)["value"] == text


def test_disable_stops_the_master_and_enable_boots_the_network_again(bus, start_daemon, run):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    assert r.request("disable") == (0, "master 0x8000 disabled\n", "")
    disabled = time.time()
    r.expect("master: status 0x8000 disabled")
    frames = [f for f in bus.collect(0.5) if f.timestamp > disabled]
    assert [f for f in frames if f.can_id == 0x000 or 0x600 <= f.can_id <= 0x67F] == []
    assert frames, "the drives beat on"
    rc, out, _ = r.request("status")
    assert out.splitlines()[:3] == ["master 0x8000 disabled", "protocol 0 disabled", "node 4 drive4 0x0000 idle"]
    rc, _, err = r.request("nmt", "start", 4, "--run")
    assert (rc, err) == (EXIT_REFUSED, "comaster: error: the communication of the run is disabled: comaster enable\n")
    assert r.request("--json", "enable") == (0, '{"status": "0x0000", "disabled": false}\n', "")
    bus.expect(0x000, "8200")
    expect_booted(r)


def test_can_tells_the_controller_state_and_counters(bus, start_daemon, run):
    start_daemon(bus, "--node-id", "4-6")
    r = run()
    expect_booted(r)
    rc, out, _ = r.request("can")
    assert rc == 0
    assert re.fullmatch(r"can vcan0: error-active, rx \d+, tx \d+, tx-dropped 0, error-frames 0, bus-off 0\n", out), out
    rc, out, _ = r.request("--json", "can")
    state = json.loads(out)
    assert state["state"] == "error-active" and state["bus_power"] is True and state["tx"] > 10
    assert (state["node_id"], state["bit_rate"]) == (None, None)  # bench.ini gives no markers
    try:
        subprocess.run(["ip", "link", "set", IFACE, "down"], check=True, timeout=5)
        deadline = time.monotonic() + 2.0
        while (out := r.request("can")[1]).split(",")[0] != "can vcan0: no bus power":
            assert time.monotonic() < deadline, out
        rc, out, _ = r.request("status")  # bits 14 and 15 (the slaves are lost meanwhile)
        assert re.fullmatch(r"master 0xC0[0-9A-F]{2} .*no-bus-power disabled", out.splitlines()[0]), out
    finally:
        subprocess.run(["ip", "link", "set", IFACE, "up"], check=True, timeout=5)


def test_can_tells_the_node_id_and_bit_rate_markers(bus, start_daemon, run, tmp_path):
    """The PLC300's CAN interface markers as [Master] gives them: %CB3052 (node-id) and %CB3055
    (bit rate code 2 = 500 kbit/s), reported with the controller's state."""
    ini = tmp_path / "bench.ini"
    ini.write_text(f"[Master]\ncpj = {NET / 'bench.cpj'}\nnode_id = 1\nbit_rate = 2\n")
    start_daemon(bus, "--node-id", "4-6")
    r = run(ini)
    expect_booted(r)
    rc, out, _ = r.request("can")
    assert rc == 0
    assert re.fullmatch(r"can vcan0: error-active, rx \d+, tx \d+, tx-dropped 0, error-frames 0, bus-off 0, "
                        r"node-id 1, bit-rate 2 \(500 kbit/s\)\n", out), out
    state = json.loads(r.request("--json", "can")[1])
    assert (state["node_id"], state["bit_rate"]) == (1, {"code": 2, "bit_s": 500000})
    ini.write_text(f"[Master]\ncpj = {NET / 'bench.cpj'}\nbit_rate = 1\n")
    rc, _, err = comaster("run", ini, "--control", tmp_path / "other.sock")
    assert rc == 65 and "bit_rate = '1': give the PLC300's code" in err, err


def test_mandatory_drive_lost_stops_all_nodes(bus, start_daemon, run, tmp_path):
    """CiA 302-2's 1F80h bit 6 ([Master] on_mandatory_error = stop_all, which the run shows as
    1F80h = 0x41): drive 4, mandatory, killed; the master stops every node (000#0200) instead of
    resetting drive 4, drives 5 and 6 beat Stopped until the application starts all nodes."""
    drive4 = start_daemon(bus, "--node-id", "4")
    start_daemon(bus, "--node-id", "5-6")
    text = (NET / "bench.ini").read_text().replace("cpj = bench.cpj", f"cpj = {NET / 'bench.cpj'}")
    ini = tmp_path / "bench.ini"
    ini.write_text(text.replace("start = each\n", "start = each\non_mandatory_error = stop_all\n"))
    r = run(ini)
    r.expect(f"comaster: network bench: 3 slaves on {IFACE}, NMT start-up 1F80h = 0x00000041, control socket "
             f"{r.control}")
    expect_booted(r)
    lost = time.time()
    drive4.proc.kill()
    drive4.proc.wait()
    bus.expect(0x000, "0200", timeout=2.0)
    r.expect("node 4 drive4: error control lost", timeout=1.0)
    bus.expect(0x705, "04", timeout=1.0)
    bus.expect(0x706, "04", timeout=1.0)
    assert [f for f in bus.collect(0.5, 0x000) if f.timestamp > lost and f.data != bytes([0x02, 0x00])] == []
    rc, _, err = r.request("--timeout", 300, "nmt", "start", "all", "--run")
    assert rc == EXIT_TIMEOUT, err  # drive 4 cannot confirm: it is gone
    bus.expect(0x705, "05", timeout=1.0)
    bus.expect(0x706, "05", timeout=1.0)
