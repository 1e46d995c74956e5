# SPDX-License-Identifier: Apache-2.0
"""The control surface on real SocketCAN: `atv312d --control PATH` and `atv312d ctl PATH COMMAND`,
each command with the frames it causes on the bus (fault -> EMCY, 603Fh, status word; the fault
reset once the cause is gone -> the EMCY error reset), and every refusal with its one-line error
and no frame."""

import json
import subprocess

import pytest

from conftest import NMT_START, REPLY_TIMEOUT, Frame, daemon_path

NODE = 4
EXIT_REFUSED = 1  # the daemon's "error: ..." reply, which ctl prints as its own error on stderr
EX_UNAVAILABLE = 69


def ctl(sock, *words):
    """Runs `atv312d ctl SOCK WORDS...`; returns (exit status, reply line or error line)."""
    done = subprocess.run([daemon_path(), "ctl", str(sock), *map(str, words)], capture_output=True, text=True, timeout=10)
    return done.returncode, (done.stdout + done.stderr).strip()


def state(sock, node=NODE):
    status, reply = ctl(sock, "--json", "state", node)
    assert status == 0, reply
    return json.loads(reply)["nodes"][0]


@pytest.fixture
def control(bus, start_daemon, tmp_path):
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", NODE, "--control", sock)
    return sock


def test_fault_then_reset_once_the_cause_is_gone(bus, control):
    status, reply = ctl(control, "fault", NODE, "OHF")
    assert status == 0 and reply.startswith("ok node 4: OHF"), reply
    bus.expect(0x84, "1042010000000000")
    assert bus.sdo_read(NODE, 0x603F, 0) == 0x4210
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0608
    assert bus.sdo_read(NODE, 0x1001, 0) == 0x01  # "=1 (error)"
    assert bus.sdo_read(NODE, 0x1003, 1) == 0x4210
    s = state(control)
    assert (s["cia402"], s["display"], s["fault"], s["statusword"]) == ("Fault", "OHF", "OHF", 0x0608)
    # The fault reset is refused while the cause is present: no frame, still Fault.
    bus.sdo_write(NODE, 0x6040, 0, 0x0080, 2)
    bus.expect_none(0x84, 0.3)
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0608
    status, reply = ctl(control, "clear", NODE, "OHF")
    assert (status, reply) == (0, "ok node 4: cause of OHF removed")
    bus.expect_none(0x84, 0.3)
    bus.sdo_write(NODE, 0x6040, 0, 0x0000, 2)
    # The error reset goes out before the SDO answer of the write that caused it.
    mark = bus.mark()
    bus.sdo_write(NODE, 0x6040, 0, 0x0080, 2)
    bus.expect(0x84, "0000000000000000", since=mark)
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0640
    assert bus.sdo_read(NODE, 0x603F, 0) == 0
    s = state(control)
    assert (s["cia402"], s["display"], s["fault"]) == ("Switch on disabled", "nSt", None)


def test_fault_stops_the_running_motor_on_tpdo1(bus, control):
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    bus.nmt(NMT_START, NODE)
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    bus.expect(0x184, "2702", timeout=REPLY_TIMEOUT)
    s = state(control)
    assert (s["nmt"], s["run_led"], s["cia402"]) == ("Operational", "on", "Operation enabled")
    assert ctl(control, "fault", NODE, "OCF")[0] == 0
    bus.expect(0x84, "1023010000000000")
    bus.expect(0x184, "0806")
    s = state(control)
    assert (s["speed_rpm"], s["current_a"], s["display"]) == (0, 0, "OCF")
    # OCF needs a power cycle: the fault reset is refused even with the cause gone.
    assert ctl(control, "clear", NODE, "all") == (0, "ok node 4: causes removed: OCF")
    bus.sdo_write(NODE, 0x6040, 0, 0x0080, 2)
    bus.expect_none(0x84, 0.3)
    assert state(control)["cia402"] == "Fault"


