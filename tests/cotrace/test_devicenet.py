# SPDX-License-Identifier: Apache-2.0
"""cotrace --devicenet on a trace of the DeviceNet slave library: the trace made again byte for
byte by its recorder, decoded as expected, and decoded alike by Wireshark's DeviceNet dissector
(tshark): for every frame the message group, message ID and MAC ID, and every field the
dissector decodes besides (the duplicate MAC ID check's fields, a UCMM service, the service and
destination of a request or response on a connection the UCMM opened, and service,
class, instance, attribute and status wherever it gives them). docs/cotrace.md says what the
dissector leaves undecoded."""

import os
import re
import shutil
import struct
import subprocess
import tempfile
import unittest
from pathlib import Path

COTRACE = os.environ["COTRACE"]
RECORD = os.environ["RECORD_DEVICENET"]
HERE = Path(__file__).resolve().parent
LOG = HERE / "devicenet.log"

LINKTYPE_CAN_SOCKETCAN = 227
CANDUMP = re.compile(r"^\((\d+)\.(\d{6})\) (\S+) ([0-9A-F]{3})#([0-9A-F]*)$")
LINE = re.compile(r"^\(\d+\.\d{6}\) \S+ (?P<frame>\S+)\s+G(?P<group>\d) msg (?P<msg>\d+)"
                  r"(?: (?:from|to) (?P<mac>\d+))?: (?P<meaning>.*)$")
DUP_MAC = re.compile(r"duplicate MAC ID check (request|response), port (\d+), vendor 0x([0-9A-F]{4}),"
                     r" serial number 0x([0-9A-F]{8})")
UCMM = re.compile(r"UCMM (request|response) to (\d+): (.+) (request|response)")
SERVICES = {"Open Explicit Messaging Connection": 0x4B, "Close Connection": 0x4C}
# An explicit message on a connection the UCMM opened: the other end, the service.
UCMM_CONNECTION = re.compile(r"UCMM connection (request|response) to (\d+): (\S+)")
CIP_SERVICES = {"Get_Attribute_Single": 0x0E, "Set_Attribute_Single": 0x10}

# tshark's fields, in this order.
FIELDS = ["devicenet.grp_msg1.id", "devicenet.grp_msg2.id", "devicenet.grp_msg3.id",
          "devicenet.grp_msg4.id", "devicenet.src_mac_id", "devicenet.dup_mac_id.rr",
          "devicenet.dup_mac_id.physical_port_number", "devicenet.dup_mac_id.vendor",
          "devicenet.dup_mac_id.serial_number", "devicenet.service", "devicenet.rr",
          "devicenet.dest_mac_id", "devicenet.class", "devicenet.instance",
          "devicenet.attribute", "cip.genstat"]


def to_pcap(log, pcap):
    """A candump -L log as a pcap file of SocketCAN frames (LINKTYPE_CAN_SOCKETCAN: the
    identifier big-endian, the length, three reserved bytes, the data)."""
    with open(pcap, "wb") as out:
        out.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, LINKTYPE_CAN_SOCKETCAN))
        for line in log.read_text().splitlines():
            seconds, micros, _, can_id, data = CANDUMP.match(line).groups()
            payload = bytes.fromhex(data)
            record = struct.pack(">IBBBB", int(can_id, 16), len(payload), 0, 0, 0) + payload
            out.write(struct.pack("<IIII", int(seconds), int(micros), len(record), len(record)))
            out.write(record)


def tshark_frames(log):
    """Each frame's fields as tshark's DeviceNet dissector decodes them (absent ones left out)."""
    with tempfile.TemporaryDirectory() as tmp:
        pcap = Path(tmp) / "devicenet.pcap"
        to_pcap(log, pcap)
        args = ["tshark", "-r", str(pcap), "-d", "can.subdissector,devicenet", "-T", "fields",
                "-E", "separator=/t", "-E", "occurrence=f"]
        for field in FIELDS:
            args += ["-e", field]
        result = subprocess.run(args, capture_output=True, text=True, timeout=120, check=True)
    frames = []
    for row in result.stdout.splitlines():
        values = row.split("\t")
        frames.append({f: int(v, 0) for f, v in zip(FIELDS, values) if v != ""})
    return frames


