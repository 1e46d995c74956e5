#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes the seed corpus of the harnesses, fuzz/corpus/<harness>/<name>, from readable frames,
time steps and commands (the encoding is in fuzz/steps.h, the commands in each harness), storage
files (docs/atv312d.md, "Storage file") and EDS/DCF text. The committed corpus is these seeds
plus what a fuzzing run added, minimised (docs/fuzzing.md): run this again only to change the
seeds."""
import binascii
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
    """Frames ("604#2B17100064000000", "704#R"), time steps ("+100ms") and commands already
    encoded (bytes) in a row."""
    out = bytearray()
    for step in steps:
        if isinstance(step, bytes):
            out += step
            continue
        if step.startswith("+"):
            us = int(step[1:-2]) * 1000 if step.endswith("ms") else int(step[1:-1]) * 1000000
            shift = 0
            while us >> shift > 0xFFFF:
                shift += 1
            out += bytes([0xF0 | shift]) + struct.pack("<H", us >> shift)
            continue
        can_id, data = step.split("#")
        can_id = int(can_id, 16)
        rtr = data == "R"
        payload = b"" if rtr else bytes.fromhex(data)
        assert len(payload) <= 8, step
        out += bytes([len(payload) << 4 | (0x08 if rtr else 0) | can_id >> 8, can_id & 0xFF])
        out += payload
    return bytes(out)


# The SDO client's seeds: the client talks to server 5 (requests on 605h, answers on 585h); a
# header (its blksize, its pst, flags: 1 = the done callback starts the transfer again), then its
# requests and the server's answers. Downloads send the bytes (31 i + 7) mod 256.
MODES = {"auto": 0, "segmented": 1, "block": 2, "none": 3}


def sdo_header(blksize=0, pst=0, chain=False):
    return bytes([blksize, pst, 1 if chain else 0])


def sdo_request(upload, mux, size, mode="auto", timeout_ms=100, null=False):
    index, sub = (int(x, 16) for x in mux.split(":"))
    tag = 0xE0 | (1 if upload else 0) | MODES[mode] << 1 | (0x08 if null else 0)
    return bytes([tag]) + struct.pack("<HBHB", index, sub, size, timeout_ms)


def upload(mux, size, mode="auto", timeout_ms=100, null=False):
    return sdo_request(True, mux, size, mode, timeout_ms, null)


def download(mux, size, mode="auto", timeout_ms=100, null=False):
    return sdo_request(False, mux, size, mode, timeout_ms, null)


def block_end(data, unused):
    """The block upload's end from the server, n and the CRC of the value."""
    crc = binascii.crc_hqx(data, 0)
    return "585#%02X%04X0000000000" % (0xC1 | unused << 2, crc >> 8 | (crc & 0xFF) << 8)