def test_fault_reaction_ramps_down_in_tpdos_before_the_fault(bus, control):
    """COL = 2 (ramp stop): COF injected into the running drive stops the motor on the DEC ramp
    (2.0 s here) in Fault reaction active: TPDO6 (ETAD, RFRD) shows ETAD 0x020F with the speed
    falling frame after frame, then ETAD 0x0608 at speed 0 (Fault). The speed is whole rpm of a
    motor modelled in milli-rpm: when a 10 ms step leaves it under 1 rpm, the last reaction frame
    shows 0 rpm while the motor still turns."""
    bus.sdo_write(NODE, 0x2022, 2, 2, 2)  # COL: ramp stop
    bus.sdo_write(NODE, 0x203C, 3, 20, 2)  # DEC 2.0 s
    bus.sdo_write(NODE, 0x1805, 1, 0x284, 4)  # TPDO6 valid: ETAD + RFRD
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    bus.nmt(NMT_START, NODE)
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    bus.expect(0x284, "2706DC05", timeout=5.0)
    mark = bus.mark()
    status, reply = ctl(control, "fault", NODE, "COF")
    assert status == 0 and reply.startswith("ok node 4: COF"), reply
    s = state(control)
    assert (s["cia402"], s["display"], s["statusword"]) == ("Fault reaction active", "COF", 0x020F)
    reaction = []
    while True:
        frame = bus.expect(0x284, timeout=5.0)
        status, speed = int.from_bytes(frame.data[0:2], "little"), int.from_bytes(frame.data[2:4], "little", signed=True)
        if (status, speed) == (0x0627, 1500) and not reaction:
            continue  # sent before the fault
        if status != 0x020F:
            break
        reaction.append(speed)
    assert (status, speed) == (0x0608, 0), frame
    bus.expect(0x84, "3081010000000000", since=mark)
    assert len(reaction) >= 5, reaction
    assert all(a > b for a, b in zip(reaction, reaction[1:])), reaction
    assert 1500 >= reaction[0] and reaction[-1] >= 0, reaction
    assert state(control)["cia402"] == "Fault"


def test_mains_undervoltage_ends_by_itself(bus, control):
    assert ctl(control, "mains", NODE, "undervoltage")[0] == 0
    bus.expect(0x84, "2031010000000000")
    assert state(control)["display"] == "USF"
    assert ctl(control, "mains", NODE, "normal") == (0, "ok node 4: mains normal")
    bus.expect(0x84, "0000000000000000")
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0640
    s = state(control)
    assert (s["display"], s["run_led"], s["err_led"]) == ("nSt", "blinking", "off")


def test_state_of_every_node_in_text(bus, control):
    status, reply = ctl(control, "state")
    assert status == 0
    assert reply == (
        "ok node 4: nmt Pre-operational, cia402 Switch on disabled, statusword 0640, speed 0 rpm, "
        "current 0.0 A, torque 0 %, display nSt, RUN blinking, ERR off, fault none, "
        "frames received 0, sent 1, dropped 0, SDO requests 0, SDO aborts 0, EMCY 0"
    )


def test_frame_counters_of_each_of_two_drives(bus, start_daemon, tmp_path):
    """N SDO requests to node 5 of two drives, one of them refused, and one fault: node 5 counts
    exactly the N frames routed to it, its boot-up, N answers and one EMCY sent, N SDO requests, one
    abort, one EMCY; node 4 sees none of it (node 5's COB-IDs are not routed to it), then the NMT
    broadcast reaches both."""
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", "4-5", "--control", sock)
    n = 7
    for _ in range(n - 1):
        assert bus.sdo_read(5, 0x1000, 0) == 0x00010192
    assert bus.sdo_abort_code(5, "4034120000000000") == 0x06020000  # 1234h does not exist
    assert ctl(sock, "fault", 5, "OHF")[0] == 0
    bus.expect(0x85, "1042010000000000")

    def frames():
        status, reply = ctl(sock, "--json", "state")
        assert status == 0, reply
        return {node["node"]: node["frames"] for node in json.loads(reply)["nodes"]}

    counts = frames()
    assert counts[5] == {"received": n, "sent": 1 + n + 1, "dropped": 0, "sdo_requests": n, "sdo_aborts": 1, "emcy": 1}
    assert counts[4] == {"received": 0, "sent": 1, "dropped": 0, "sdo_requests": 0, "sdo_aborts": 0, "emcy": 0}
    bus.nmt(0x80, 0)  # enter pre-operational, all nodes: no answer
    bus.expect_none(0x704, 0.2)
    counts = frames()
    assert (counts[4]["received"], counts[5]["received"]) == (1, n + 1)