def cotrace_frames(log):
    """Each frame's fields as cotrace --devicenet's line says them, named like tshark's."""
    result = subprocess.run([COTRACE, "--devicenet", str(log)], capture_output=True, text=True,
                            timeout=30, check=True)
    frames = []
    for line in result.stdout.splitlines():
        m = LINE.match(line)
        assert m, f"not a DeviceNet line: {line}"
        group = int(m["group"])
        fields = {f"devicenet.grp_msg{group}.id": int(m["msg"])}
        if m["mac"] is not None:
            fields["devicenet.src_mac_id"] = int(m["mac"])
        dup = DUP_MAC.fullmatch(m["meaning"])
        if dup:
            fields["devicenet.dup_mac_id.rr"] = int(dup[1] == "response")
            fields["devicenet.dup_mac_id.physical_port_number"] = int(dup[2])
            fields["devicenet.dup_mac_id.vendor"] = int(dup[3], 16)
            fields["devicenet.dup_mac_id.serial_number"] = int(dup[4], 16)
        ucmm = UCMM.match(m["meaning"])
        if ucmm:
            fields["devicenet.dest_mac_id"] = int(ucmm[2])
            fields["devicenet.service"] = SERVICES[ucmm[3]]
            fields["devicenet.rr"] = int(ucmm[4] == "response")
        connected = UCMM_CONNECTION.match(m["meaning"])
        if connected:
            fields["devicenet.rr"] = int(connected[1] == "response")
            fields["devicenet.dest_mac_id"] = int(connected[2])
            fields["devicenet.service"] = CIP_SERVICES[connected[3]]
        frames.append((line, fields))
    return frames


class RecordedTrace(unittest.TestCase):
    def test_recorder_makes_the_same_trace(self):
        result = subprocess.run([RECORD], capture_output=True, text=True, timeout=30)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, LOG.read_text())

    def test_decoded_as_expected(self):
        result = subprocess.run([COTRACE, "--devicenet", str(LOG)], capture_output=True,
                                text=True, timeout=30)
        self.assertEqual(result.stderr, "")
        self.assertEqual(result.returncode, 0)
        self.assertEqual(result.stdout, (HERE / "devicenet.expected").read_text())


class AgreesWithWireshark(unittest.TestCase):
    def setUp(self):
        if shutil.which("tshark") is None:
            if os.environ.get("CI"):
                self.fail("tshark is missing: scripts/setup installs it")
            self.skipTest("tshark is not installed (scripts/setup installs it)")

    def test_every_field_the_dissector_decodes(self):
        theirs = tshark_frames(LOG)
        ours = cotrace_frames(LOG)
        self.assertEqual(len(theirs), len(ours))
        compared = set()
        for (line, mine), wireshark in zip(ours, theirs):
            for field, value in wireshark.items():
                with self.subTest(frame=line, field=field):
                    self.assertIn(field, mine, "the dissector decodes a field cotrace's line "
                                  "does not say")
                    self.assertEqual(mine[field], value)
                compared.add(field)
            for field in ("devicenet.grp_msg1.id", "devicenet.grp_msg2.id",
                          "devicenet.grp_msg3.id", "devicenet.src_mac_id"):
                if field in mine:
                    self.assertIn(field, wireshark, f"{line}: the dissector has no {field}")
        # The trace has every group of the predefined set, the check both ways and a UCMM
        # request: these fields were all compared at least once.
        self.assertLessEqual({"devicenet.grp_msg1.id", "devicenet.grp_msg2.id",
                              "devicenet.grp_msg3.id", "devicenet.src_mac_id",
                              "devicenet.dup_mac_id.rr", "devicenet.dup_mac_id.vendor",
                              "devicenet.dup_mac_id.serial_number", "devicenet.service",
                              "devicenet.dest_mac_id"}, compared)


if __name__ == "__main__":
    unittest.main()