VALUE20 = bytes(range(0x41, 0x41 + 20))
SDO_CLIENT = {
    "upload-expedited": (sdo_header(), [upload("1000:00", 4), "585#4300100092010100"]),
    "upload-segmented": (sdo_header(), [
        upload("1008:00", 20), "+60ms", "585#4108100009000000", "+60ms",
        "585#0041545633313244", "+60ms", "585#1B41420000000000"]),
    "upload-segmented-no-size": (sdo_header(), [
        upload("1008:00", 20, "segmented"), "585#4008100000000000", "585#0141545633313244"]),
    "upload-too-large": (sdo_header(), [upload("1008:00", 4), "585#4108100009000000"]),
    "upload-wrong-toggle": (sdo_header(), [
        upload("1008:00", 20), "585#4108100009000000", "585#1041545633313244"]),
    "upload-server-abort": (sdo_header(), [upload("6000:00", 4), "585#8000600000000206"]),
    "upload-short-abort": (sdo_header(), [upload("6000:00", 4), "585#8000600000"]),
    "upload-past-buffer": (sdo_header(), [
        upload("2003:00", 8, "segmented"), "585#4003200000000000", "585#00" + VALUE20[0:7].hex(),
        "585#1B" + VALUE20[7:9].hex() + "0000000000"]),
    "upload-timeout": (sdo_header(), [upload("1000:00", 4, timeout_ms=50), "+30ms",
                                      "585#", "+30ms", "+30ms"]),
    "download-expedited": (sdo_header(), [download("2000:01", 2), "585#6000200100000000"]),
    "download-segmented": (sdo_header(), [
        download("2001:00", 10, "segmented"), "585#6001200000000000", "585#2000000000000000",
        "585#3000000000000000"]),
    "download-wrong-mux": (sdo_header(), [download("2001:00", 10), "585#6002200000000000"]),
    "download-block": (sdo_header(), [
        download("2002:00", 20, "block"), "585#A402200004000000", "585#A203040000000000",
        "585#A100000000000000"]),
    "download-block-resend": (sdo_header(pst=4), [
        download("2002:00", 20), "585#A002200002000000", "585#A201020000000000",
        "585#A202020000000000", "585#A100000000000000"]),
    "download-block-empty": (sdo_header(), [
        download("2002:00", 0, "block"), "585#A402200001000000", "585#A201010000000000",
        "585#A100000000000000"]),
    "upload-block": (sdo_header(blksize=4), [
        upload("2003:00", 20, "block"), "585#C603200014000000",
        "585#01" + VALUE20[0:7].hex(), "585#02" + VALUE20[7:14].hex(),
        "585#83" + VALUE20[14:20].hex() + "00", block_end(VALUE20, 1)]),
    "upload-block-lost-segment": (sdo_header(blksize=2), [
        upload("2003:00", 20, "block"), "585#C003200000000000",
        "585#02" + VALUE20[7:14].hex(), "585#01" + VALUE20[0:7].hex(),
        "585#02" + VALUE20[7:14].hex(), "585#81" + VALUE20[14:20].hex() + "00",
        block_end(VALUE20, 1)]),
    "upload-block-pst-fallback": (sdo_header(pst=8), [
        upload("2003:00", 20), "585#4B03200034120000"]),
    "requests-refused": (sdo_header(blksize=200), [
        upload("1000:00", 4), upload("1000:00", 4), download("2000:01", 2, "none"),
        download("2000:01", 2, null=True), "585#4300100092010100",
        upload("1000:00", 4, timeout_ms=0), "595#4300100092010100", "585#R"]),
    "chained": (sdo_header(chain=True), [
        upload("1000:00", 4), "585#4300100092010100", "585#4300100092010100", "+100ms",
        "+100ms"]),
}


# The network master's seeds: a header (fuzz_net_master.c: the start, reset all, SYNC, a process
# image, the boot time and retry delay, then each slave's flags and error control time), then the
# slaves' frames. Slave k is node k (1..3); its identity is the harness's: device type 00020192h,
# 1018h 5Fh, 312h, 00010001h, 12345678h; its writes 1017h (2 bytes), 6060h (1 byte) and 2001h
# (11 bytes, segmented).
STARTS = {"each": 0, "all": 1, "none": 2}
CONTROLS = {"none": 0, "heartbeat": 1, "guarding": 2}
IDENTITY = [0x5F, 0x312, 0x00010001, 0x12345678]