@pytest.mark.parametrize(
    "words, error",
    [
        (["fault", 4, "XYZ"], "error: unknown fault 'XYZ': node 4 knows COF, ILF, SLF, OCF, SCF, OSF, USF, PHF, ObF, OPF, OHF, OtF, OLF, SOF, CrF, EEF, InF, CFF, CFI, LFF, EPF"),
        (["fault", 9, "OHF"], "error: node 9 is not present: this daemon runs node-id 4"),
        (["fault", 4], "error: usage: fault NODE CODE (e.g. fault 4 OHF)"),
        (["clear", 4, "OHF"], "error: node 4: no cause of OHF is present"),
        (["mains", 4, "low"], "error: usage: mains NODE undervoltage|normal"),
        (["state", "x"], "error: node x is not present: this daemon runs node-id 4"),
        (["reboot", 4], "error: unknown command 'reboot': the commands are fault, clear, mains, stop-key, run-key, local, load, input, analog, pot, marker, state"),
        (["run-key", 4], "error: node 4 is under network control: the RUN key works under local control (local 4 on, or a command channel other than CANopen)"),
        (["local", 4, "off"], "error: node 4 is under network control already"),
        (["load", 4, "151"], "error: load 151: give a percentage of nominal torque, 0..150"),
        (["load", 4, "-1"], "error: load -1: give a percentage of nominal torque, 0..150"),
    ],
)
def test_refused_commands_say_why_and_send_nothing(bus, control, words, error):
    assert ctl(control, *words) == (EXIT_REFUSED, "atv312d: " + error)
    status, reply = ctl(control, "--json", *words)
    assert (status, json.loads(reply)) == (EXIT_REFUSED, {"ok": False, "error": error[len("error: "):]})
    bus.expect_none(0x84, 0.2)
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0640


def test_fault_injected_twice_is_refused(bus, control):
    assert ctl(control, "fault", NODE, "ohf")[0] == 0
    bus.expect(0x84, "1042010000000000")
    assert ctl(control, "fault", NODE, "OHF") == (EXIT_REFUSED, "atv312d: error: node 4: the cause of OHF is present already")
    bus.expect_none(0x84, 0.2)


def test_no_daemon_is_a_clear_error(tmp_path):
    status, reply = ctl(tmp_path / "none.sock", "state")
    assert status == EX_UNAVAILABLE
    assert reply.startswith("atv312d: error: ctl: cannot connect") and "--control" in reply


def run_fast(bus):
    """Operational, ACC = DEC = 0.1 s, running at 1500 rpm: TPDO1 says 0x0627."""
    bus.sdo_write(NODE, 0x203C, 2, 1, 2)
    bus.sdo_write(NODE, 0x203C, 3, 1, 2)
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    bus.nmt(NMT_START, NODE)
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    bus.expect(0x184, "2706")


def test_stop_key_under_network_control(bus, control):
    run_fast(bus)
    assert ctl(control, "stop-key", NODE) == (0, "ok node 4: STOP key (freewheel stop, status word bit 14)")
    # Switch on disabled, remote, at target 0 (freewheel), bit 14.
    bus.expect(0x184, "4046")
    s = state(control)
    assert (s["cia402"], s["speed_rpm"], s["display"]) == ("Switch on disabled", 0, "nSt")
    # The master's next run sequence clears bit 14.
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.expect(0x184, "2106")


def test_local_control_and_the_keypad(bus, control):
    run_fast(bus)
    assert ctl(control, "local", NODE, "on") == (0, "ok node 4: local control (status word bit 9 = 0)")
    bus.expect(0x184, "4004")
    # The network's run command is ignored.
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x0440
    assert ctl(control, "run-key", NODE) == (0, "ok node 4: RUN key")
    bus.expect(0x184, "2704")
    assert ctl(control, "stop-key", NODE)[0] == 0
    bus.expect(0x184, "4044")
    assert ctl(control, "local", NODE, "off") == (0, "ok node 4: network control (status word bit 9 = 1)")
    bus.expect(0x184, "4046")


