# SPDX-License-Identifier: Apache-2.0
"""atv312d --devicenet on real SocketCAN against the project's scanner, dnscan: the duplicate MAC ID
check of several drives on one bus, scan, explicit get/set with a fragmented response, polled I/O
to 1200 rpm, the transparent assemblies after selecting them and an Identity Reset, the stored
selection across a restart, a UCMM connection (group 3) with its Get, Set and Close, dnscan's
get and set over a connection it opens by UCMM, an I/O
timeout faulting the drive with CnF and the scanner's fault reset, the connections released while the drive runs, bus off and the interface coming back as
the same CnF, a drive killed and restarted, and the command lines that mix CANopen and DeviceNet.

Frames are DeviceNet's predefined master/slave connection set (docs/devicenet.md): for MAC ID 25
the check is 4CF, the explicit response 4CB, the scanner's explicit request 4CC, its unconnected
request 4CE. Every wait has a deadline: a frame, a line of dnscan, or a state of the control
surface."""

import os
import queue
import signal
import subprocess
import threading
import time

import can
import pytest

from conftest import ONLINE_TIMEOUT, ROOT, ctl_state, daemon_path, wait_state

DNSCAN = os.environ.get("DNSCAN") or str(ROOT / "build" / "apps" / "dnscan" / "dnscan")
IFACE = "vcan0"
EX_USAGE = 64

# The check request of MAC ID 25 and 63: port 0, vendor 0x00F3, serial 0x31200000 + MAC ID.
CHECK_25 = (0x4CF, "00F30019002031")
CHECK_63 = (0x5FF, "00F3003F002031")
# The poll period of the continuous polls: dnscan makes it the expected packet rate, so the
# polled connection times out after 4 x 104 ms without a poll. With 25 ms (128 ms) a stall of
# the loaded User-Mode Linux guest timed a connection out now and then, a CnF no test asked for.
POLL_MS = 100


def dnscan(*args, timeout=30):
    """Runs dnscan on vcan0 as MAC ID 0 without its own 2 s check; (exit status, stdout, stderr)."""
    p = subprocess.run([DNSCAN, "-i", IFACE, "--no-check", *map(str, args)], capture_output=True, text=True,
                       timeout=timeout)
    return p.returncode, p.stdout, p.stderr


class Poller:
    """dnscan poll ... --every MS running in the background, its lines read with deadlines."""

    def __init__(self, *args):
        self.proc = subprocess.Popen([DNSCAN, "-i", IFACE, "--no-check", "poll", *map(str, args)],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.lines = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line.rstrip("\n"))

    def expect(self, text, timeout):
        """The first line containing text; fails with the lines seen when the deadline passes."""
        deadline = time.monotonic() + timeout
        seen = []
        while True:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise AssertionError(f"no line with {text!r} within {timeout} s; saw {seen[-5:]}") from None
            if text in line:
                return line
            seen.append(line)

    def stop(self, sig=signal.SIGINT):
        self.proc.send_signal(sig)
        return self.proc.wait(timeout=5)


def test_two_drives_check_their_mac_ids_and_answer_a_scan(start_dn, dump):
    d, sock = start_dn([25, 63])
    assert "started on vcan0: 2 drive(s) on DeviceNet at 125 kbit/s, MAC ID 25,63 (atv312)" in d.log()
    status, out, err = dnscan("scan")
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "25  vendor 0x00F3  type 2  product 6153  revision 1.1  serial 0x31200019  ATV312",
        "63  vendor 0x00F3  type 2  product 6153  revision 1.1  serial 0x3120003F  ATV312",
    ]
    # Allocate explicit on the unconnected port, Release after the identity.
    dump.expect(0x4CE, "004B03010100")
    dump.expect(0x4CB, "00CB00")
    dump.expect(0x5FE, "004B03010100", since=0)
    dump.expect(0x5FB, "00CB00", since=0)
    state = ctl_state(sock, 63)
    assert (state["node"], state["ms"], state["ns"], state["supervisor"], state["cia402"]) == (
        63, "green", "flashing-green", "not-ready", "Switch on disabled")
    # MS and NS are the card's LEDs; the CANopen card's RUN and ERR do not exist on DeviceNet.
    assert "run_led" not in state and "err_led" not in state and "sdo_requests" not in state["frames"]