def slave(mandatory=False, report=False, control="heartbeat", time_ms=100, writes=1, check=1):
    flags = (1 if mandatory else 0) | (2 if report else 0) | CONTROLS[control] << 2 \
        | writes << 4 | check << 6
    return bytes([flags, time_ms // 10])


REACTIONS = {"alone": (0, 0), "stop_all": (0x80, 0), "reset_all": (0x80, 0x80)}


def net_header(slaves, start="each", reset_all=True, sync=False, image=False, boot_ms=200,
               retry_ms=500, on_mandatory_error="alone"):
    """on_mandatory_error: 1F80h's reaction to a mandatory slave's loss (bit 6 stop all, bit 4
    reset all), header[0] bit 7 and header[1] bit 7."""
    network, reset = REACTIONS[on_mandatory_error]
    flags = STARTS[start] | (4 if reset_all else 0) | (8 if sync else 0) | (0x10 if image else 0) \
        | (len(slaves) - 1) << 5 | network
    body = b"".join(slaves) + slave() * (3 - len(slaves))
    return bytes([flags, boot_ms // 50 | reset, retry_ms // 50]) + body


def configured(node, writes=1, check=1, device_type=0x00020192):
    """The slave's answers to a whole configuration: 1000h, the checked 1018h subs, the writes."""
    tx = "%03X#" % (0x580 + node)
    answers = [tx + "43001000" + struct.pack("<I", device_type).hex()]
    for sub in range({0: 0, 1: 0, 2: 2, 3: 4}[check]):
        answers.append(tx + "431810%02X" % (sub + 1) + struct.pack("<I", IDENTITY[sub]).hex())
    confirm = ["6017100000000000", "6060600000000000",
               "6001200000000000", "2000000000000000", "3000000000000000"]
    answers += [tx + c for c in confirm[:[0, 1, 2, 5][writes]]]
    return answers


def write_output(offset, data):
    payload = bytes.fromhex(data)
    return bytes([0xE0 | len(payload), offset]) + payload


def disable():
    return bytes([0xEC])


def enable():
    return bytes([0xED])


def nmt_request(command, node, timeout_10ms=9):
    """co_net_master_nmt: command 0..4 (start, stop, preop, reset node, reset communication), node
    0 (all) or the table's slave k % count."""
    return bytes([0xEE, command, node, timeout_10ms])


def sdo_request(slave_index, write=False):
    """co_net_master_sdo: 1018h:01 read, or 6060h written, on slave slave_index % count."""
    return bytes([0xEF, slave_index, 1 if write else 0])


def heartbeats(node, count, period_ms=50, state="05"):
    return ["%03X#%s" % (0x700 + node, state), "+%dms" % period_ms] * count


NET_MASTER = {
    "boot-one": (net_header([slave()]), ["701#00"] + configured(1) + heartbeats(1, 4)),
    "boot-three-start-all": (
        net_header([slave(mandatory=True, writes=3, check=3), slave(check=2), slave(writes=0)],
                   start="all"),
        ["701#00", "702#00", "703#00"] + configured(1, writes=3, check=3)
        + configured(2, check=2) + configured(3, writes=0)
        + ["701#05", "702#05", "703#05", "+50ms"] * 3),
    "boot-each-reset-each": (
        net_header([slave(check=0), slave(control="none")], reset_all=False),
        ["701#00", "702#00"] + configured(1, check=0) + configured(2) + heartbeats(1, 3)),
    "start-none": (net_header([slave(writes=2)], start="none"),
                   ["701#00"] + configured(1, writes=2) + ["701#7F", "+50ms", "701#7F"]),
    "device-type-mismatch-retry": (
        net_header([slave()], retry_ms=100),
        ["701#00", "581#4300100091010200", "+100ms", "701#00"] + configured(1)
        + heartbeats(1, 2)),
    "identity-mismatch": (net_header([slave(check=2)]),
                          ["701#00", "581#4300100092010200", "581#431810015E000000", "+1s"]),
    "sdo-timeout": (net_header([slave()], boot_ms=100), ["+100ms", "+50ms", "+50ms"]),
    "sdo-abort": (net_header([slave(writes=3)]),
                  ["701#00", "581#4300100092010200", "581#8017100000000206", "+1s"]),
    "heartbeat-loss-reboot": (
        net_header([slave()]),
        ["701#00"] + configured(1) + heartbeats(1, 2) + ["+200ms", "701#00"] + configured(1)
        + heartbeats(1, 2)),
    "first-heartbeat-missing": (
        net_header([slave(), slave(check=0)]),
        ["701#00", "702#00"] + configured(1) + configured(2, check=0) + ["702#05", "+50ms"]
        + ["702#05", "+50ms"] * 3 + ["701#00"] + configured(1) + heartbeats(1, 2)),
    "heartbeat-loss-report": (
        net_header([slave(report=True)]),
        ["701#00"] + configured(1) + heartbeats(1, 2) + ["+200ms"] + heartbeats(1, 2)),
    "boot-up-while-operational": (
        net_header([slave()]),
        ["701#00"] + configured(1) + heartbeats(1, 2) + ["701#00"] + configured(1)
        + heartbeats(1, 2)),
    # 1F80h bits 6 and 4: the mandatory slave 1 falls silent; all nodes stopped (SYNC and outputs
    # stop), then started again by the application, or all reset and the network booted again.
    "mandatory-loss-stop-all": (
        net_header([slave(mandatory=True), slave(check=0)], sync=True, image=True,
                   on_mandatory_error="stop_all"),
        ["701#00", "702#00"] + configured(1) + configured(2, check=0)
        + ["701#05", "+50ms", "701#05", "+200ms", write_output(0, "0102"), "+20ms", "701#05",
           nmt_request(0, 0), "+1ms", "701#05", "702#05", "+20ms"]),
    "mandatory-loss-reset-all": (
        net_header([slave(mandatory=True, control="guarding", time_ms=50), slave(check=0)],
                   start="all", on_mandatory_error="reset_all"),
        ["701#00", "702#00"] + configured(1) + configured(2, check=0)
        + ["701#05", "+50ms", "+200ms", "701#00", "702#00"] + configured(1)
        + configured(2, check=0) + ["701#05", "+50ms", "701#85"]),
    "guarding": (
        net_header([slave(control="guarding", time_ms=50)]),
        ["701#00"] + configured(1) + ["701#05", "+50ms", "701#85", "+50ms", "701#05", "+50ms",
                                      "+200ms", "701#85"]),
    "requests": (
        net_header([slave(), slave(check=0)]),
        [sdo_request(0), "701#00", "702#00"] + configured(1) + configured(2, check=0)
        + ["581#431810015F000000", sdo_request(1, write=True), "+1ms", "582#6060600000000000",
           nmt_request(1, 1), "+1ms", "702#04", nmt_request(2, 0), "701#7F", "702#7F",
           nmt_request(3, 2), "+1ms", "702#00"] + configured(2, check=0)
        + [sdo_request(0), sdo_request(1), disable(), "+200ms", "701#05", enable(), "+1ms",
           "701#00", "702#00"] + configured(1) + configured(2, check=0) + heartbeats(1, 2)),
    "process-image": (
        net_header([slave(), slave(writes=0, check=0)], sync=True, image=True),
        ["701#00", "702#00"] + configured(1) + configured(2, writes=0, check=0)
        + ["181#3412", "182#78563412", write_output(0, "ABCD"), write_output(1, "CD01"),
           write_output(2, "01020304"),
           "+10ms", write_output(6, "99"), write_output(7, "0102"), "701#05", "702#05",
           "+10ms"]),
    "emcy": (net_header([slave()]), ["701#00"] + configured(1)
             + ["081#1000010000000000", "085#1000010000000000", "081#00"] + heartbeats(1, 1)),
    # Issue 22's items 1-5, which these inputs broke before they were fixed.
    "item1-ready-while-client-busy": (net_header([slave(), slave()]), ["+200ms", "+50ms"]),
    "item2-boot-up-during-download": (
        net_header([slave(writes=3)]),
        ["701#00", "581#4300100092010200", "581#6017100000000000", "701#00",
         "581#6060600000000000", "581#6001200000000000", "581#2000000000000000",
         "581#3000000000000000"]),
    "boot-up-during-download-reconfigured": (
        net_header([slave(writes=3)]),
        ["701#00", "581#4300100092010200", "581#6017100000000000", "701#00"]
        + configured(1, writes=3) + heartbeats(1, 2)),
    "item3-report-no-first-heartbeat": (
        net_header([slave(report=True)]),
        ["701#00"] + configured(1) + ["+150ms", "701#7F", "+50ms"]),
    "item4-report-lost-before-start-all": (
        net_header([slave(mandatory=True, report=True), slave()], start="all", boot_ms=1000),
        ["701#00"] + configured(1) + ["+150ms", "701#05", "+50ms", "702#00"] + configured(2)
        + ["701#05", "702#05", "+50ms"]),
    "item5-write-without-image": (net_header([slave()]), [write_output(0, ""),
                                                          write_output(0, "01")]),
    "optional-slave-missing": (
        net_header([slave(mandatory=True), slave()], start="all", boot_ms=100),
        ["701#00"] + configured(1) + ["701#05", "+50ms", "701#05", "+50ms", "701#05", "+50ms",
                                      "701#05", "+50ms"]),
}


# The EDS/DCF reader's seeds: files as comaster and cotrace meet them (read for node 5).
EDS_READER = {
    "example": (pathlib.Path(__file__).resolve().parent.parent / "tests" / "tools" / "fixtures"
                / "example.eds").read_bytes(),
    "dcf": b"""[DeviceInfo]
VendorNumber=0x0000005F
ProductNumber=0x00000312

[1000]
ParameterName=Device type
DataType=0x0007
AccessType=ro
DefaultValue=0x00020192

[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2

[1018sub0]
ParameterName=Highest sub-index supported
DataType=0x0005
AccessType=ro
DefaultValue=1

[1018sub1]
ParameterName=Vendor-ID
DataType=0x0007
AccessType=ro
DefaultValue=0x5F

[1800sub1]
ParameterName=COB-ID used by TPDO 1
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x180
ParameterValue=0x40000185

[2001sub5]
ParameterName=HSP high speed (0.1 Hz)
DataType=0x0006
AccessType=rww
DefaultValue=500
Denotation=speed limit
ParameterValue=400

[1008]
ParameterName=Manufacturer device name
DataType=0x0009
AccessType=const
DefaultValue=ATV312
""",
    "syntax": b"""; comment [1000]
# another comment
  [ 1000 ]  
  parametername = Device type 
DATATYPE=7

[1A00SUB0A]
ParameterName=a sub-index in capitals
DataType=5+$nodeid
[DummyUsage]
Dummy0005=1
[1400sub01]
DefaultValue=010
ParameterName=a name
ParameterName=its second name
[1003subFE]
ParameterValue=1
DefaultValue=2
AccessType=RW
[1003subff]
DefaultValue=3
""",
    "error-open-header": b"[1000]\nParameterName=x\n[1001\nDataType=5\n",
    "error-no-key": b"[1000]\nParameterName=x\nDataType\n",
    "error-data-type": b"[1000]\n\n; the next line\nDataType=0x1FFFF\n",
    "no-object": b"[FileInfo]\nFileName=x.eds\n[DeviceInfo]\nVendorNumber=1\n",
    # A line one character longer than the INI reader reads: refused with its number, its tail
    # "[1001]" never taken for a section.
    "error-line-too-long": b"[1000]\nParameterName=" + b"x" * 1003 + b"[1001]\n",
    # Issue 22's item 10: names an object's section would have in another notation.
    "item10-section-0x": b"[1000]\nDataType=7\n[0x12]\nParameterName=x\n",
    "item10-sub-0x": b"[1018sub0x1]\nParameterName=x\n",
}


# The slcan codec's seeds: the bytes a host's slcand and kernel driver write on the serial link
# (lines end in CR), and frame records (fuzz_slcan.c: CAN-ID, length, flags, data, a case
# pattern) that the harness encodes and decodes; each input is both, so a record's bytes are junk
# on the link too.
def slcan_record(can_id, data=b"", flags=0, length=None, case=0):
    length = len(data) if length is None else length
    return struct.pack("<IBB8sB", can_id, length, flags, data, case)


RTR, EFF = 1, 2
SLCAN = {
    "frames": b"t12380011223344556677\rt0800\rt7FF2CAFE\rT1ABCDEF03010203\r",
    "remote-frames": b"r7100\rr7101\rR1FFFFFFF8\r",
    "longest-line": b"T1FFFFFFF8FFFFFFFFFFFFFFFF\r",
    "small-letters": b"t6012cafe\rT1abcdef03a0b0c0\r",
    "slcand-start": b"C\rS8\rO\r",  # slcand -o -c -s8
    "bitrates-and-flush": b"S0\rS4\rS6\r\r\rC\r",
    "malformed": b"t\rt1239\rt1231A\rt1231AAB\rt800\rT200000000\rr71001\rS9\rO1\rZ\r"
                 b"t1239112233445566778899\rT0000000090011223344556677889\r",
    "overlong-then-frame": b"t6048400010000000000000000000000\rt0801AA\r",
    "junk-then-frame": b"\x00\xff\x07garbage\nt7101" + b"05\r",
    "line-without-cr": b"O\rt12380011",
    "records": b"".join([
        slcan_record(0x604, bytes.fromhex("4000100000000000")),
        slcan_record(0x1ABCDEF0, b"\x01\x02\x03", EFF, case=0xFF),
        slcan_record(0x710, b"\xAA", RTR),
        slcan_record(0x1FFFFFFF, b"\xFF" * 8, EFF, case=0x55),
        slcan_record(0x800),                    # 11-bit identifier too large: refused
        slcan_record(0x20000000, flags=EFF),    # 29-bit identifier too large: refused
        slcan_record(0x123, b"\x00" * 8, length=9),  # DLC 9: refused
    ]),
}


# cotrace's DeviceNet decoder's seeds: a header byte (fuzz_dn_trace.c: the assemblies in use
# and a small buffer's size) and candump -L lines; the log recorded from the slave library and
# traces of the decoder's tests (tests/cotrace/test_devicenet_decoder.c).
def dn_header(consumed=None, produced=None, small_cap=41):
    return bytes([[None, 20, 21, 100].index(consumed) | [None, 70, 71, 101].index(produced) << 2
                  | (small_cap - 1) // 5 << 4])


def dn_trace(frames, seconds=1700000000.0):
    return "".join("(%.6f) vcan0 %s\n" % (seconds + i / 1000, f)
                   for i, f in enumerate(frames)).encode()


DN_LOG = (pathlib.Path(__file__).resolve().parent.parent / "tests" / "cotrace"
          / "devicenet.log").read_bytes()
DN_TRACE = {
    "devicenet-log": dn_header() + DN_LOG,
    "devicenet-log-assemblies-20-70": dn_header(20, 70, small_cap=1) + DN_LOG,
    "groups": dn_header() + dn_trace([
        "3FF#", "37F#01020304", "3BF#01", "33F#", "07F#AA", "5F8#0102", "5F9#", "5FA#", "605#01",
        "7C1#", "7ED#00CC", "7F0#", "5FC#R", "12345678#00", "20000004#0010000000000000"]),
    "explicit-errors": dn_header() + dn_trace([
        "5FE#014B03010301", "5FB#01CB00", "5FC#4110050209E803", "5FB#4190E803",
        "5FC#010E7001C8", "5FB#019414FF", "5FE#014C03", "5FB#019408", "5FB#0194", "5FB#0185",
        "5FC#01", "5FC#0132990203"]),
    "fragments": dn_header() + dn_trace([
        "5FC#010E010107", "5FB#81008E0641545633", "5FC#81C000", "5FB#81008E0641545633",
        "5FB#81413132", "5FB#81413132", "5FB#8182", "5FB#81C101", "5FB#81C107",
        "5FC#8181B004", "5FC#8100100415036100", "5FC#8182B004", "5FC#8100100415036100",
        "5FC#8181B004"]),
    "fragments-too-much": dn_header() + dn_trace(
        ["5FC#8100000000000000"] + ["5FC#81%02X000000000000" % (0x40 | i) for i in range(1, 12)]),
    "io-allocation": dn_header(small_cap=16) + dn_trace([
        "5FD#6100B004", "5FD#", "5FD#0102", "3FF#FF074FFB", "5FE#014B03011001", "5FB#01CB00",
        "5FD#0100B004", "3FF#", "37F#70030000", "5FA#", "5FE#014C030110", "5FB#01CC",
        "5FE#014B03012001", "5FB#01CB00", "37F#70030000"]),
    "assembly-selection-restart": dn_header() + dn_trace([
        "5FC#01100500646400", "5FB#0190", "5FC#01100500651400", "5FB#019409FF", "5FD#0F00B004",
        "5FF#00F30078563412", "5FD#0F00B004", "3FF#2706B004", "5FC#010E046503",
        "5FB#018E2706B004"]),
    "assemblies-given": dn_header(20, 70) + dn_trace(["5FD#0500F6FF", "3FF#FF00F6FF",
                                                      "3FF#00000000"]),
    "ucmm": dn_header() + dn_trace(["781#194B0031", "759#01CB00", "759#01CC", "781#19"]),
    # cotrace reads any number of timestamp digits, and interfaces of up to 15 characters.
    "timestamps-and-interfaces": dn_header() + (
        b"(1.0) can0 4CC#010E010101\n(0.5) x 4CB#018EF300\nnot a line\n\n"
        b"(9223372036854775807.999999999) abcdefghijklmno 4CF#00F30078563412\n"),
}


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
    # LSS records (area 81h: node-id, bit timing) under a node-id's key and an unconfigured
    # node's (80h + k), its parameters under that key too.
    "node4-lss-unconfigured": store_file([
        (4, 2, image(1, 0, [(0x1017, 0, u16(100))])),
        (4, 0x81, bytes([20, 2])),
        (0x81, 2, image(1, 0, [(0x1017, 0, u16(200))])),
        (0x81, 0x81, bytes([0xFF, 9])),
    ]),
    # A DeviceNet record of MAC ID 0 (area 80h) first: the drive bound is node 4's.
    "mac0-then-node4": store_file([
        (0, 0x80, bytes([100, 0, 101, 0, 1])),
        (4, 2, image(1, 0, [(0x1017, 0, u16(100))])),
    ]),
}


# The drive on DeviceNet at MAC ID 25, the scanner at 1: Allocate on 4CE, explicit requests on
# 4CC, polls on 4CD; commands E0 (bus off) and E1 (the interface back).
DN_CONNECT = ["4CE#014B03010301", "4CC#41100502096400"]
DN_RUN = "4CD#6100B004"  # Run forward, NetCtrl, NetRef, 1200 rpm
DN_BUS_OFF, DN_INTERFACE_BACK = b"\xE0", b"\xE1"
DN_DRIVE = {
    "online": ["+2000ms"],
    "poll-run-bus-off": ["+2000ms", *DN_CONNECT, DN_RUN, "+50ms", DN_BUS_OFF, "+1000ms"],
    "poll-run-boi-bus-off": ["+2000ms", *DN_CONNECT, "4CC#011003010301", DN_RUN, "+50ms", DN_BUS_OFF,
                             "+2500ms"],
    "poll-run-interface-back": ["+2000ms", *DN_CONNECT, DN_RUN, "+50ms", DN_INTERFACE_BACK, "+2500ms"],
    "poll-run-timeout": ["+2000ms", *DN_CONNECT, DN_RUN, "+100ms", DN_RUN, "+1000ms"],
    "poll-run-release": ["+2000ms", *DN_CONNECT, DN_RUN, "+50ms", "4CE#014C030102", "+1000ms"],
    "explicit-run-watchdog": ["+2000ms", "4CE#014B03010101", "4CC#01102A0108B004", "4CC#011029010301",
                              "+11000ms"],
    "explicit-run-release": ["+2000ms", "4CE#014B03010101", "4CC#01102A0108B004", "4CC#011029010301",
                             "+100ms", "4CE#014C030101"],
    "transparent-run": ["+2000ms", "4CC#01100500646400", "4CC#01050101", "+2000ms", *DN_CONNECT,
                        "4CD#0600B004", "4CD#0700B004", "4CD#0F00B004", "+500ms", DN_BUS_OFF],
    "col-ignore": ["+2000ms", *DN_CONNECT, "4CC#01108101020000", DN_RUN, "+50ms",
                   DN_BUS_OFF],
}


# The DeviceNet scanner's seeds: a scanner of MAC ID 0 and slaves 1, 2, 63 (fuzz_scanner.c).
# Slave 1 answers on 40B (explicit response), hears 40E (unconnected) and 40D (polls), and
# answers polls on 3C1; its COS data come on 341. A request's header carries the XID, toggled
# from 00 to 40 at each request of the slave.
def scanner_command(number, slave=0, a=0, b=0):
    return bytes([0xE0 | number, slave, a, b])


def allocate(choice=0x03):
    return scanner_command(0, a=choice)


def release(choice=0x03):
    return scanner_command(1, a=choice)


def keep_polling(period_ms=25, rate_ms=25):
    return scanner_command(4, a=period_ms - 1, b=rate_ms)


def poll_every(period_ms):
    return scanner_command(5, a=period_ms)


POLL_ANSWER = "3C1#01020304"
SCANNER = {
    "allocate-get-release": [allocate(), "40B#00CB00", scanner_command(2, a=1, b=1),
                             "40B#408EF300", release(), "40B#00CC"],
    "allocate-refused": [allocate(), "40B#00940C01", allocate(0x02), "+1s"],
    "get-fragmented": [allocate(0x01), "40B#00CB00", scanner_command(2, a=1, b=1),
                       "40B#C0008E0641545633", "40B#C0813132"],
    "get-fragment-lost": [allocate(0x01), "40B#00CB00", scanner_command(2, a=1, b=1),
                          "40B#C0008E0641545633", "40B#C0823132"],
    "set-fragmented": [allocate(0x01), "40B#00CB00", scanner_command(3, a=14), "40B#C0C000",
                       "40B#C0C100", "40B#C0C200", "40B#409415FF"],
    "set-fragment-unacknowledged": [allocate(0x01), "40B#00CB00", scanner_command(3, a=20),
                                    "+1s", "+1s"],
    "poll-once": [allocate(), "40B#00CB00", scanner_command(7, a=4), scanner_command(6),
                  POLL_ANSWER, scanner_command(6), "+1s"],
    "keep-polling-lost-restored": [allocate(), "40B#00CB00", keep_polling(), POLL_ANSWER, "+25ms",
                                   POLL_ANSWER, "+125ms", "40B#40CC", "40B#00CB00",
                                   "40B#40902000", "+25ms", POLL_ANSWER],
    "keep-polling-bounded-retry": [allocate(), "40B#00CB00", keep_polling(), "+100ms", "+5s",
                                   "+10s", "+10s", "40B#40CC", "40B#00940C01", "+10s"],
    "keep-polling-stopped-in-a-try": [allocate(), "40B#00CB00", keep_polling(), "+100ms",
                                      "40B#40CC", poll_every(0), release(), "40B#00CB00",
                                      "40B#40CC"],
    "late-answer": [allocate(), "40B#00CB00", poll_every(200), "+1000ms", POLL_ANSWER,
                    POLL_ANSWER],
    "cos-acknowledged": [allocate(0x11), "40B#00CB00", "341#01020304", "341#"],
    "three-slaves": [allocate(), scanner_command(0, slave=1, a=3), scanner_command(0, slave=2, a=3),
                     "40B#00CB00", "413#00CB00", "5FB#00CB00", keep_polling(),
                     scanner_command(4, slave=1, a=24, b=25), scanner_command(4, slave=2, a=24, b=25),
                     POLL_ANSWER, "3C2#01020304", "3FF#01020304", "+25ms", "3FF#01020304"],
    "duplicate-mac": [scanner_command(9), "407#800100FFFFFFFF", "+3s"],
    "check-then-online": [scanner_command(9), "+1s", "+1s", "407#000100FFFFFFFF"],
}


ACTIONS, TOKEN, ANY_ADDRESS, STREAMS_FULL = 1, 2, 4, 8  # fuzz_web.c's first byte


def web(flags, head, body=b""):
    """A request to the web handler: the server's flags, then the request as text."""
    return bytes([flags]) + head.replace(b"\n", b"\r\n") + b"\r\n" + body


def command(line, flags=ACTIONS, headers=b""):
    body = b'{"command":"' + line + b'"}'
    return web(flags, b"POST /api/command HTTP/1.1\nHost: 127.0.0.1:8080\n"
               b"Content-Type: application/json\nContent-Length: %d\n" % len(body) + headers, body)


WEB = {
    "page": web(0, b"GET / HTTP/1.1\nHost: 127.0.0.1:8080\n"),
    "page-fresh": web(0, b"GET /index.html HTTP/1.1\nHost: localhost\nIf-None-Match: \"x\"\n"),
    "bench": web(0, b"GET /api/bench?x=1 HTTP/1.1\nHost: [::1]:8080\n"),
    "state-head": web(0, b"HEAD /api/state HTTP/1.1\nHost: 127.0.0.1\n"),
    "events": web(0, b"GET /api/events HTTP/1.1\nHost: 127.0.0.1:8080\n"),
    "events-full": web(STREAMS_FULL, b"GET /api/events HTTP/1.1\nHost: 127.0.0.1:8080\n"),
    "not-found": web(0, b"GET /api/nothing HTTP/1.1\nHost: 127.0.0.1:8080\n"),
    "wrong-method": web(0, b"DELETE /api/state HTTP/1.1\nHost: 127.0.0.1:8080\n"),
    "rebinding": web(0, b"GET / HTTP/1.1\nHost: evil.example\n"),
    "long-target": web(0, b"GET /" + b"a" * 2100 + b" HTTP/1.1\nHost: 127.0.0.1\n"),
    "long-head": web(0, b"GET / HTTP/1.1\nHost: 127.0.0.1\nCookie: " + b"c" * 8200 + b"\n"),
    "command": command(b"fault 4 OHF"),
    "command-escaped": command(b"input 4 \\u004cI3 on"),
    "command-state": command(b"state"),
    "command-refused": command(b"fault 9 OHF"),
    "command-actions-off": command(b"fault 4 OHF", flags=0),
    "command-token": command(b"fault 4 OHF", ACTIONS | TOKEN | ANY_ADDRESS,
                             b"X-Atv312d-Token: s3cret\n"),
    "command-wrong-token": command(b"fault 4 OHF", ACTIONS | TOKEN, b"X-Atv312d-Token: s3cre\n"),
    "command-cross-site": command(b"fault 4 OHF", headers=b"Origin: http://evil.example\n"
                                  b"Sec-Fetch-Site: cross-site\n"),
    "command-same-origin": command(b"local 4 on", headers=b"Origin: http://127.0.0.1:8080\n"
                                   b"Sec-Fetch-Site: same-origin\n"),
    "command-text": web(ACTIONS, b"POST /api/command HTTP/1.1\nHost: 127.0.0.1\n"
                        b"Content-Type: text/plain\n", b"fault 4 OHF"),
    "command-too-long": web(ACTIONS, b"POST /api/command HTTP/1.1\nHost: 127.0.0.1\n"
                            b"Content-Type: application/json\nContent-Length: 2000\n",
                            b'{"command":"' + b"x" * 1990 + b'"}'),
    "command-malformed": web(ACTIONS, b"POST /api/command HTTP/1.1\nHost: 127.0.0.1\n"
                             b"Content-Type: application/json; charset=utf-8\n", b'{"command": '),
}


def main():
    for harness, seeds in (
            ("frames", {k: frames_input(v) for k, v in FRAMES.items()}),
            ("store", STORES),
            ("sdo_client", {k: h + frames_input(v) for k, (h, v) in SDO_CLIENT.items()}),
            ("net_master", {k: h + frames_input(v) for k, (h, v) in NET_MASTER.items()}),
            ("eds_reader", EDS_READER),
            ("dn_drive", {k: frames_input(v) for k, v in DN_DRIVE.items()}),
            ("slcan", SLCAN),
            ("dn_trace", DN_TRACE),
            ("scanner", {k: frames_input(v) for k, v in SCANNER.items()}),
            ("web", WEB)):
        folder = CORPUS / harness
        folder.mkdir(parents=True, exist_ok=True)
        for name, data in seeds.items():
            (folder / name).write_bytes(data)


if __name__ == "__main__":
    main()
