# SPDX-License-Identifier: Apache-2.0
"""The DeviceNet EDS of the Altivar 312 (eds/00F3000218090100.EDS): eds-pie, an EDS parser the
project did not write, reads it; its identity, I/O and parameters are those the drive implements;
its application-object parameters are those of the drive's dictionary eds/ATV312.eds at the
paths of the address formula; and the emulated drive answers what the file says (dn_eds_probe,
the drive and the project's scanner wired in memory, path in $DN_EDS_PROBE)."""
import logging
import os
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DN_EDS = os.path.join(ROOT, "eds", "00F3000218090100.EDS")
CANOPEN_EDS = os.path.join(ROOT, "eds", "ATV312.eds")
sys.path.insert(0, os.path.join(ROOT, "tools"))
import edstool  # noqa: E402

from eds_pie.eds import EDS_RefDatabase  # noqa: E402
from eds_pie.eds_pie import CIP_EDS  # noqa: E402

# The application objects' address formula (Altivar 312 DeviceNet manual, "Explicit Messaging")
# on the dictionary's addresses (docs/decisions.md, D-MANUFACTURER-ADDRESS), with the values
# src/drive/models/atv312/devicenet.c gives the adapter; the probe tests hold it to the adapter.
CLASS_FIRST, CLASS_LAST = 0x70, 0xA8
# The node-id of the drive behind the card (atv312d's DN_DRIVE_NODE_ID), which a default of
# $NODEID+n in the CANopen EDS (AdCO, D-ADCO-BDCO) is relative to.
CARD_DRIVE_NODE_ID = 1
ADDRESSES_PER_CLASS = 200
INDEX_FIRST = 0x2000
ADDRESSES_PER_INDEX = 100

# CiA 301 data type -> CIP data type code, size, range.
CIP_TYPES = {0x0005: (0xC6, 1, 0, 0xFF), 0x0003: (0xC3, 2, -0x8000, 0x7FFF),
             0x0006: (0xC7, 2, 0, 0xFFFF)}
CIP_BOOL, CIP_INT, CIP_USINT, CIP_UINT = 0xC1, 0xC3, 0xC6, 0xC7
CIP_SIZES = {CIP_BOOL: 1, CIP_INT: 2, CIP_USINT: 1, CIP_UINT: 2}
# Descriptor bits (CIP Parameter object attribute 4).
ENUMERATED, SCALED, READ_ONLY, MONITOR = 0x0002, 0x0004, 0x0010, 0x0020
# The unit a dictionary entry's name ends with -> units string and scaling divisor.
UNITS = {"0.1 Hz": ("Hz", 10), "0.1 s": ("s", 10), "0.1 A": ("A", 10), "0.1 mA": ("mA", 10),
         "rpm": ("rpm", 1), "%": ("%", 1), "V": ("V", 1)}
# [IO_Info] connection type bits.
POLL, COS, CYCLIC = 0x0001, 0x0004, 0x0008
# CIP general status codes the drive answers.
NOT_SETTABLE, INVALID_VALUE, DEVICE_STATE_CONFLICT = 0x0E, 0x09, 0x10
# A command the drive takes only in Operation enabled (docs/atv312.md, tUn): refused at power-up.
NEEDS_OPERATION_ENABLED = {"tUn auto-tuning"}
# Parameters whose values are a set within their limits: the value tried instead of default + 1.
SET_VALUED = {"rPS ramp switching": 101}  # 0 or a switching source; 101 is LI1

# Param field positions.
(F_RESERVED, F_PATH_SIZE, F_PATH, F_DESCRIPTOR, F_TYPE, F_SIZE, F_NAME, F_UNITS, F_HELP, F_MIN,
 F_MAX, F_DEFAULT, F_MULTIPLIER, F_DIVISOR, F_BASE, F_OFFSET) = range(16)
F_DECIMALS = 20