def test_load_raises_torque_and_current(bus, control):
    run_fast(bus)
    assert (bus.sdo_read(NODE, 0x2002, 9), bus.sdo_read(NODE, 0x2002, 4)) == (20, 17)
    assert ctl(control, "load", NODE, 50) == (0, "ok node 4: load 50 %")
    assert (bus.sdo_read(NODE, 0x2002, 9), bus.sdo_read(NODE, 0x2002, 4)) == (70, 31)
    s = state(control)
    assert (s["torque_percent"], s["current_a"], s["speed_rpm"]) == (70, 3.1, 1500)


def test_analog_input_and_terminal_run(bus, control):
    """CHCF = SIM, Fr1 = AI2: reference and command from the terminals. `analog 4 AI2 5` and
    `input 4 LI1 on` run the drive to 750 rpm (TPDO6: ETAD 0x0427, RFRD 750); -5 V reverses it
    (0x8427, -750); LI1 off stops it to Switch on disabled (0x0440)."""
    bus.sdo_write(NODE, 0x2036, 0x0E, 2, 2)  # Fr1 = AI2
    bus.sdo_write(NODE, 0x1805, 1, 0x284, 4)  # TPDO6 valid: ETAD + RFRD
    bus.nmt(NMT_START, NODE)
    bus.expect(0x284, "40040000", timeout=REPLY_TIMEOUT)
    assert ctl(control, "analog", NODE, "AI2", 5) == (0, "ok node 4: AI2 5.000 V")
    assert ctl(control, "input", NODE, "LI1", "on") == (0, "ok node 4: LI1 on")
    bus.expect(0x284, "2704EE02", timeout=5.0)
    assert ctl(control, "analog", NODE, "AI2", -5) == (0, "ok node 4: AI2 -5.000 V")
    bus.expect(0x284, "278412FD", timeout=5.0)
    assert ctl(control, "input", NODE, "LI1", "off") == (0, "ok node 4: LI1 off")
    bus.expect(0x284, "40040000", timeout=5.0)
    assert ctl(control, "pot", NODE, 50) == (EXIT_REFUSED, "atv312d: error: node 4 has no reference potentiometer")


def test_atv31_potentiometer_and_stop_reset_key(bus, start_daemon, tmp_path):
    """The ATV31's potentiometer (Fr1 = 7) gives the reference: 50 % is 750 rpm (TPDO6); its
    STOP/RESET key resets OHF once the cause is gone (EMCY 0000, status word 0x4640)."""
    sock = tmp_path / "atv31.sock"
    start_daemon(bus, "--node-id", NODE, "--model", "atv31", "--control", sock)
    bus.sdo_write(NODE, 0x2036, 2, 2, 2)  # CHCF = SEP: the network commands
    bus.sdo_write(NODE, 0x2036, 0x0E, 7, 2)  # Fr1 = AIP
    bus.sdo_write(NODE, 0x1805, 1, 0x284, 4)  # TPDO6 valid: ETAD + RFRD
    bus.nmt(NMT_START, NODE)
    assert ctl(sock, "pot", NODE, 50) == (0, "ok node 4: AIP 50.0 %")
    bus.sdo_write(NODE, 0x6040, 0, 0x0006, 2)
    bus.sdo_write(NODE, 0x6040, 0, 0x000F, 2)
    bus.expect(0x284, "2706EE02", timeout=5.0)
    assert ctl(sock, "fault", NODE, "OHF")[0] == 0
    bus.expect(0x84, "1042010000000000")
    assert ctl(sock, "clear", NODE, "OHF")[0] == 0
    mark = bus.mark()
    assert ctl(sock, "stop-key", NODE) == (0, "ok node 4: STOP/RESET key: fault OHF reset (status word bit 14)")
    bus.expect(0x84, "0000000000000000", since=mark)
    assert bus.sdo_read(NODE, 0x6041, 0) == 0x4640


