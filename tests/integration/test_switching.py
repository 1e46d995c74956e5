# SPDX-License-Identifier: Apache-2.0
"""The ATV312's switching on the bus (docs/atv312.md, "Access level, switching sources, ramp
switching"): the DeviceNet manual's configuration CCS = C212, rFC = C213 set by SDO, then CMD bits
12 and 13 seen in TPDO1 (status word) and TPDO6 (status word, speed); a logic input set by the
control surface switching the reference and the command; rPS = Cd15 switching to AC2."""

import re
import subprocess

from conftest import NMT_START, Frame, daemon_path

NODE = 4
LAC, CHCF, RFC, CCS = (0x2036, 1), (0x2036, 2), (0x2036, 0x0C), (0x2036, 0x16)
RPS, AC2 = (0x203C, 0x0B), (0x203C, 0x0D)
SEPARATE, C212, C213, CD15, LI3 = 2, 212, 213, 315, 103
ABORT_INCOMPATIBLE = 0x06040043


def write(bus, param, value):
    bus.sdo_write(NODE, param[0], param[1], value, 2)


def write_abort(bus, param, value):
    index, sub = param
    request = bytes([0x2B, index & 0xFF, index >> 8, sub]) + value.to_bytes(4, "little")
    return bus.sdo_abort_code(NODE, request)


def command(bus, word):
    bus.send(Frame(0x200 + NODE, word.to_bytes(2, "little")))


def enable_tpdo6(bus):
    """TPDO6 (6041h, 6044h) valid, asynchronous, no event timer: a frame on each change."""
    bus.sdo_write(NODE, 0x1805, 5, 0, 2)
    bus.sdo_write(NODE, 0x1805, 1, 0x280 + NODE, 4)


def tpdo6(status, rpm):
    return status.to_bytes(2, "little") + rpm.to_bytes(2, "little", signed=True)


def test_c213_switches_the_reference_and_c212_the_command(bus, drive):
    write(bus, CHCF, SEPARATE)
    write(bus, CCS, C212)
    write(bus, RFC, C213)
    bus.sdo_write(NODE, 0x203C, 2, 5, 2)  # ACC 0.5 s
    bus.sdo_write(NODE, 0x203C, 3, 5, 2)  # DEC 0.5 s
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    enable_tpdo6(bus)
    bus.nmt(NMT_START, NODE)
    bus.expect(0x280 + NODE, tpdo6(0x0640, 0))
    command(bus, 0x0006)
    command(bus, 0x000F)
    bus.expect(0x280 + NODE, tpdo6(0x0627, 1500), timeout=3.0)
    # Bit 13 (by default the DC injection stop): the reference from Fr2 = AI2, none in the
    # emulation, so LSP = 0 on the DEC ramp; the drive stays in Operation enabled, remote.
    command(bus, 0x200F)
    bus.expect(0x280 + NODE, tpdo6(0x0627, 0), timeout=3.0)
    # Bit 12 (by default the Stt stop): the command to Cd2 = terminals, bit 9 clear, a freewheel
    # stop to Switch on disabled.
    command(bus, 0x300F)
    bus.expect(0x180 + NODE, "4004")
    # Bit 12 back to 0: the network commands again, from Switch on disabled.
    command(bus, 0x000F)
    bus.expect(0x180 + NODE, "4006")
    command(bus, 0x0006)
    bus.expect(0x180 + NODE, "2106")


def test_logic_input_from_the_control_surface(bus, start_daemon, tmp_path):
    sock = tmp_path / "atv312d.sock"
    start_daemon(bus, "--node-id", NODE, "--control", sock)
    write(bus, RFC, LI3)  # CHCF = SIM: "Input LI3 switches the target (1 <-> 2) and the command"
    bus.sdo_write(NODE, 0x1800, 5, 0, 2)  # TPDO1 on changes only
    bus.nmt(NMT_START, NODE)
    bus.expect(0x180 + NODE, "4006")

    def ctl(*words):
        done = subprocess.run([daemon_path(), "ctl", str(sock), *map(str, words)], capture_output=True, text=True, timeout=10)
        return done.returncode, (done.stdout + done.stderr).strip()

    assert ctl("input", NODE, "LI3", "on") == (0, "ok node 4: LI3 on")
    bus.expect(0x180 + NODE, "4004")
    status, reply = ctl("state", NODE)
    assert status == 0 and re.search(r"fault none, frames received \d+, sent \d+, dropped 0, SDO requests \d+, "
                                     r"SDO aborts \d+, EMCY \d+, inputs LI3$", reply), reply
    assert ctl("input", NODE, "LI3", "off") == (0, "ok node 4: LI3 off")
    bus.expect(0x180 + NODE, "4006")
    # Refused by the daemon: atv312d ctl's error, exit 1.
    assert ctl("input", NODE, "LI4", "on") == (1, "atv312d: error: node 4 has no input LI4: its inputs are LI1..LI3")
    assert ctl("input", NODE, "AI2", "on") == (1, "atv312d: error: node 4 has no input AI2: its inputs are LI1..LI3")
    assert ctl("input", NODE, "LI3") == (1, "atv312d: error: usage: input NODE LIn|DIn on|off (e.g. input 4 LI3 on)")
    bus.expect_none(0x180 + NODE, 0.05)


def test_rps_cd15_under_l3_and_refused_under_l1(bus, drive):
    write(bus, LAC, 1)
    assert write_abort(bus, RPS, CD15) == ABORT_INCOMPATIBLE
    write(bus, LAC, 3)
    write(bus, RPS, CD15)
    assert write_abort(bus, LAC, 1) == ABORT_INCOMPATIBLE
    write(bus, AC2, 1)  # 0.1 s instead of ACC's 3.0 s
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    enable_tpdo6(bus)
    bus.nmt(NMT_START, NODE)
    bus.expect(0x280 + NODE, tpdo6(0x0640, 0))
    command(bus, 0x0006)
    bus.expect(0x280 + NODE, tpdo6(0x0621, 0))
    command(bus, 0x800F)
    start = bus.expect(0x280 + NODE)
    # AC2: at speed 0.1 s after the run command (with ACC it would take 3.0 s).
    end = bus.expect(0x280 + NODE, tpdo6(0x0627, 1500), timeout=1.0)
    assert end.timestamp - start.timestamp < 0.5, (str(start), str(end))