# Frames for nobody on a bench of MAC IDs 25 and 63: other MAC IDs' group 2 messages, the group 2
# messages a slave does not take (bit-strobe, multicast poll, its own explicit response), group 1
# frames, group 3's UCMM responses (message 5: a card consumes group 3's other messages of every
# MAC ID, D-DEVICENET-UCMM), a CANopen heartbeat, a 29-bit frame.
FOR_NOBODY = ["4D6#004B03010100", "4D7#00F30078563412", "4C8#00", "4C9#00", "4CB#00CB00", "3D9#00000000",
              "359#00000000", "759#01CB00100A00", "77F#05"]


def test_frames_for_other_mac_ids_do_not_wake_the_daemon(start_dn, bus):
    d, sock = start_dn([25, 63])
    before = d.proc_status("voluntary_ctxt_switches")
    for _ in range(40):
        for text in FOR_NOBODY:
            bus.send(text)
        bus.bus.send(can.Message(arbitration_id=0x1234567, is_extended_id=True, data=b"\x01"), timeout=1.0)
    bus.collect(0.3)
    woke = d.proc_status("voluntary_ctxt_switches") - before
    assert woke == 0, f"{woke} wake-ups for {40 * (len(FOR_NOBODY) + 1)} frames addressed to nobody"
    # What a card consumes reaches it, and only it: MAC ID 63 counts no frame of MAC ID 25's.
    assert dnscan("get", 25, 1, 1, 1, "--type", "u16") == (0, "243\n", "")
    assert ctl_state(sock, 25)["frames"]["received"] == 3  # Allocate, Get, Release
    assert ctl_state(sock, 63)["frames"]["received"] == 0


def test_explicit_get_and_set_with_a_fragmented_response(start_dn, dump):
    start_dn([25])
    mark = dump.mark()
    assert dnscan("get", 25, 1, 1, 7, "--type", "string") == (0, "ATV312\n", "")
    # Identity product name, 9 bytes of response body: two fragments, each acknowledged.
    dump.expect(0x4CC, "400E010107", since=mark)
    dump.expect(0x4CB, "C0008E0641545633")
    dump.expect(0x4CC, "C0C000")
    dump.expect(0x4CB, "C0813132")
    dump.expect(0x4CC, "C0C100")
    # ACC (address 9001): class 8Eh, attribute 2, in 0.1 s.
    assert dnscan("set", 25, "0x8E", 1, 2, "u16:50") == (0, "", "")
    assert dnscan("get", 25, "0x8E", 1, 2, "--type", "u16") == (0, "50\n", "")
    status, out, err = dnscan("get", 25, 1, 1, 99)
    assert (status, out) == (1, "")
    assert err == "dnscan: error: MAC ID 25, get 1/1/99: CIP error 0x14 (attribute not supported), additional code 0xFF\n"
    status, _, err = dnscan("set", 25, "0x8E", 1, 2, "u16:65535")
    assert status == 1 and "CIP error" in err, err


def test_ucmm_opens_an_explicit_connection_that_gets_and_sets(start_dn, bus):
    """The manual's explicit server instances 10-14 over real SocketCAN: a scanner at MAC ID 1
    opens by UCMM (group 3 message 6, 781h) and gets the group 3 answer (759h), reads the vendor
    ID and the product name (fragmented) and sets ACC on the connection (641h, answered on 619h),
    then closes it. The other drive (63) answers none of it."""
    _, sock = start_dn([25, 63])
    assert bus.request("781#194B0031", 0x759).data.hex().upper() == "01CB00100A00"
    assert bus.request("641#190E010101", 0x619).data.hex().upper() == "018EF300"
    assert bus.request("641#190E010107", 0x619).data.hex().upper() == "81008E0641545633"
    assert bus.request("641#99C000", 0x619).data.hex().upper() == "81813132"
    bus.send("641#99C100")
    assert bus.request("641#19108E01023200", 0x619).data.hex().upper() == "0190"  # ACC 5.0 s
    assert bus.request("641#190E8E0102", 0x619).data.hex().upper() == "018E3200"
    assert ctl_state(sock, 25)["ns"] == "green"
    # The Open asked again is the same connection; Close ends it; then requests go unanswered.
    assert bus.request("781#194B0031", 0x759).data.hex().upper() == "01CB00100A00"
    assert bus.request("781#194C0A00", 0x759).data.hex().upper() == "01CC"
    bus.send("641#190E010101")
    bus.expect_none(0x619, 0.3)
    assert ctl_state(sock, 25)["ns"] == "flashing-green"
    assert ctl_state(sock, 63)["ns"] == "flashing-green"