def test_state_of_a_full_bench(bus, start_daemon, tmp_path):
    """127 drives: `state` answers every one on one line, whole (text and JSON)."""
    sock = tmp_path / "bench.sock"
    start_daemon(bus, "--node-id", "1-127", "--control", sock)
    status, reply = ctl(sock, "--json", "state")
    assert status == 0
    nodes = json.loads(reply)["nodes"]
    assert [n["node"] for n in nodes] == list(range(1, 128))
    assert {n["cia402"] for n in nodes} == {"Switch on disabled"}
    status, reply = ctl(sock, "state")
    assert status == 0 and reply.count("; node ") == 126 and reply.endswith("node 127: nmt Pre-operational, cia402 Switch on disabled, statusword 0640, speed 0 rpm, current 0.0 A, torque 0 %, display nSt, RUN blinking, ERR off, fault none, frames received 0, sent 1, dropped 0, SDO requests 0, SDO aborts 0, EMCY 0")
    assert len(reply) < 65536


def test_state_and_log_tell_a_heartbeat_loss_from_a_guarding_loss(bus, start_daemon, tmp_path):
    sock = tmp_path / "atv312d.sock"
    d = start_daemon(bus, "--node-id", "4-5", "--control", sock)
    # Node 4 consumes node 1's heartbeat (1016h:01, 100 ms); node 5 is life guarded (100 ms x 2).
    bus.sdo_write(4, 0x1016, 1, (1 << 16) | 100, 4)
    bus.sdo_write(5, 0x100C, 0, 100, 2)
    bus.sdo_write(5, 0x100D, 0, 2, 1)
    bus.send(Frame(0x701, b"\x05"))
    bus.request(Frame(0x705, b"", rtr=True), 0x705)
    bus.expect(0x084, "3081010000000000", timeout=1.0)
    bus.expect(0x085, "3081010000000000", timeout=1.0)
    status, reply = ctl(sock, "state")
    assert status == 0, reply
    assert ", ERR double flash, fault COF, comm-loss heartbeat node 1, frames " in reply, reply
    assert ", ERR double flash, fault COF, comm-loss guarding, frames " in reply, reply
    assert state(sock, 4)["comm_loss"] == {"by": "heartbeat", "node": 1}
    assert state(sock, 5)["comm_loss"] == {"by": "guarding"}
    log = d.log()
    assert "node 4: communication loss (EMCY 8130, error register 01): heartbeat of node 1 timed out" in log, log
    assert "node 5: communication loss (EMCY 8130, error register 01): life guarding timed out" in log, log
    bus.sdo_write(4, 0x6040, 0, 0x0080, 2)  # fault reset: the loss is over
    assert state(sock, 4)["comm_loss"] is None


def test_canopen_off_drive_is_present_and_silent(bus, start_daemon, tmp_path):
    """AdCO = 0, "disables the CANopen communications" (the ATV312 manual's COM- menu;
    D-ADCO-BDCO): node 5 with --canopen-off beside node 4. Node 4 boots and answers; node 5 sends
    no boot-up, nothing after a broadcast NMT start, no SDO answer, while the daemon shows it and
    runs it from its keypad (local control, the RUN key)."""
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", 5, "--canopen-off", "--node-id", NODE, "--control", sock,
                 boot_ids=[NODE])
    bus.nmt(NMT_START, 0)
    bus.expect(0x180 + NODE, "4006")
    bus.send(Frame(0x605, bytes.fromhex("4000100000000000")))
    assert bus.sdo_read(NODE, 0x201E, 0x34) == NODE
    for can_id in (0x705, 0x185, 0x585, 0x85):
        bus.expect_none(can_id, 0.1)
    s = state(sock, 5)
    assert (s["nmt"], s["cia402"]) == ("Initialising", "Switch on disabled"), s
    assert ctl(sock, "local", 5, "on")[0] == 0
    assert ctl(sock, "run-key", 5)[0] == 0
    assert state(sock, 5)["cia402"] == "Operation enabled"
    assert ctl(sock, "fault", 5, "OHF")[0] == 0
    assert state(sock, 5)["cia402"] == "Fault"
    for can_id in (0x705, 0x185, 0x285, 0x85):
        bus.expect_none(can_id, 0.1)