class Recorder(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.records = []

    def emit(self, record):
        self.records.append((record.levelname, record.getMessage()))


def parse_with_eds_pie():
    """The file as eds-pie reads it, and what eds-pie logged at WARNING and above."""
    recorder = Recorder()
    logger = logging.getLogger("eds_pie")
    logger.addHandler(recorder)
    logger.propagate = False  # eds-pie's basicConfig would print its DEBUG trace
    try:
        with open(DN_EDS, encoding="ascii") as f:
            eds = CIP_EDS(f.read())
    finally:
        logger.removeHandler(recorder)
    return eds, recorder.records


EDS, EDS_PIE_MESSAGES = parse_with_eds_pie()


def default_of(text):
    """A CANopen EDS DefaultValue, N or $NODEID+N, as the drive behind the card holds it."""
    if text.upper().startswith("$NODEID+"):
        return CARD_DRIVE_NODE_ID + int(text[len("$NODEID+"):], 0)
    return int(text, 0)


def number(value):
    """A numeric field: eds-pie keeps limits and defaults (typed by the parameter's data type)
    as written."""
    return value if isinstance(value, int) else int(value, 0)


def path_of(param):
    """(class, instance, attribute) of a parameter's link path "20 cc 24 ii 30 aa"."""
    data = bytes.fromhex(EDS.get_value("Params", param, F_PATH))
    if len(data) != 6 or data[0] != 0x20 or data[2] != 0x24 or data[4] != 0x30:
        raise AssertionError("%s: not a class/instance/attribute path: %s" % (param, data.hex()))
    return data[1], data[3], data[5]


def params():
    return [key for key in EDS.get_section("Params").entries if key.startswith("Param")]


def address_of(index, sub):
    return (index - INDEX_FIRST) * ADDRESSES_PER_INDEX + sub - 1


def application_path(index, sub):
    """Where the DeviceNet card reaches dictionary entry index:sub."""
    offset = address_of(index, sub)
    return CLASS_FIRST + offset // ADDRESSES_PER_CLASS, 1, offset % ADDRESSES_PER_CLASS + 1


def dictionary_entry(path):
    """The dictionary entry of an application object's attribute."""
    cls, _, attribute = path
    offset = (cls - CLASS_FIRST) * ADDRESSES_PER_CLASS + attribute - 1
    return INDEX_FIRST + offset // ADDRESSES_PER_INDEX, offset % ADDRESSES_PER_INDEX + 1


def manufacturer_entries():
    """{(index, sub): Section} of the dictionary's entries the application objects reach."""
    canopen = edstool.parse_eds(CANOPEN_EDS)
    entries = {}
    for index, subs in canopen.subs.items():
        for sub, section in subs.items():
            if sub >= 1 and CLASS_FIRST <= application_path(index, sub)[0] <= CLASS_LAST:
                entries[(index, sub)] = section
    return entries


def split_name(name):
    """'ACC acceleration time (0.1 s)' -> ('ACC acceleration time', '0.1 s')."""
    if name.endswith(")") and " (" in name:
        head, _, tail = name.rpartition(" (")
        return head, tail[:-1]
    return name, None


def probe(lines):
    """Each request's answer from the emulated drive."""
    tool = os.environ.get("DN_EDS_PROBE")
    if not tool:
        raise AssertionError("DN_EDS_PROBE is not set: run through ctest (eds_devicenet)")
    done = subprocess.run([tool], input="".join(line + "\n" for line in lines), text=True,
                          capture_output=True, timeout=60)
    if done.returncode != 0:
        raise AssertionError("dn_eds_probe failed: %s" % done.stderr)
    answers = done.stdout.splitlines()
    if len(answers) != len(lines):
        raise AssertionError("dn_eds_probe answered %d of %d requests" % (len(answers), len(lines)))
    return answers


def get(path):
    return "get %X %X %X" % path


def value_hex(value, cip_type):
    size = CIP_SIZES[cip_type]
    return value.to_bytes(size, "little", signed=cip_type == CIP_INT).hex().upper()


class EdsPieTest(unittest.TestCase):
    def test_what_eds_pie_says_is_only_what_it_cannot_know(self):
        # eds-pie 1.2.0 ships reference data for EtherNet/IP only: a DeviceNet classification
        # is one error, and [IO_Info], the DeviceNet I/O section, is in its meta library without
        # any key, so that each of its entries and fields is "unknown". Every other section
        # must pass its checks without a word. Once eds-pie learns DeviceNet, this test says so.
        db = EDS_RefDatabase()
        self.assertNotIn("DeviceNet", db.multi_protocol_db)
        self.assertEqual(db.meta_db["sections"]["IO_Info"]["entries"], {})
        io_info = EDS.get_section("IO_Info").entries
        expected = [("ERROR", 'Requested Protocol Database "DeviceNet" not available!')]
        for key, entry in io_info.items():
            expected.append(("WARNING", "Unknown Entry [{section.keyword,}].{entry.keyword}"))
            expected += [("WARNING", "Unknown Field [IO_Info].%s.field%d" % (key, n))
                         for n in range(len(entry.fields))]
        self.assertEqual(sorted(EDS_PIE_MESSAGES), sorted(expected))

    def test_sections(self):
        self.assertEqual(list(EDS.sections),
                         ["File", "Device", "Device Classification", "IO_Info", "Params"])
        self.assertEqual(EDS.protocol, "DeviceNet")


class IdentityTest(unittest.TestCase):
    def test_device(self):
        device = {key: EDS.get_value("Device", key) for key in EDS.get_section("Device").entries}
        self.assertEqual(device, {"VendCode": 243, "VendName": "Schneider Electric",
                                  "ProdType": 2, "ProdTypeStr": "AC Drive", "ProdCode": 6153,
                                  "MajRev": 1, "MinRev": 1, "ProdName": "ATV312",
                                  "Catalog": "ATV-312"})

    def test_file_name_is_the_manuals_pattern(self):
        # 00F30002XXXX0100.EDS: vendor, device type, product code, major revision, 00.
        name = "%04X%04X%04X%02X00.EDS" % (EDS.get_value("Device", "VendCode"),
                                           EDS.get_value("Device", "ProdType"),
                                           EDS.get_value("Device", "ProdCode"),
                                           EDS.get_value("Device", "MajRev"))
        self.assertEqual(os.path.basename(DN_EDS), name)

    def test_the_drive_reports_it(self):
        name = EDS.get_value("Device", "ProdName").encode("ascii")
        self.assertEqual(probe(["get 1 1 1", "get 1 1 2", "get 1 1 3", "get 1 1 4",
                                "get 1 1 7"]),
                         ["ok " + value_hex(EDS.get_value("Device", "VendCode"), CIP_UINT),
                          "ok " + value_hex(EDS.get_value("Device", "ProdType"), CIP_UINT),
                          "ok " + value_hex(EDS.get_value("Device", "ProdCode"), CIP_UINT),
                          "ok %02X%02X" % (EDS.get_value("Device", "MajRev"),
                                           EDS.get_value("Device", "MinRev")),
                          "ok " + (bytes([len(name)]) + name).hex().upper()])


class IoInfoTest(unittest.TestCase):
    def fields(self, key):
        return [field.value for field in EDS.get_section("IO_Info").entries[key].fields]

    def assembly(self, key):
        size, bits, types, _, path_size, path, _ = self.fields(key)
        size, bits, path_size = number(size), number(bits), number(path_size)
        data = bytes.fromhex(path)
        self.assertEqual((len(data), data[:3], data[4:]),
                         (path_size, bytes([0x20, 0x04, 0x24]), bytes([0x30, 0x03])), key)
        return size, bits, number(types), data[3]

    def test_connections(self):
        self.assertEqual(number(self.fields("Default")[0]), POLL)
        self.assertEqual([number(v) for v in self.fields("PollInfo")], [POLL | COS | CYCLIC, 1, 1])
        self.assertEqual([number(v) for v in self.fields("COSInfo")], [POLL | COS, 1, 1])
        self.assertEqual([number(v) for v in self.fields("CyclicInfo")], [POLL | CYCLIC, 1, 1])

    def test_assemblies_four_bytes_defaults_21_and_71(self):
        every = POLL | COS | CYCLIC
        self.assertEqual([self.assembly("Input%d" % n) for n in (1, 2, 3)],
                         [(4, 32, every, 71), (4, 32, every, 70), (4, 32, every, 101)])
        self.assertEqual([self.assembly("Output%d" % n) for n in (1, 2, 3)],
                         [(4, 32, every, 21), (4, 32, every, 20), (4, 32, every, 100)])

    def test_the_drive_has_them(self):
        instances = [self.assembly(key)[3] for key in EDS.get_section("IO_Info").entries
                     if key.startswith(("Input", "Output"))]
        answers = probe(["get 4 %X 3" % instance for instance in instances] +
                        ["get 5 0 64", "get 5 0 65"])
        self.assertEqual([len(answer) for answer in answers[:-2]], [len("ok 00000000")] * 6)
        self.assertEqual(answers[-2:], ["ok 1500", "ok 4700"])  # the selection: 21, 71


class ParamsTest(unittest.TestCase):
    def field(self, param, position):
        return EDS.get_value("Params", param, position)

    def test_application_objects_are_the_dictionarys_parameters(self):
        entries = manufacturer_entries()
        by_path = {path_of(p): p for p in params()
                   if CLASS_FIRST <= path_of(p)[0] <= CLASS_LAST}
        self.assertEqual(sorted(by_path), sorted(application_path(*key) for key in entries))
        for (index, sub), section in sorted(entries.items()):
            param = by_path[application_path(index, sub)]
            with self.subTest(entry="%04X:%02X" % (index, sub), param=param):
                self.check_against_dictionary(param, section)

    def check_against_dictionary(self, param, section):
        cip_type, size, low, high = CIP_TYPES[int(section.get("DataType"), 0)]
        name, suffix = split_name(section.get("ParameterName"))
        units, divisor = UNITS.get(suffix, ("", 1))
        read_only = section.get("AccessType") == "ro"
        monitor = read_only and section.get("PDOMapping") == "1"
        descriptor = ((READ_ONLY if read_only else 0) | (MONITOR if monitor else 0) |
                      (SCALED if divisor != 1 else 0))
        self.assertEqual(
            [self.field(param, n) for n in (F_RESERVED, F_PATH_SIZE, F_DESCRIPTOR, F_TYPE, F_SIZE,
                                            F_NAME, F_UNITS, F_HELP)],
            [0, 6, descriptor, cip_type, size, name, units,
             suffix if suffix not in UNITS and suffix else ""])
        self.assertEqual([number(self.field(param, n)) for n in (F_MIN, F_MAX, F_DEFAULT)],
                         [int(section.get("LowLimit") or str(low), 0),
                          int(section.get("HighLimit") or str(high), 0),
                          default_of(section.get("DefaultValue"))])
        scaling = [self.field(param, n)
                   for n in (F_MULTIPLIER, F_DIVISOR, F_BASE, F_OFFSET, F_DECIMALS)]
        self.assertEqual(scaling, [1, 10, 1, 0, 1] if divisor != 1 else ["", "", "", "", 0])

    def test_every_param_is_well_formed(self):
        for param in params():
            with self.subTest(param=param):
                cip_type = self.field(param, F_TYPE)
                low, high, default = (number(self.field(param, n))
                                      for n in (F_MIN, F_MAX, F_DEFAULT))
                self.assertEqual(self.field(param, F_SIZE), CIP_SIZES[cip_type])
                self.assertLessEqual(low, default)
                self.assertLessEqual(default, high)
                enumerated = bool(self.field(param, F_DESCRIPTOR) & ENUMERATED)
                self.assertEqual(enumerated, EDS.has_entry("Params", "Enum" + param[5:]))

    def test_the_drive_answers_each_path_with_its_default(self):
        # At power-up every parameter reads its default: the type, size and value of the EDS.
        all_params = params()
        answers = probe([get(path_of(p)) for p in all_params])
        for param, answer in zip(all_params, answers):
            with self.subTest(param=param, path=path_of(param)):
                self.assertEqual(answer, "ok " + value_hex(number(self.field(param, F_DEFAULT)),
                                                           self.field(param, F_TYPE)))

    def test_read_only_params_are_refused_a_set(self):
        read_only = [p for p in params() if self.field(p, F_DESCRIPTOR) & READ_ONLY]
        answers = probe(["set %X %X %X " % path_of(p) +
                         value_hex(number(self.field(p, F_DEFAULT)), self.field(p, F_TYPE))
                         for p in read_only])
        self.assertEqual(answers, ["error %02X FF" % NOT_SETTABLE] * len(read_only))

    def test_application_paths_reach_their_dictionary_entry(self):
        # A value next to the default, set through the path, is in the dictionary entry the
        # formula names; a value above the EDS's maximum is refused; the default is set back.
        settable = [p for p in params() if CLASS_FIRST <= path_of(p)[0] <= CLASS_LAST and
                    not self.field(p, F_DESCRIPTOR) & READ_ONLY]
        self.assertTrue(settable)
        lines, expected = [], []
        for p in settable:
            path, cip_type = path_of(p), self.field(p, F_TYPE)
            low, high, default = (number(self.field(p, n)) for n in (F_MIN, F_MAX, F_DEFAULT))
            other = SET_VALUED.get(self.field(p, F_NAME),
                                   default + 1 if default < high else default - 1)
            type_high = CIP_TYPES[0x0003][3] if cip_type == CIP_INT else 0xFFFF
            lines += ["set %X %X %X %s" % (path + (value_hex(other, cip_type),)),
                      "od %X %X" % dictionary_entry(path)]
            if self.field(p, F_NAME) in NEEDS_OPERATION_ENABLED:
                expected += ["error %02X FF" % DEVICE_STATE_CONFLICT,
                             "ok " + value_hex(default, cip_type)]
            else:
                expected += ["ok ", "ok " + value_hex(other, cip_type)]
            if high < type_high:
                lines.append("set %X %X %X %s" % (path + (value_hex(high + 1, cip_type),)))
                expected.append("error %02X FF" % INVALID_VALUE)
            lines.append("set %X %X %X %s" % (path + (value_hex(default, cip_type),)))
            expected.append("ok ")
        self.assertEqual(probe(lines), expected)


if __name__ == "__main__":
    unittest.main()