def test_dnscan_opens_its_explicit_connection_by_ucmm(start_dn, dump):
    """dnscan --ucmm-connection: Open on the drive's UCMM (780h, the header naming MAC ID 25) and its
    answer (759h: the scanner's message ID 0, the drive's 0, instance 10), the Get over the
    connection (600h, answered on 619h in two fragments, each acknowledged on 600h), Close; no
    Allocate on the unconnected port (4CEh). A Set the same way; the connection is gone after."""
    _, sock = start_dn([25])
    mark = dump.mark()
    assert dnscan("--ucmm-connection", "get", 25, 1, 1, 7, "--type", "string") == (0, "ATV312\n", "")
    dump.expect(0x780, "194B0030", since=mark)
    dump.expect(0x759, "00CB00000A00")
    dump.expect(0x600, "590E010107")
    dump.expect(0x619, "C0008E0641545633")
    dump.expect(0x600, "D9C000")
    dump.expect(0x619, "C0813132")
    dump.expect(0x600, "D9C100")
    dump.expect(0x780, "194C0A00")
    dump.expect(0x759, "00CC")
    assert [f for f in dump.seen[mark:] if f.can_id in (0x4CE, 0x4CC)] == []
    mark = dump.mark()
    assert dnscan("--ucmm-connection", "set", 25, "0x8E", 1, 2, "u16:50") == (0, "", "")
    dump.expect(0x600, "59108E01023200", since=mark)
    dump.expect(0x619, "4090")
    assert dnscan("--ucmm-connection", "get", 25, "0x8E", 1, 2, "--type", "u16") == (0, "50\n", "")
    assert ctl_state(sock, 25)["ns"] == "flashing-green"  # closed: no connection left
    # SIGINT while the Open awaits its answer (no slave at MAC ID 40): nothing to close.
    proc = subprocess.Popen([DNSCAN, "-i", IFACE, "--no-check", "--timeout", "5000", "--ucmm-connection", "get",
                             "40", "1", "1", "1"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    dump.expect(0x780, "284B0030")
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=5)
    assert (proc.returncode, out, err) == (3, "", "dnscan: error: interrupted by a signal before the command finished\n")
    assert dnscan("--ucmm-connection", "poll", 25) == (
        EX_USAGE, "", "dnscan: error: --ucmm-connection: for get and set only, not poll\nTry 'dnscan --help'.\n")


def test_poll_21_71_runs_the_drive_to_1200_rpm(start_dn):
    _, sock = start_dn([25, 63])
    poller = Poller(25, "--assembly", "21/71", "--set", "NetCtrl=1", "--set", "NetRef=1", "--set", "Run_fwd=1",
                    "--set", "Speed_reference=1200", "--every", POLL_MS)
    try:
        line = poller.expect("At reference=1", timeout=10)
        assert line == ("MAC ID 25: Faulted=0 Warning=0 Running1=1 Running2=0 Ready=1 Ctrl from net=1 "
                        "Ref from net=1 At reference=1 Drive state=4 Speed actual=1200")
        state = wait_state(sock, 25, ns="green", supervisor="enabled", cia402="Operation enabled")
        assert state["speed_rpm"] == 1200
        # The other drive saw every frame and stayed as it was.
        other = ctl_state(sock, 63)
        assert (other["ns"], other["cia402"], other["speed_rpm"]) == ("flashing-green", "Switch on disabled", 0)
    finally:
        assert poller.stop() == 0


def test_transparent_assemblies_after_selecting_them_and_a_reset(start_dn, dump, bus, tmp_path):
    store = tmp_path / "dn.store"
    d, sock = start_dn([25], "--store", store)
    assert dnscan("set", 25, 5, 0, 100, "u16:100") == (0, "", "")
    assert dnscan("set", 25, 5, 0, 101, "u16:101") == (0, "", "")
    # Used after a restart: Identity Reset type 0 on the explicit connection, its response, then
    # the card checks its MAC ID again.
    bus.request("4CE#004B03010100", 0x4CB, "00CB00")
    mark = dump.mark()
    bus.request("4CC#0005010100", 0x4CB, "0085")
    dump.expect(*CHECK_25, timeout=1.0, since=mark)
    dump.expect(*CHECK_25, timeout=1.5)
    wait_state(sock, 25, timeout=ONLINE_TIMEOUT, ns="flashing-green")
    # The assemblies in use come from the slave (Connection instance 2's paths): 101 answers
    # 6041h (0x0640, Switch on disabled) and 6044h.
    assert dnscan("poll", 25, "--count", 1) == (0, "MAC ID 25: Status word=1600 Output speed=0\n", "")
    # 100 carries 6040h and 6042h as they are: Shutdown, Switch on (one poll each, then released:
    # the drive stands), Enable operation polled on, since a release while the drive runs would
    # be its CnF (test_release_while_running_is_cnf).
    for control_word in (6, 7):
        status, _, err = dnscan("poll", 25, "--assembly", "100/101", "--set", f"Control_word={control_word}",
                                  "--set", "Reference_speed=300", "--count", 1)
        assert (status, err) == (0, ""), err
    wait_state(sock, 25, cia402="Switched on", fault=None)
    poller = Poller(25, "--assembly", "100/101", "--set", "Control_word=15", "--set", "Reference_speed=300",
                    "--every", POLL_MS)
    wait_state(sock, 25, timeout=5.0, cia402="Operation enabled", speed_rpm=300)
    poller.proc.kill()
    poller.proc.wait(timeout=5)
    # The selection and Quick Connect are in the store: the next start reads them.
    assert d.stop() == 0
    d2, _ = start_dn([25], "--store", store)
    assert f"store {store}: MAC ID 25: consumed assembly 100, produced assembly 101, Quick Connect off" in d2.log()
    assert dnscan("get", 25, 5, 0, 100, "--type", "u16") == (0, "100\n", "")
    assert dnscan("get", 25, 5, 0, 101, "--type", "u16") == (0, "101\n", "")


def test_io_timeout_is_cnf_and_the_scanner_resets_it(start_dn):
    _, sock = start_dn([25])
    poller = Poller(25, "--assembly", "21/71", "--set", "NetCtrl=1", "--set", "NetRef=1", "--set", "Run_fwd=1",
                    "--set", "Speed_reference=600", "--every", POLL_MS)
    poller.expect("Running1=1", timeout=5)
    wait_state(sock, 25, ns="green", cia402="Operation enabled")
    # The scanner dies: no poll, no release. The polled connection times out (4 x its expected
    # packet rate): the drive's communication loss CnF, NS flashing red.
    poller.proc.kill()
    poller.proc.wait(timeout=5)
    state = wait_state(sock, 25, timeout=2.0, fault="CnF", ns="flashing-red")
    assert state["cia402"] in ("Fault", "Fault reaction active")
    # The scanner comes back: releases the timed-out connections, polls once with Fault reset.
    assert dnscan("release", 25) == (0, "MAC ID 25: released 0x33\n", "")
    wait_state(sock, 25, cia402="Fault", ns="flashing-green")
    status, _, err = dnscan("poll", 25, "--assembly", "21/71", "--set", "Fault_reset=1", "--count", 1)
    assert (status, err) == (0, ""), err
    state = wait_state(sock, 25, fault=None)
    assert state["cia402"] != "Fault"


def test_release_while_running_is_cnf(start_dn):
    _, sock = start_dn([25])
    poller = Poller(25, "--assembly", "21/71", "--set", "NetCtrl=1", "--set", "NetRef=1", "--set", "Run_fwd=1",
                    "--set", "Speed_reference=600", "--every", POLL_MS)
    try:
        poller.expect("Running1=1", timeout=5)
        wait_state(sock, 25, ns="green", supervisor="enabled", fault=None)
        # Another scanner process of the same MAC ID releases the connections while the drive
        # runs: its commands stop, the same CnF as a timeout, at once (COL 1: freewheel).
        assert dnscan("release", 25) == (0, "MAC ID 25: released 0x33\n", "")
        state = wait_state(sock, 25, fault="CnF", supervisor="faulted", ns="flashing-green")
        assert (state["cia402"], state["frames"]["timeouts"]) == ("Fault", 0)
    finally:
        # The poller finds its connection lost and allocates it again; SIGINT releases it.
        poller.stop()
    # The fault reset by the scanner; its release after it leaves the standing drive as it is.
    status, _, err = dnscan("poll", 25, "--assembly", "21/71", "--set", "Fault_reset=1", "--count", 1)
    assert (status, err) == (0, ""), err
    wait_state(sock, 25, fault=None, supervisor="ready")


def test_a_killed_drive_checks_its_mac_id_again_and_is_allocated_again(start_dn, dump):
    d, _ = start_dn([25])
    assert dnscan("allocate", 25, "0x03")[0] == 0
    assert d.stop(signal.SIGKILL) == -signal.SIGKILL
    # Gone: nobody answers the scanner.
    status, _, err = dnscan("--timeout", 300, "get", 25, 1, 1, 1)
    assert status == 2, err
    start_dn([25])
    # A fresh card: nothing allocated, the scanner allocates again.
    assert dnscan("allocate", 25, "0x03") == (0, "MAC ID 25: allocated 0x03\n", "")
    assert dnscan("release", 25) == (0, "MAC ID 25: released 0x33\n", "")


def test_scanner_on_a_mac_id_in_use_exits_5(start_dn):
    """The scanner's own duplicate MAC ID check (no --no-check) answered by the drive on its MAC
    ID: exit 5, which means nothing else in any of the four programs."""
    start_dn([25])
    p = subprocess.run([DNSCAN, "-i", IFACE, "--mac-id", "25", "get", "63", "1", "1", "1"], capture_output=True,
                       text=True, timeout=30)
    assert (p.returncode, p.stdout, p.stderr) == (
        5, "", "dnscan: error: MAC ID 25 is in use on vcan0: give the scanner another with --mac-id N\n")


@pytest.mark.parametrize("args, message", [
    (["--devicenet", "--node-id", "4"],
     "--node-id 4: --devicenet makes vcan0 a DeviceNet bus, whose drives have MAC IDs: give --mac-id 0..63 "
     "instead (one interface is either CANopen or DeviceNet: run one atv312d per bus)"),
    (["--node-id", "4", "--mac-id", "25"],
     "--mac-id 25: MAC IDs are DeviceNet's and this interface is CANopen: add --devicenet to put the drives on "
     "DeviceNet"),
    (["--devicenet", "--mac-id", "25", "--model", "atv58"],
     "--model atv58: the atv58 has no DeviceNet card here: on DeviceNet give --model atv312, or leave --model out"),
])
def test_mixing_canopen_and_devicenet_is_refused(args, message, dump):
    p = subprocess.run([daemon_path(), IFACE, *args], capture_output=True, text=True, timeout=10)
    assert (p.returncode, p.stdout, p.stderr) == (EX_USAGE, "", f"atv312d: error: {message}\nTry 'atv312d --help'.\n")
    dump.expect_none(0x4CF, 0.2)


def send_bus_off():
    """A bus-off error frame, as a controller driver reports it (linux/can/error.h CAN_ERR_BUSOFF)."""
    subprocess.run(["cansend", IFACE, "20000040#0000000000000000"], check=True, timeout=5)


def test_bus_off_goes_to_the_card_with_and_without_boi(start_dn, dump):
    _, sock = start_dn([25, 63])
    # MAC ID 25 with BOI (DeviceNet attribute 3) set starts over: a new check, online again.
    assert dnscan("set", 25, 3, 1, 3, "u8:1") == (0, "", "")
    mark = dump.mark()
    send_bus_off()
    dump.expect(*CHECK_25, timeout=1.0, since=mark)
    dump.expect(*CHECK_25, timeout=1.5)
    wait_state(sock, 25, timeout=ONLINE_TIMEOUT, ns="flashing-green")
    assert dnscan("get", 25, 3, 1, 4, "--type", "u8") == (0, "1\n", "")  # the bus-off counter
    # MAC ID 63, without BOI, stays off the bus: NS solid red, no answer.
    state = wait_state(sock, 63, ns="red")
    assert state["ms"] == "green"
    assert dnscan("--timeout", 300, "get", 63, 1, 1, 1)[0] == 2


def run_at_600_rpm(every_ms):
    """dnscan polling MAC ID 25 Run forward at 600 rpm, every_ms apart (its expected packet rate,
    a watchdog of four times that); returns the poller once the drive runs on those commands."""
    poller = Poller(25, "--assembly", "21/71", "--set", "NetCtrl=1", "--set", "NetRef=1", "--set", "Run_fwd=1",
                    "--set", "Speed_reference=600", "--every", every_ms)
    poller.expect("Running1=1", timeout=5)
    return poller


def test_bus_off_while_running_is_cnf(start_dn, dump):
    """Bus off takes every connection of the card (no BOI: it stays off the bus); the drive that ran
    on the polls takes the communication loss at once, not at a watchdog (docs/decisions.md,
    D-DEVICENET-CONNECTION-END)."""
    _, sock = start_dn([25])
    poller = run_at_600_rpm(1000)  # a watchdog of 4 s: not what ends the connection here
    try:
        wait_state(sock, 25, ns="green", supervisor="enabled", fault=None)
        send_bus_off()
        state = wait_state(sock, 25, timeout=1.0, fault="CnF", ns="red")
        assert (state["cia402"], state["frames"]["timeouts"]) == ("Fault", 0)
    finally:
        poller.proc.kill()
        poller.proc.wait(timeout=5)


def test_interface_back_while_running_is_cnf(start_dn, bus):
    """The interface down and up again within the poll's watchdog: the card goes on the bus again
    with a new check and no connection, and the drive that ran on them takes CnF. (candump ends
    with its interface; the test's own socket stays.)"""
    _, sock = start_dn([25])
    poller = run_at_600_rpm(1000)
    try:
        wait_state(sock, 25, ns="green", supervisor="enabled", fault=None)
        mark = bus.mark()
        subprocess.run(["ip", "link", "set", IFACE, "down"], check=True, timeout=5)
        subprocess.run(["ip", "link", "set", IFACE, "up"], check=True, timeout=5)
        bus.expect(*CHECK_25, timeout=2.0, since=mark)
        state = wait_state(sock, 25, timeout=1.0, fault="CnF")
        assert (state["cia402"], state["frames"]["timeouts"]) == ("Fault", 0)
    finally:
        poller.proc.kill()
        poller.proc.wait(timeout=5)


def ctl(sock, *words):
    done = subprocess.run([daemon_path(), "ctl", str(sock), *map(str, words)], capture_output=True, text=True,
                          timeout=10)
    return done.returncode, (done.stdout + done.stderr).strip()


def test_control_surface_faults_and_keys_by_mac_id(start_dn):
    _, sock = start_dn([25])
    # What the DeviceNet bus shows of it: the Control supervisor and the Identity, no EMCY.
    assert ctl(sock, "fault", 25, "OHF") == (
        0, "ok node 25: OHF (drive overheating), supervisor faulted, Identity major recoverable fault")
    state = wait_state(sock, 25, fault="OHF", cia402="Fault", supervisor="faulted")
    assert (state["display"], state["ms"], state["ns"]) == ("OHF", "green", "flashing-green")
    # The scanner sees it: Faulted in assembly 71, refused fault reset while the cause is present.
    assert dnscan("poll", 25, "--assembly", "21/71", "--count", 1) == (
        0, "MAC ID 25: Faulted=1 Warning=0 Running1=0 Running2=0 Ready=0 Ctrl from net=1 Ref from net=1 "
        "At reference=1 Drive state=7 Speed actual=0\n", "")
    assert ctl(sock, "clear", 25, "OHF") == (0, "ok node 25: cause of OHF removed")
    assert dnscan("poll", 25, "--assembly", "21/71", "--set", "Fault_reset=1", "--count", 1)[0] == 0
    # The card's Stop after the reset is a Shutdown: Ready to switch on.
    wait_state(sock, 25, fault=None, supervisor="ready", cia402="Ready to switch on")
    # COF, the card not working (the manual's "Communication fault management"): injected as any
    # fault, seen by the scanner as Faulted; the reset is taken once the card works again.
    status, reply = ctl(sock, "fault", 25, "COF")
    assert (status, reply.startswith("ok node 25: COF (communication card fault")) == (0, True), reply
    wait_state(sock, 25, fault="COF", cia402="Fault", supervisor="faulted")
    assert dnscan("poll", 25, "--assembly", "21/71", "--count", 1)[1].startswith("MAC ID 25: Faulted=1")
    assert ctl(sock, "clear", 25, "COF") == (0, "ok node 25: cause of COF removed")
    assert dnscan("poll", 25, "--assembly", "21/71", "--set", "Fault_reset=1", "--count", 1)[0] == 0
    wait_state(sock, 25, fault=None, supervisor="ready")
    assert ctl(sock, "load", 25, 50) == (0, "ok node 25: load 50 %")
    assert ctl(sock, "fault", 4, "OHF") == (1, "atv312d: error: node 4 is not present: this daemon runs MAC ID 25")
