# SPDX-License-Identifier: Apache-2.0
"""Unit tests of tools/edstool.py: the tables the generator writes from an EDS or a DCF, its
refusals, the hooks file, every rule of the checker, and deterministic output. Standard library
only, but for python canopen, whose import of a DCF the generated values are compared with; runs
the tool with the interpreter running the tests."""
import contextlib
import copy
import os
import random
import resource
import signal
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.normpath(os.path.join(HERE, "..", "..", "tools", "edstool.py"))
sys.path.insert(0, os.path.dirname(TOOL))
import edstool  # noqa: E402

sys.path.insert(0, os.path.normpath(os.path.join(HERE, "..", "..", "fuzz")))
import eds_invariants  # noqa: E402


def var(name, dtype, access, default=None, mapping=0, **extra):
    keys = {"ParameterName": name, "ObjectType": "0x7", "DataType": dtype, "AccessType": access}
    if default is not None:
        keys["DefaultValue"] = default
    keys["PDOMapping"] = str(mapping)
    keys.update(extra)
    return keys


def record(name, count, otype="0x9"):
    return {"ParameterName": name, "ObjectType": otype, "SubNumber": str(count)}


# A small valid device: every checker rule passes, without warnings.
BASE = {
    "FileInfo": {"FileName": "t.eds", "FileVersion": "1", "FileRevision": "0",
                 "EDSVersion": "4.0", "Description": "test", "CreationTime": "12:00PM",
                 "CreationDate": "01-01-2024", "CreatedBy": "tests"},
    "DeviceInfo": {"VendorName": "T", "VendorNumber": "0x5F", "ProductName": "P",
                   "ProductNumber": "1", "RevisionNumber": "1", "OrderCode": "X",
                   "BaudRate_10": "0", "BaudRate_20": "0", "BaudRate_50": "0",
                   "BaudRate_125": "1", "BaudRate_250": "1", "BaudRate_500": "1",
                   "BaudRate_800": "0", "BaudRate_1000": "1", "SimpleBootUpMaster": "0",
                   "SimpleBootUpSlave": "1", "Granularity": "8",
                   "DynamicChannelsSupported": "0", "GroupMessaging": "0", "NrOfRXPDO": "1",
                   "NrOfTXPDO": "1", "LSS_Supported": "0"},
    "MandatoryObjects": {"SupportedObjects": "3", "1": "0x1000", "2": "0x1001", "3": "0x1018"},
    "OptionalObjects": {"SupportedObjects": "6", "1": "0x1008", "2": "0x1014", "3": "0x1400",
                        "4": "0x1600", "5": "0x1800", "6": "0x1A00"},
    "ManufacturerObjects": {"SupportedObjects": "2", "1": "0x2000", "2": "0x2001"},
    "1000": var("Device type", "0x0007", "ro", "0x00010192"),
    "1001": var("Error register", "0x0005", "ro", "0", mapping=1),
    "1008": var("Device name", "0x0009", "const", "Dev"),
    "1014": var("COB-ID EMCY", "0x0007", "rw", "$NODEID+0x80"),
    "1018": record("Identity", 2),
    "1018sub0": var("Highest sub-index supported", "0x0005", "ro", "1"),
    "1018sub1": var("Vendor-ID", "0x0007", "ro", "0x5F"),
    "1400": record("RPDO1 communication", 2),
    "1400sub0": var("Highest sub-index supported", "0x0005", "ro", "1"),
    "1400sub1": var("COB-ID", "0x0007", "rw", "$NODEID+0x200"),
    "1600": record("RPDO1 mapping", 2, "0x8"),
    "1600sub0": var("Number of mapped objects", "0x0005", "rw", "1", LowLimit="0",
                    HighLimit="1"),
    "1600sub1": var("Mapped object 1", "0x0007", "rw", "0x20010010"),
    "1800": record("TPDO1 communication", 2),
    "1800sub0": var("Highest sub-index supported", "0x0005", "ro", "1"),
    "1800sub1": var("COB-ID", "0x0007", "rw", "0x180+$NODEID"),
    "1A00": record("TPDO1 mapping", 2, "0x8"),
    "1A00sub0": var("Number of mapped objects", "0x0005", "rw", "1"),
    "1A00sub1": var("Mapped object 1", "0x0007", "rw", "0x20000110"),
    "2000": record("Record", 3),
    "2000sub0": var("Highest sub-index supported", "0x0005", "ro", "2"),
    "2000sub1": var("Signed", "0x0003", "rw", "-10", mapping=1, LowLimit="-100",
                    HighLimit="100"),
    "2000sub2": var("Text", "0x0009", "ro", "abc", **{";size": "8"}),
    "2001": var("Limited", "0x0006", "rww", "100", mapping=1, LowLimit="10", HighLimit="1000"),
}


def dummy_usage(**values):
    """An edit adding [DummyUsage] with every key 0, then `values` (Dummy0005="1", ...)."""
    def edit(sections):
        sections["DummyUsage"] = {"Dummy%04d" % n: "0" for n in range(1, 8)}
        sections["DummyUsage"].update(values)
    return edit


MEMORY_LIMIT = 1 << 30


def limit_memory():
    """In the tool's process: a run-away allocation fails there instead of exhausting the
    machine."""
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


@contextlib.contextmanager
def bounded(seconds):
    """The limits of run_tool() for the tool run in this process: a run-away allocation raises
    MemoryError, a run-away loop TimeoutError."""
    def timeout(signum, frame):
        raise TimeoutError("still running after %d s" % seconds)
    memory = resource.getrlimit(resource.RLIMIT_AS)
    handler = signal.signal(signal.SIGALRM, timeout)
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, memory[1]))
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, handler)
        resource.setrlimit(resource.RLIMIT_AS, memory)


def render(sections):
    lines = []
    for name, keys in sections.items():
        lines.append("[%s]" % name)
        lines.extend("%s=%s" % kv for kv in keys.items())
        lines.append("")
    return "\n".join(lines)


class ToolCase(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, name, text):
        path = os.path.join(self.dir, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def eds(self, edit=None, name="t.eds"):
        sections = copy.deepcopy(BASE)
        if edit is not None:
            edit(sections)
        return self.write(name, render(sections))

    def run_tool(self, *args, timeout=60, encoding=None):
        """Runs the tool; `encoding` is that of its standard streams (PYTHONIOENCODING)."""
        env = dict(os.environ, PYTHONIOENCODING=encoding) if encoding else None
        p = subprocess.run([sys.executable, TOOL] + list(args), capture_output=True, text=True,
                           preexec_fn=limit_memory, timeout=timeout, env=env)
        return p.returncode, p.stdout, p.stderr

    def generate(self, path, hooks=None, out="gen"):
        args = ["generate", path, "--prefix", "t", "--out-dir", os.path.join(self.dir, out)]
        if hooks is not None:
            args += ["--hooks", hooks]
        return self.run_tool(*args)

    def entries(self, path, hooks=None):
        entries = edstool.build_entries(edstool.parse_eds(path))
        if hooks is not None:
            edstool.apply_hooks(entries, hooks)
        edstool.layout(entries)
        return {(e.index, e.sub): e for e in entries}

    def read(self, name):
        with open(os.path.join(self.dir, "gen", name)) as f:
            return f.read()


class GeneratedTable(ToolCase):
    def test_entries_sorted_with_contiguous_offsets(self):
        keys = list(self.entries(self.eds()))
        self.assertEqual(keys, sorted(keys))
        self.assertEqual(keys[:4], [(0x1000, 0), (0x1001, 0), (0x1008, 0), (0x1014, 0)])
        self.assertIn((0x1018, 0), keys)
        entries = list(self.entries(self.eds()).values())
        offset = 0
        for e in entries:
            self.assertEqual(e.offset, offset)
            offset += e.size

    def test_header_declares_sizes_and_table(self):
        self.assertEqual(self.generate(self.eds())[0], 0)
        entries = list(self.entries(self.eds()).values())
        size = sum(e.size for e in entries)
        header = self.read("t_od.h")
        self.assertIn("#define T_OD_DATA_SIZE %du\n" % size, header)
        self.assertIn("#define T_OD_ENTRIES %du\n" % len(entries), header)
        self.assertIn("extern const co_od_t t_od;", header)
        self.assertIn("Generated from t.eds by tools/edstool.py: do not edit.", header)

    def test_omit_leaves_objects_out(self):
        code, _, err = self.run_tool("generate", self.eds(), "--prefix", "t", "--out-dir",
                                     os.path.join(self.dir, "gen"), "--omit", "0x1014", "2000")
        self.assertEqual((code, err), (0, ""))
        source = self.read("t_od.c")
        self.assertNotIn("/* 1014:00 */", source)
        self.assertNotIn("/* 2000:01 */", source)
        self.assertIn("/* 1018:00 */", source)

    def test_sync_producer_with_1006(self):
        def with_producer(sections):
            sections["OptionalObjects"].update({"SupportedObjects": "8", "7": "0x1005",
                                                "8": "0x1006"})
            sections["1005"] = var("COB-ID SYNC", "0x0007", "rw", "0x80")
            sections["1006"] = var("Communication cycle period", "0x0007", "rw", "0")
        self.assertEqual(self.generate(self.eds(with_producer))[0], 0)
        source = self.read("t_od.c")
        self.assertIn('#include "co/co_sync.h"\n', source)
        self.assertIn("/* SYNC producer */ co_sync_produce};\n", source)
        code, _, err = self.run_tool("generate", self.eds(with_producer), "--prefix", "t",
                                     "--out-dir", os.path.join(self.dir, "gen"), "--omit", "1006")
        self.assertEqual((code, err), (0, ""))
        source = self.read("t_od.c")
        self.assertNotIn("co/co_sync.h", source)
        self.assertIn("/* SYNC producer */ NULL};\n", source)

    def test_omit_refuses_an_object_the_eds_lacks(self):
        code, _, err = self.run_tool("generate", self.eds(), "--prefix", "t", "--out-dir",
                                     os.path.join(self.dir, "gen"), "--omit", "0x1017")
        self.assertEqual(code, 2)
        self.assertIn("--omit 1017h: no such object in the EDS", err)
        code, _, err = self.run_tool("generate", self.eds(), "--prefix", "t", "--out-dir",
                                     os.path.join(self.dir, "gen"), "--omit", "heartbeat")
        self.assertEqual(code, 2)
        self.assertIn("'heartbeat' is not an object index", err)

    def test_default_bytes_little_endian(self):
        entries = self.entries(self.eds())
        self.assertEqual(entries[(0x1000, 0)].default, bytes([0x92, 0x01, 0x01, 0x00]))
        self.assertEqual(entries[(0x2000, 1)].default, (-10 & 0xFFFF).to_bytes(2, "little"))
        self.assertEqual(entries[(0x2000, 2)].default, b"abc" + bytes(5))
        source = (self.generate(self.eds()), self.read("t_od.c"))[1]
        self.assertIn("/* 1000:00 */ 0x92, 0x01, 0x01, 0x00,", source)

    def test_node_id_defaults_stored_without_node_id(self):
        entries = self.entries(self.eds())
        for key, base in (((0x1014, 0), 0x80), ((0x1400, 1), 0x200), ((0x1800, 1), 0x180)):
            self.assertEqual(entries[key].default, base.to_bytes(4, "little"))
            self.assertTrue(entries[key].flags & edstool.NODEID)
        self.assertFalse(entries[(0x1000, 0)].flags & edstool.NODEID)
        self.generate(self.eds())
        self.assertIn("CO_OD_READ | CO_OD_WRITE | CO_OD_NODEID, 4,", self.read("t_od.c"))

    def test_flags_from_access_type_and_pdo_mapping(self):
        R, W, C, T, P = edstool.READ, edstool.WRITE, edstool.CONST, edstool.TPDO, edstool.RPDO
        expected = {("ro", 0): R, ("ro", 1): R | T, ("const", 0): R | C, ("const", 1): R | C | T,
                    ("wo", 0): W, ("wo", 1): W | P, ("rw", 0): R | W, ("rw", 1): R | W | T | P,
                    ("rwr", 0): R | W, ("rwr", 1): R | W | T, ("rww", 0): R | W,
                    ("rww", 1): R | W | P}
        for (access, mapping), flags in expected.items():
            def edit(s):
                s["2001"]["AccessType"] = access
                s["2001"]["PDOMapping"] = str(mapping)
            with self.subTest(access=access, mapping=mapping):
                self.assertEqual(self.entries(self.eds(edit))[(0x2001, 0)].flags, flags)

    def test_limits(self):
        entries = self.entries(self.eds())
        self.assertEqual(entries[(0x2000, 1)].limits, (-100, 100))
        self.assertEqual(entries[(0x2001, 0)].limits, (10, 1000))
        self.assertIsNone(entries[(0x1000, 0)].limits)
        self.generate(self.eds())
        source = self.read("t_od.c")
        self.assertIn("{(uint64_t)INT64_C(-100), (uint64_t)INT64_C(100)}", source)
        self.assertIn("{UINT64_C(10), UINT64_C(1000)}", source)

    def test_one_sided_and_hex_signed_limits(self):
        def edit(s):
            del s["2001"]["HighLimit"]
            s["2000sub1"]["LowLimit"] = "0xFF9C"
            s["2000sub1"]["HighLimit"] = "0x0064"
        entries = self.entries(self.eds(edit))
        self.assertEqual(entries[(0x2001, 0)].limits, (10, 0xFFFF))
        self.assertEqual(entries[(0x2000, 1)].limits, (-100, 100))

    def test_every_core_data_type(self):
        cases = {"0x0001": ("1", b"\x01"), "0x0002": ("-1", b"\xFF"),
                 "0x0004": ("-2", b"\xFE\xFF\xFF\xFF"), "0x0005": ("255", b"\xFF"),
                 "0x0007": ("0x12345678", b"\x78\x56\x34\x12"),
                 "0x0008": ("1.5", b"\x00\x00\xC0\x3F"),
                 "0x000A": ("01A2", b"\x01\xA2"), "0x000B": ("Hi", b"H\x00i\x00"),
                 "0x000F": ("0102", b"\x01\x02"),
                 "0x0011": ("-0.25", b"\x00\x00\x00\x00\x00\x00\xD0\xBF"),
                 "0x0015": ("-2", b"\xFE" + b"\xFF" * 7),
                 "0x001B": ("0x0102030405060708", bytes(range(8, 0, -1)))}
        for dtype, (text, data) in cases.items():
            def edit(s):
                s["2001"] = var("X", dtype, "rw", text)
            with self.subTest(dtype=dtype):
                e = self.entries(self.eds(edit))[(0x2001, 0)]
                self.assertEqual(e.default, data)
                self.assertEqual(e.size, len(data))
                self.assertEqual(e.dtype, int(dtype, 16))

    def test_real_range_ends(self):
        cases = {("0x0008", "3.4028235e38"): b"\xFF\xFF\x7F\x7F",
                 ("0x0008", "-3.4028235e+38"): b"\xFF\xFF\x7F\xFF",
                 ("0x0008", "1e-50"): bytes(4),
                 ("0x0011", "1.7976931348623157e308"): b"\xFF" * 6 + b"\xEF\x7F"}
        for (dtype, text), data in cases.items():
            def edit(s):
                s["2001"] = var("R", dtype, "rw", text)
            with self.subTest(text=text):
                self.assertEqual(self.run_tool("check", self.eds(edit)), (0, "", ""))
                self.assertEqual(self.entries(self.eds(edit))[(0x2001, 0)].default, data)

    def test_string_capacity_directive(self):
        e = self.entries(self.eds())[(0x2000, 2)]
        self.assertEqual((e.size, e.default), (8, b"abc" + bytes(5)))

        def no_directive(s):
            del s["2000sub2"][";size"]
        self.assertEqual(self.entries(self.eds(no_directive))[(0x2000, 2)].size, 3)

    def test_unicode_string_capacity(self):
        def edit(s):
            s["2001"] = var("U", "0x000B", "rw", "Hi", **{";size": "6"})
        e = self.entries(self.eds(edit))[(0x2001, 0)]
        self.assertEqual((e.size, e.default), (6, b"H\x00i\x00\x00\x00"))
        code, out, _ = self.run_tool("dump", self.eds(edit))
        self.assertEqual(code, 0)
        self.assertIn('| 2001h | 0 | U | UNICODE_STRING | rw | - | "Hi" |  | 6 |\n', out)

    def test_domain_with_size_directive(self):
        def edit(s):
            s["2001"] = var("Blob", "0x000F", "rw", **{";size": "16"})
        e = self.entries(self.eds(edit))[(0x2001, 0)]
        self.assertEqual((e.size, e.default), (16, bytes(16)))

    def test_compact_array(self):
        def edit(s):
            s["2001"] = var("Compact", "0x0006", "rw", "7", CompactSubObj="3", ObjectType="0x8")
            s["2001Value"] = {"NrOfEntries": "1", "2": "9"}
        entries = self.entries(self.eds(edit))
        self.assertEqual(entries[(0x2001, 0)].default, b"\x03")
        self.assertEqual([entries[(0x2001, n)].default for n in (1, 2, 3)],
                         [b"\x07\x00", b"\x09\x00", b"\x07\x00"])
        self.assertNotIn((0x2001, 4), entries)

    def test_dummy_usage(self):
        cases = ((None, "0"), (dummy_usage(), "0"),
                 (dummy_usage(Dummy0007="1", Dummy0005="1"),
                  "CO_OD_DUMMY(CO_DT_UNSIGNED8) | CO_OD_DUMMY(CO_DT_UNSIGNED32)"))
        for edit, types in cases:
            with self.subTest(types=types):
                self.assertEqual(self.generate(self.eds(edit))[0], 0)
                self.assertIn("    t_od_defaults, /* [DummyUsage] */ %s, t_od_names,\n" % types,
                              self.read("t_od.c"))

    def test_atv312_declares_no_dummy(self):
        path = os.path.join(HERE, "..", "..", "eds", "ATV312.eds")
        self.assertEqual(edstool.dummy_types(edstool.parse_eds(path)), [])

    def test_deterministic_output(self):
        hooks = self.write("t.hooks", "0x2001 zero-ok app_hook\n")
        self.assertEqual(self.generate(self.eds(), hooks, out="a")[0], 0)
        self.assertEqual(self.generate(self.eds(), hooks, out="b")[0], 0)
        for name in ("t_od.h", "t_od.c"):
            with open(os.path.join(self.dir, "a", name), "rb") as a, \
                    open(os.path.join(self.dir, "b", name), "rb") as b:
                self.assertEqual(a.read(), b.read())

    def test_output_that_is_not_utf8_is_replaced(self):
        os.makedirs(os.path.join(self.dir, "gen"))
        with open(os.path.join(self.dir, "gen", "t_od.c"), "wb") as f:
            f.write(b"\xff\xfe")
        self.assertEqual(self.generate(self.eds()), (0, "", ""))
        self.assertIn("const co_od_t t_od = {", self.read("t_od.c"))

    def test_unchanged_output_is_not_rewritten(self):
        self.generate(self.eds())
        path = os.path.join(self.dir, "gen", "t_od.c")
        os.utime(path, (1000, 1000))
        self.generate(self.eds())
        self.assertEqual(os.stat(path).st_mtime, 1000)


class Hooks(ToolCase):
    def test_zero_ok_and_hook_names(self):
        hooks = self.write("t.hooks", "# comment\n\n0x2001 zero-ok  # 0 = disabled\n"
                                      "0x2000:0x01 signed_hook\n0x1018 identity_hook\n")
        entries = self.entries(self.eds(), hooks)
        self.assertTrue(entries[(0x2001, 0)].flags & edstool.ZERO_OK)
        self.assertEqual(entries[(0x2000, 1)].hook, "signed_hook")
        self.assertIsNone(entries[(0x2000, 2)].hook)
        self.assertEqual([entries[(0x1018, n)].hook for n in (0, 1)], ["identity_hook"] * 2)
        self.assertEqual(self.generate(self.eds(), hooks)[0], 0)
        source = self.read("t_od.c")
        self.assertIn("extern const co_od_hook_t identity_hook;\n", source)
        self.assertIn("extern const co_od_hook_t signed_hook;\n", source)
        self.assertIn("&t_od_limits[1], &signed_hook},", source)
        self.assertIn("CO_OD_RPDO | CO_OD_ZERO_OK, 2,", source)

    def test_decimal_sub_index(self):
        hooks = self.write("t.hooks", "0x2000:2 text_hook\n")
        self.assertEqual(self.entries(self.eds(), hooks)[(0x2000, 2)].hook, "text_hook")

    def domain_eds(self):
        def edit(sections):
            sections["2000"] = record("Record", 4)
            sections["2000sub0"]["DefaultValue"] = "3"
            sections["2000sub3"] = var("Image", "0x000F", "rw", **{";size": "16"})
        return self.eds(edit)

    def test_stream(self):
        plain = self.entries(self.domain_eds())
        self.assertEqual(plain[(0x2000, 3)].size, 16)
        hooks = self.write("t.hooks", "0x2000:3 stream=image_stream\n")
        entries = self.entries(self.domain_eds(), hooks)
        e = entries[(0x2000, 3)]
        self.assertEqual((e.stream, e.hook, e.size), ("image_stream", None, 0))
        self.assertTrue(e.flags & edstool.STREAM)
        self.assertEqual(self.generate(self.domain_eds(), hooks)[0], 0)
        source = self.read("t_od.c")
        self.assertIn("extern const co_od_stream_t image_stream;\n", source)
        self.assertRegex(source, r"\{0x2000, 0x03, CO_DT_DOMAIN, CO_OD_READ \| CO_OD_WRITE \| "
                                 r"CO_OD_STREAM, 0, \d+, NULL, &image_stream\.hook\},")
        self.assertNotIn("co_od_hook_t", source)
        self.assertIn("    /* streamed entries */ &co_od_streaming, /* SYNC producer */ NULL};\n",
                      source)
        self.assertEqual(self.generate(self.domain_eds())[0], 0)
        self.assertIn("    /* streamed entries */ NULL, /* SYNC producer */ NULL};\n",
                      self.read("t_od.c"))
        code, out, err = self.run_tool("dump", self.domain_eds(), "--hooks", hooks)
        self.assertEqual(code, 0, err)
        self.assertIn("(stream image_stream)", out)

    def check_stream_refused(self, text, message):
        hooks = self.write("t.hooks", text)
        code, out, err = self.generate(self.domain_eds(), hooks)
        self.assertEqual(code, 1)
        self.assertIn(hooks + ": " + message, err)

    def test_stream_of_another_type_refused(self):
        self.check_stream_refused("0x2000:1 stream=s\n",
                                  "line 1: 0x2000:0x01 is not a DOMAIN: only a DOMAIN can be "
                                  "streamed")

    def test_stream_and_hook_refused(self):
        self.check_stream_refused("0x2000:3 h\n0x2000:3 stream=s\n",
                                  "line 2: 0x2000:0x03 already has hook h")
        self.check_stream_refused("0x2000:3 stream=s h\n", "line 1: 0x2000:0x03 already has hook s")
        self.check_stream_refused("0x2000:3 stream=s stream=t\n",
                                  "line 1: 0x2000:0x03 already has hook s")

    def check_refused(self, text, message):
        hooks = self.write("t.hooks", text)
        code, out, err = self.generate(self.eds(), hooks)
        self.assertEqual(code, 1)
        self.assertIn(hooks + ": line", err)
        self.assertIn(message, err)

    def test_absent_object_refused(self):
        self.check_refused("0x2001 zero-ok\n0x2002 zero-ok\n", "line 2: 0x2002 is not in the EDS")

    def test_absent_sub_index_refused(self):
        self.check_refused("0x2000:0x05 h\n", "line 1: 0x2000:0x05 is not in the EDS")

    def test_bad_word_refused(self):
        self.check_refused("0x2001 zero_ok-\n", "'zero_ok-' is neither zero-ok, process-data nor a C identifier")

    def test_no_action_refused(self):
        self.check_refused("0x2001\n", "names no hook, zero-ok or process-data")

    def test_two_hooks_refused(self):
        self.check_refused("0x2001 a\n0x2001 b\n", "line 2: 0x2001:0x00 already has hook a")

    def test_sub_index_as_the_hooks_file_writes_it(self):
        """0x hex or decimal digits: no sign, no '_' between digits, no other script's digits,
        which int() takes ('2_0' was 20)."""
        for text in ("+2", "2_0", "0x_2", "0x+2", "\u0662", "-1", "0x"):
            with self.subTest(sub=text):
                self.check_refused("0x2000:%s h\n" % text,
                                   "line 1: '%s' is not a sub-index (0x02 or 2)" % text)
        hooks = self.write("t.hooks", "0x2000:0X02 h\n0x2000:01 g\n")
        entries = self.entries(self.eds(), hooks)
        self.assertEqual((entries[(0x2000, 2)].hook, entries[(0x2000, 1)].hook), ("h", "g"))


    def test_range_of_objects(self):
        """FIRST-LAST names every object of the range (the PLC300's 1,792 markers in one line)."""
        hooks = self.write("t.hooks", "0x2000-0x2001 range_hook\n")
        entries = self.entries(self.eds(), hooks)
        self.assertEqual({entries[(0x2000, n)].hook for n in (0, 1, 2)}, {"range_hook"})
        self.assertEqual(entries[(0x2001, 0)].hook, "range_hook")
        self.assertIsNone(entries[(0x1018, 0)].hook)

    def test_range_refusals(self):
        self.check_refused("0x2001-0x2000 h\n",
                           "line 1: range 0x2001-0x2000 is backwards: write it as 0x2000-0x2001")
        self.check_refused("0x2000-0x2001:1 h\n",
                           "line 1: '0x2000-0x2001:1': a range of objects takes no sub-index")
        self.check_refused("0x3000-0x31FF h\n",
                           "line 1: no object of 0x3000-0x31FF is in the EDS")
        self.check_refused("0x2000-x h\n",
                           "line 1: '0x2000-x' is not a hex index like 0x203C or a range like "
                           "0x3000-0x31FF")


class GeneratorRefusals(ToolCase):
    def refused(self, edit, message):
        path = self.eds(edit)
        code, out, err = self.generate(path)
        self.assertEqual(code, 1, err)
        self.assertEqual(err.strip(), path + ": " + message)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "gen")))

    def test_unsupported_data_type(self):
        self.refused(lambda s: s["1018sub1"].update(DataType="0x0020"),
                     "[1018sub1] DataType=0x0020: unsupported data type")

    def test_cia_type_missing_from_core(self):
        self.refused(lambda s: s["2001"].update(DataType="0x0010"),
                     "[2001] DataType=0x0010: unsupported data type")

    def test_unknown_access_type(self):
        self.refused(lambda s: s["2001"].update(AccessType="rx"),
                     "[2001] AccessType=rx: unknown access type "
                     "(expected one of ro, wo, rw, rwr, rww, const)")

    def test_leading_zero_decimal(self):
        self.refused(lambda s: s["2001"].update(DefaultValue="010"),
                     "[2001] DefaultValue=010: leading zero in a decimal number (octal in CiA "
                     "306, refused by python canopen): write it without the zero or as 0x hex")

    def test_default_out_of_range(self):
        self.refused(lambda s: s["1001"].update(DefaultValue="256"),
                     "[1001] DefaultValue=256: outside the range of UNSIGNED8 (0..255)")

    def test_domain_without_data(self):
        self.refused(lambda s: s.update({"2001": var("Blob", "0x000F", "rw")}),
                     "[2001] DefaultValue: DOMAIN with no default value and no ';size=N' "
                     "comment: its size is unknown")

    def test_size_directive_below_default(self):
        self.refused(lambda s: s["2000sub2"].update({";size": "2"}),
                     "[2000sub2] ;size=2: smaller than the default value (3 bytes)")

    def test_limits_on_real(self):
        self.refused(lambda s: s.update({"2001": var("R", "0x0008", "rw", "1", LowLimit="0")}),
                     "[2001] LowLimit=0: limits on REAL32 are not enforced by the core")

    def test_node_id_limit(self):
        self.refused(lambda s: s["2001"].update(HighLimit="$NODEID+1"),
                     "[2001] HighLimit=$NODEID+1: node-id relative limits cannot be represented")

    def test_low_above_high(self):
        self.refused(lambda s: s["2001"].update(LowLimit="2000"),
                     "[2001] LowLimit=2000: LowLimit above HighLimit")

    def test_listed_object_without_section(self):
        self.refused(lambda s: s.pop("2001"), "[ManufacturerObjects] 2=0x2001: object has no "
                                              "section")

    def test_unlisted_object(self):
        def edit(s):
            s["2002"] = var("Extra", "0x0005", "rw", "0")
        self.refused(edit, "[2002] object not listed in any of "
                           "MandatoryObjects/OptionalObjects/ManufacturerObjects")

    def test_record_without_sub0(self):
        self.refused(lambda s: s.pop("2000sub0"), "[2000] RECORD without a sub-index 0 section")

    def test_unsupported_object_type(self):
        self.refused(lambda s: s["2001"].update(ObjectType="0x5"),
                     "[2001] ObjectType=0x5: unsupported object type")

    def test_non_ascii_visible_string(self):
        self.refused(lambda s: s["1008"].update(DefaultValue="D\u00e9v"),
                     "[1008] DefaultValue=D\u00e9v: VISIBLE_STRING must be ASCII")

    def test_boolean_dummy(self):
        self.refused(dummy_usage(Dummy0001="1"), "[DummyUsage] Dummy0001=1: BOOLEAN dummies are "
                                                 "not supported: the core maps whole bytes")

    def test_bad_dummy_usage(self):
        self.refused(dummy_usage(Dummy0005="2"), "[DummyUsage] Dummy0005=2: must be 0 or 1")

    def test_duplicate_key(self):
        path = self.write("t.eds", render(BASE).replace("[2001]\n", "[2001]\nDataType=0x0005\n"))
        code, _, err = self.generate(path)
        self.assertEqual(code, 1)
        self.assertRegex(err, r"\[2001\] DataType: line \d+: duplicate key")

    def test_duplicate_section(self):
        path = self.write("t.eds", render(BASE) + "[1000]\nParameterName=again\n")
        code, _, err = self.generate(path)
        self.assertEqual(code, 1)
        self.assertRegex(err, r"\[1000\] line \d+: duplicate section")

    def test_object_section_names(self):
        """Issue 22 item 10: an object's section is four hex digits, a sub-index's adds sub and
        one or two (ASCII, any case). A name that starts as a number in another notation is
        refused with its line; one that goes on with a word is a section of another kind."""
        text = render(BASE)
        line = text.count("\n") + 1
        for name in ("0x2002", "0X1018", "12", "02002", "+2002", "-2002", "2000sub", "2000sub100",
                     "2000sub 1", "2000sub0x1", "2000subG", "2000 sub1", "BAD"):
            with self.subTest(name=name):
                path = self.write("t.eds", text + "[%s]\nParameterName=x\n" % name)
                code, _, err = self.generate(path)
                self.assertEqual(code, 1)
                self.assertEqual(err, "%s: [%s] line %d: not an object's section: write its index "
                                      "in four hex digits ([1018]), a sub-index's with sub and "
                                      "one or two ([1018sub1])\n" % (path, name, line))
        # 'ſ' is 's' to a case-insensitive Unicode match, not to CiA 306: a section of another
        # kind, as [2001Value] is.
        path = self.write("t.eds", text + "[2000\u017fub3]\nParameterName=x\nDataType=0x0005\n"
                                          "AccessType=ro\n[2001Value]\nParameterName=y\n")
        self.assertEqual(self.generate(path)[0], 0)
        self.assertNotIn((0x2000, 3), self.entries(path))

    def test_missing_file(self):
        code, _, err = self.generate(os.path.join(self.dir, "none.eds"))
        self.assertEqual(code, 1)
        self.assertIn("none.eds: cannot read", err)


class BadEds(ToolCase):
    """A bad EDS gets one line naming file, section and key, and exit code 1, from check, generate
    and dump alike: never a traceback, never unbounded memory or time (run_tool's limits)."""

    def refused(self, edit, message):
        path = self.eds(edit)
        line = path + ": " + message + "\n"
        out_dir = os.path.join(self.dir, "gen")
        for command, extra, expected in (("check", [], (line, "")),
                                         ("generate", ["--prefix", "t", "--out-dir", out_dir],
                                          ("", line)),
                                         ("dump", [], ("", line))):
            with self.subTest(command=command):
                code, out, err = self.run_tool(command, path, *extra)
                self.assertNotIn("Traceback", err)
                self.assertEqual((code, out, err), (1,) + expected)
        self.assertFalse(os.path.exists(out_dir))

    def test_supported_objects_beyond_an_index_per_object(self):
        self.refused(lambda s: s["ManufacturerObjects"].update(SupportedObjects="0x100000000"),
                     "[ManufacturerObjects] SupportedObjects=0x100000000: must be 0..65535")

    def test_number_wider_than_64_bits(self):
        hex_text, dec_text = "0x" + "F" * 5000, "9" * 5000
        self.refused(lambda s: s["ManufacturerObjects"].update(SupportedObjects=hex_text),
                     "[ManufacturerObjects] SupportedObjects=%s: wider than 64 bits" % hex_text)
        self.refused(lambda s: s["2001"].update(PDOMapping=dec_text),
                     "[2001] PDOMapping=%s: wider than 64 bits" % dec_text)

    def test_real32_beyond_its_range(self):
        self.refused(lambda s: s.update({"2001": var("R", "0x0008", "rw", "1e300")}),
                     "[2001] DefaultValue=1e300: outside the range of REAL32 "
                     "(-3.4028235e+38..3.4028235e+38)")

    def test_real64_beyond_its_range(self):
        self.refused(lambda s: s.update({"2001": var("R", "0x0011", "rw", "-1e309")}),
                     "[2001] DefaultValue=-1e309: outside the range of REAL64 "
                     "(-1.7976931348623157e+308..1.7976931348623157e+308)")

    def test_real_not_a_finite_decimal(self):
        for text in ("nan", "inf", "-Infinity", "1_000.5", "0x1p3"):
            with self.subTest(text=text):
                self.refused(lambda s: s.update({"2001": var("R", "0x0008", "rw", text)}),
                             "[2001] DefaultValue=%s: not a finite decimal number like -1.5e3"
                             % text)

    def test_unicode_string_odd_size(self):
        self.refused(lambda s: s.update({"2001": var("U", "0x000B", "rw", "Hi",
                                                     **{";size": "5"})}),
                     "[2001] ;size=5: must be even: UNICODE_STRING characters take 2 bytes")

    def test_size_directive_not_a_number(self):
        self.refused(lambda s: s["2000sub2"].update({";size": "8 bytes"}),
                     "[2000sub2] ;size=8 bytes: not a number")
        self.refused(lambda s: s["2000sub2"].update({";size": "eight"}),
                     "[2000sub2] ;size=eight: not a number")

    def test_size_directive_beyond_an_entry(self):
        for text in ("0x10000", "0", "-1"):
            with self.subTest(size=text):
                self.refused(lambda s: s.update({"2001": var("D", "0x000F", "rw",
                                                             **{";size": text})}),
                             "[2001] ;size=%s: must be 1..65535" % text)

    def test_node_id_default_stored_below_zero(self):
        # Within UNSIGNED8 once node-id 1..127 is added, but the table stores it without it.
        self.refused(lambda s: s["1001"].update(DefaultValue="$NODEID+-1"),
                     "[1001] DefaultValue=$NODEID+-1: outside the range of UNSIGNED8 (0..255)")

    def test_compact_array_value_section(self):
        def bad_number(s):
            s["2001"] = var("Compact", "0x0006", "rw", "7", CompactSubObj="3", ObjectType="0x8")
            s["2001Value"] = {"NrOfEntries": "1", "2": "abc"}
        self.refused(bad_number, "[2001Value] 2=abc: not a number")

        def beyond_size(s):
            s["2001"] = var("Compact", "0x0009", "rw", "ab", CompactSubObj="3", ObjectType="0x8",
                            **{";size": "4"})
            s["2001Value"] = {"NrOfEntries": "1", "2": "toolong"}
        self.refused(beyond_size, "[2001] ;size=4: smaller than the default value (7 bytes)")

    def test_non_ascii_value_on_an_ascii_terminal(self):
        path = self.eds(lambda s: s["1008"].update(DefaultValue="D\u00e9v"))
        code, out, err = self.run_tool("check", path, encoding="ascii")
        self.assertEqual((code, out, err), (1, path + ": [1008] DefaultValue=D\\xe9v: "
                                                      "VISIBLE_STRING must be ASCII\n", ""))

    def test_empty_object_type(self):
        # python canopen fails on it too (int("", 0)); only a missing ObjectType means VAR.
        self.refused(lambda s: s["2001"].update(ObjectType=""), "[2001] ObjectType=: not a number")

    def test_bad_dummy_usage(self):
        self.refused(dummy_usage(Dummy0004="0x1"), "[DummyUsage] Dummy0004=0x1: must be 0 or 1")

    def test_compact_sub_obj_empty(self):
        def edit(s):
            s["2001"] = var("Compact", "0x0006", "rw", "7", CompactSubObj="", ObjectType="0x8")
        self.refused(edit, "[2001] CompactSubObj=: not a number")


class LargeFile(ToolCase):
    def test_every_manufacturer_index_in_linear_time(self):
        """16384 objects with distinct limits: about a second for each command; looking up
        sub-sections and limits by scanning them all (once minutes) would hit the timeout."""
        def edit(s):
            objects = s["ManufacturerObjects"]
            for index in range(0x2002, 0x6000):
                s["%04X" % index] = var("V", "0x0006", "rw", "0", HighLimit=str(index))
                objects[str(len(objects))] = "0x%04X" % index
            objects["SupportedObjects"] = str(len(objects) - 1)
        path = self.eds(edit)
        out_dir = os.path.join(self.dir, "gen")
        for args in (["check", path], ["dump", path],
                     ["generate", path, "--prefix", "t", "--out-dir", out_dir]):
            with self.subTest(command=args[0]):
                self.assertEqual(self.run_tool(*args, timeout=20)[0], 0)


class Fuzz(ToolCase):
    """fixtures/device.eds with one or two keys set to values from a list of bad ones, from a
    fixed seed, each held to the invariants of the EDS parser's fuzzing (fuzz/eds_invariants.py):
    every command ends with exit code 0 or 1, never an exception; a refusal is the same one line
    from generate and dump, which check --strict refuses too unless it is a feature CiA 306 has
    and the core lacks; an accepted file gives a table the core can search."""

    CASES = 400
    KEYS = ("ObjectType", "DataType", "AccessType", "DefaultValue", "PDOMapping", "LowLimit",
            "HighLimit", "SubNumber", "CompactSubObj", "SupportedObjects", ";size", "1", "2")
    VALUES = ("", "0", "1", "-1", "5", "254", "256", "65535", "0x10000", "0x100000000",
              "0x" + "F" * 40, "9" * 5000, "010", "0x", "abc", "1.5", "1e300", "-1e309", "nan",
              "inf", "1_0", "$NODEID", "$NODEID+-1", "$NODEID+0x80", "0x0", "0x5", "0x7", "0x8",
              "0x9", "0x0008", "0x000B", "0x000C", "0x000F", "0x0010", "rw", "D\u00e9v",
              "\u2603", "01A2", "0102F")

    def mutate(self, rng, lines):
        """A copy of `lines` with a key of a random section set (or added) to a random value, and
        what was set where."""
        lines = list(lines)
        heads = [n for n, line in enumerate(lines) if line.startswith("[")]
        head = rng.choice(heads)
        end = next((n for n in heads if n > head), len(lines))
        own = [line.split("=", 1)[0] for line in lines[head + 1:end] if "=" in line]
        key = rng.choice(self.KEYS + tuple(own))
        line = "%s=%s" % (key, rng.choice(self.VALUES))
        same = [n for n in range(head + 1, end)
                if lines[n].split("=", 1)[0].lower() == key.lower()]
        if same:
            lines[same[0]] = line
        else:
            lines.insert(head + 1, line)
        return lines, "%s: %s" % (lines[head], line[:40])

    def test_mutated_fixture(self):
        rng = random.Random(306)
        with open(os.path.join(HERE, "fixtures", "device.eds")) as f:
            fixture = f.read().splitlines()
        path = os.path.join(self.dir, "f.eds")
        out_dir = os.path.join(self.dir, "gen")
        for _ in range(self.CASES):
            lines, edits = fixture, []
            for _ in range(rng.randint(1, 2)):
                lines, edit = self.mutate(rng, lines)
                edits.append(edit)
            with open(path, "w") as f:
                f.write("\n".join(lines) + "\n")
            with self.subTest(edits=edits), bounded(20):
                eds_invariants.check_commands(path, out_dir)


class Usage(ToolCase):
    def test_no_command(self):
        self.assertEqual(self.run_tool()[0], 2)

    def test_missing_prefix(self):
        code, _, err = self.run_tool("generate", self.eds(), "--out-dir", self.dir)
        self.assertEqual(code, 2)
        self.assertIn("--prefix", err)

    def test_prefix_not_identifier(self):
        code, _, err = self.run_tool("generate", self.eds(), "--prefix", "1x", "--out-dir",
                                     self.dir)
        self.assertEqual(code, 2)
        self.assertIn("'1x' is not a C identifier", err)

    def test_help_exits_zero(self):
        code, out, _ = self.run_tool("generate", "--help")
        self.assertEqual(code, 0)
        self.assertIn("--hooks", out)


class WorkedExample(ToolCase):
    """docs/eds-generator.md shows the files generated from fixtures/example.eds: they must stay
    what the tool really writes."""

    def test_docs_show_real_output(self):
        fixtures = os.path.join(HERE, "fixtures")
        self.assertEqual(self.run_tool("check", "--strict",
                                       os.path.join(fixtures, "example.eds"))[:2], (0, ""))
        code, _, err = self.run_tool("generate", os.path.join(fixtures, "example.eds"),
                                     "--prefix", "fan", "--out-dir", self.dir,
                                     "--hooks", os.path.join(fixtures, "example.hooks"))
        self.assertEqual(code, 0, err)
        with open(os.path.join(HERE, "..", "..", "docs", "eds-generator.md")) as f:
            doc = f.read()
        with open(os.path.join(self.dir, "fan_od.h")) as f:
            self.assertIn("```c\n" + f.read() + "```", doc)
        with open(os.path.join(self.dir, "fan_od.c")) as f:
            source = f.read().splitlines()
        excerpt = doc.split("`gen/fan_od.c` (excerpt)", 1)[1].split("```c\n", 1)[1]
        excerpt = excerpt.split("```", 1)[0].splitlines()
        self.assertGreater(len(excerpt), 10)
        for line in excerpt:
            if line.strip() not in ("...", ""):
                self.assertIn(line, source)


class Dump(ToolCase):
    def test_lists_every_entry(self):
        hooks = self.write("t.hooks", "0x2001 zero-ok app_hook\n")
        code, out, _ = self.run_tool("dump", self.eds(), "--hooks", hooks)
        self.assertEqual(code, 0)
        lines = out.splitlines()
        self.assertEqual(len(lines), 2 + len(self.entries(self.eds())))
        self.assertIn("| 1014h | 0 | COB-ID EMCY | UNSIGNED32 | rw | - | $NODEID+0x00000080 |  "
                      "| 4 |", lines)
        self.assertIn("| 2001h | 0 | Limited | UNSIGNED16 | rww | R | 0x0064 | 10..1000 or 0 "
                      "(hook app_hook) | 2 |", lines)


    def test_non_ascii_name_on_an_ascii_terminal(self):
        path = self.eds(lambda s: s["1008"].update(ParameterName="Fan \u2603"))
        code, out, err = self.run_tool("dump", path, encoding="ascii")
        self.assertEqual((code, err), (0, ""))
        self.assertIn("| 1008h | 0 | Fan \\u2603 | VISIBLE_STRING |", out)


try:
    import canopen
except ImportError:  # the DCF's comparison with python canopen needs it (the project's .venv)
    canopen = None

DRIVE4_DCF = os.path.normpath(os.path.join(HERE, "..", "..", "examples", "netmaster",
                                           "drive4.dcf"))


def dcf_edit(sections):
    """BASE made the DCF of node 5: ParameterValues over some defaults, $NODEID in a value, a
    limit and a ParameterValue."""
    sections["DeviceComissioning"] = {"NodeID": "5", "NodeName": "t5", "Baudrate": "500"}
    sections["1014"]["ParameterValue"] = "0x85"
    sections["1800sub1"]["ParameterValue"] = "$NODEID+0x280"
    sections["2000sub1"]["ParameterValue"] = "-50"
    sections["2000sub2"]["ParameterValue"] = "xyz"
    sections["2001"].update(ParameterValue="500", LowLimit="$NODEID+5")
    sections["1008"]["ParameterValue"] = "Configured"


class Dcf(ToolCase):
    """A DCF as the source of a dictionary: the configured device's values as its defaults."""

    def dcf(self, edit=None):
        def both(sections):
            dcf_edit(sections)
            if edit is not None:
                edit(sections)
        return self.eds(both, name="t.dcf")

    def refused(self, edit, message):
        path = self.dcf(edit)
        code, _, err = self.generate(path)
        self.assertEqual(code, 1, err)
        self.assertEqual(err.strip(), path + ": " + message)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "gen")))

    def test_parameter_value_is_the_default(self):
        entries = self.entries(self.dcf())
        self.assertEqual(entries[(0x2001, 0)].default, (500).to_bytes(2, "little"))
        self.assertEqual(entries[(0x2000, 1)].default, (-50 & 0xFFFF).to_bytes(2, "little"))
        self.assertEqual(entries[(0x2000, 2)].default, b"xyz" + bytes(5))
        # A string's size is its ParameterValue's when no ';size=' comment gives one.
        self.assertEqual((entries[(0x1008, 0)].default, entries[(0x1008, 0)].size),
                         (b"Configured", 10))
        # No ParameterValue: the DefaultValue.
        self.assertEqual(entries[(0x1000, 0)].default, bytes([0x92, 0x01, 0x01, 0x00]))

    def test_node_id_terms_take_the_commissioned_node_id(self):
        entries = self.entries(self.dcf())
        for key, value in (((0x1014, 0), 0x85), ((0x1800, 1), 0x285), ((0x1400, 1), 0x205)):
            e = entries[key]
            self.assertEqual((int.from_bytes(e.default, "little"), e.flags & edstool.NODEID),
                             (value, 0), key)
        self.assertEqual(entries[(0x2001, 0)].limits, (10, 1000))
        self.assertEqual(self.generate(self.dcf())[0], 0)
        source = self.read("t_od.c")
        self.assertNotIn("CO_OD_NODEID", source)
        self.assertIn("/* 1400:01 */ 0x05, 0x02, 0x00, 0x00,", source)
        self.assertIn("Generated from t.dcf by tools/edstool.py", source)

    def test_without_a_node_id_terms_stay_relative(self):
        entries = self.entries(self.dcf(lambda s: s["DeviceComissioning"].pop("NodeID")
                                        and s["2001"].pop("LowLimit")))
        e = entries[(0x1800, 1)]
        self.assertEqual((int.from_bytes(e.default, "little"), e.flags & edstool.NODEID),
                         (0x280, edstool.NODEID))

    def test_objects_are_the_dcfs_own(self):
        def edit(sections):
            del sections["2001"]
            sections["ManufacturerObjects"].update({"SupportedObjects": "2", "2": "0x2002"})
            sections["2002"] = var("Added", "0x0007", "rw", "0", ParameterValue="0x12345678")
        entries = self.entries(self.dcf(edit))
        self.assertNotIn((0x2001, 0), entries)
        self.assertEqual(entries[(0x2002, 0)].default, bytes([0x78, 0x56, 0x34, 0x12]))

    def test_refuses_a_node_id_out_of_range(self):
        self.refused(lambda s: s["DeviceComissioning"].update(NodeID="128"),
                     "[DeviceComissioning] NodeID=128: must be 1..127")
        self.refused(lambda s: s["DeviceComissioning"].update(NodeID="four"),
                     "[DeviceComissioning] NodeID=four: not a number")

    def test_refuses_a_resolved_value_beyond_its_type(self):
        self.refused(lambda s: s["1001"].update(ParameterValue="$NODEID+0xFB"),
                     "[1001] ParameterValue=$NODEID+0xFB: outside the range of UNSIGNED8 "
                     "(0..255) with [DeviceComissioning] NodeID=5")

    def test_refuses_a_bad_parameter_value(self):
        self.refused(lambda s: s["2001"].update(ParameterValue="fast"),
                     "[2001] ParameterValue=fast: not a number")

    def test_refuses_a_domain_from_a_file(self):
        def edit(sections):
            sections["ManufacturerObjects"].update({"SupportedObjects": "3", "3": "0x2002"})
            sections["2002"] = var("Program", "0x000F", "rw", DownloadFile="prog.bin",
                                   **{";size": "16"})
        self.refused(edit, "[2002] DownloadFile=prog.bin: a value in a file is not read: write "
                           "it as ParameterValue, hex bytes")

    def test_check_refuses_what_generate_refuses(self):
        path = self.dcf(lambda s: s["1001"].update(ParameterValue="$NODEID+0xFB"))
        code, out, _ = self.run_tool("check", path)
        self.assertEqual(code, 1)
        self.assertIn(path + ": [1001] ParameterValue=$NODEID+0xFB: outside the range of "
                      "UNSIGNED8 (0..255) with [DeviceComissioning] NodeID=5\n", out)
        path = self.dcf(lambda s: s["DeviceComissioning"].update(NodeID="0"))
        code, out, _ = self.run_tool("check", path)
        self.assertEqual(code, 1)
        self.assertIn(path + ": [DeviceComissioning] NodeID=0: must be 1..127\n", out)

    def test_check_takes_the_parameter_value_as_the_default(self):
        # LowLimit=$NODEID+5 is 10 at NodeID=5: a ParameterValue of 9 is below it, though the
        # DefaultValue (100) is not and 9 is not below 6, the limit at node-id 1.
        path = self.dcf(lambda s: s["2001"].update(ParameterValue="9"))
        code, out, _ = self.run_tool("check", path)
        self.assertEqual((code, out), (1, path + ": [2001] ParameterValue=9: below LowLimit "
                                       "with [DeviceComissioning] NodeID=5\n"))
        self.assertEqual(self.run_tool("check", self.dcf())[:2], (0, ""))


@unittest.skipIf(canopen is None, "python canopen is not installed")
class DcfAgainstCanopen(ToolCase):
    """Every entry of a dictionary generated from a DCF holds the value python canopen's import
    of the same DCF gives it: its ParameterValue, else its DefaultValue, $NODEID the DCF's
    [DeviceComissioning] NodeID."""

    def same_values(self, path):
        od = canopen.import_od(path)
        entries = edstool.build_entries(edstool.parse_eds(path))
        for e in entries:
            obj = od[e.index]
            v = obj if isinstance(obj, canopen.objectdictionary.ODVariable) else obj[e.sub]
            expected = v.value if v.value is not None else v.default
            kind = edstool.DATA_TYPES[e.dtype][2]
            if kind == "vs":
                got = e.default.rstrip(b"\0").decode("ascii")
            elif kind in ("os", "d"):
                got = e.default
            else:
                got = int.from_bytes(e.default, "little", signed=kind == "i")
            with self.subTest(index=hex(e.index), sub=e.sub):
                self.assertEqual(e.flags & edstool.NODEID, 0)
                self.assertEqual(got, expected)
        return entries

    def test_drive4(self):
        entries = {(e.index, e.sub): e for e in self.same_values(DRIVE4_DCF)}
        # Its ParameterValues (heartbeat 100 ms, RPDO6 on 304h) and its NodeID=4 in 1014h.
        self.assertEqual(entries[(0x1017, 0)].default, (100).to_bytes(2, "little"))
        self.assertEqual(entries[(0x1405, 1)].default, (0x304).to_bytes(4, "little"))
        self.assertEqual(entries[(0x1014, 0)].default, (0x84).to_bytes(4, "little"))
        self.assertEqual(len(entries), 96)

    def test_hand_made(self):
        self.assertEqual(len(self.same_values(self.eds(dcf_edit, name="t.dcf"))), 18)


class Checker(ToolCase):
    def check(self, *args):
        return self.run_tool("check", *args)

    def test_valid_file_has_no_finding(self):
        self.assertEqual(self.check(self.eds()), (0, "", ""))

    def test_fixture_and_real_files_pass(self):
        fixture = os.path.join(HERE, "fixtures", "device.eds")
        self.assertEqual(self.check("--strict", fixture)[:2], (0, ""))

    def finds(self, edit, finding, strict=False):
        path = self.eds(edit)
        code, out, _ = self.check(*(["--strict", path] if strict else [path]))
        self.assertEqual(code, 1, out)
        self.assertIn(path + ": " + finding + "\n", out)

    def test_required_sections(self):
        for name in ("FileInfo", "DeviceInfo", "MandatoryObjects"):
            with self.subTest(section=name):
                self.finds(lambda s: s.pop(name), "[%s] required section missing" % name)

    def test_eds_version_in_ascii_digits(self):
        """'\\d' also takes other scripts' digits."""
        self.finds(lambda s: s["FileInfo"].update(EDSVersion="\u0664.\u0660"),
                   "[FileInfo] EDSVersion=\u0664.\u0660: must read like 4.0")

    def test_mandatory_object_missing(self):
        def edit(s):
            s.pop("1001")
            s["MandatoryObjects"] = {"SupportedObjects": "2", "1": "0x1000", "2": "0x1018"}
        self.finds(edit, "[1001] mandatory object missing")

    def test_listed_object_without_section(self):
        self.finds(lambda s: s.pop("1014"), "[OptionalObjects] 2=0x1014: listed object has no "
                                            "section")

    def test_object_not_listed(self):
        self.finds(lambda s: s.update({"2002": var("X", "0x0005", "rw", "0")}),
                   "[2002] object not listed in any of "
                   "MandatoryObjects/OptionalObjects/ManufacturerObjects")

    def test_orphan_sub_section(self):
        self.finds(lambda s: s.update({"2005sub0": var("X", "0x0005", "ro", "0")}),
                   "[2005sub0] sub-index of an object that has no section")

    def test_supported_objects_too_high(self):
        self.finds(lambda s: s["ManufacturerObjects"].update(SupportedObjects="3"),
                   "[ManufacturerObjects] 3: missing (SupportedObjects=3)")

    def test_supported_objects_missing_run(self):
        path = self.eds(lambda s: s["ManufacturerObjects"].update(SupportedObjects="65535"))
        code, out, _ = self.check(path)
        self.assertEqual((code, out.count("\n")), (1, 1))
        self.assertEqual(out, path + ": [ManufacturerObjects] 3..65535: missing "
                                     "(SupportedObjects=65535)\n")

    def test_supported_objects_too_low(self):
        def edit(s):
            s["ManufacturerObjects"]["SupportedObjects"] = "1"
        self.finds(edit, "[ManufacturerObjects] 2: beyond SupportedObjects=1")

    def test_object_in_wrong_list(self):
        def edit(s):
            s["OptionalObjects"]["6"] = "0x2001"
            s["ManufacturerObjects"]["2"] = "0x1A00"
        self.finds(edit, "[OptionalObjects] 6=0x2001: belongs in [ManufacturerObjects]")

    def test_object_listed_twice(self):
        self.finds(lambda s: s["ManufacturerObjects"].update({"2": "0x2000"}),
                   "[ManufacturerObjects] 2=0x2000: already listed in [ManufacturerObjects]")

    def test_sub_number(self):
        self.finds(lambda s: s["2000"].update(SubNumber="4"),
                   "[2000] SubNumber=4: 3 sub-index sections found")

    def test_var_with_sub_number(self):
        self.finds(lambda s: s["2001"].update(SubNumber="1"),
                   "[2001] SubNumber=1: only ARRAY and RECORD have it")

    def test_read_only_sub0_is_highest_sub_index(self):
        self.finds(lambda s: s["2000sub0"].update(DefaultValue="3"),
                   "[2000sub0] DefaultValue=3: highest sub-index present is 2")

    def test_writable_sub0_up_to_highest(self):
        self.finds(lambda s: s["1600sub0"].update(DefaultValue="2", HighLimit="2"),
                   "[1600sub0] DefaultValue=2: above the highest sub-index present is 1")
        self.finds(lambda s: s["1600sub0"].update(HighLimit="8"),
                   "[1600sub0] HighLimit=8: highest sub-index present is 1")

    def test_sub0_type(self):
        self.finds(lambda s: s["2000sub0"].update(DataType="0x0006"),
                   "[2000sub0] DataType=0x0006: sub-index 0 must be UNSIGNED8")

    def test_array_types_differ(self):
        def edit(s):
            s["1600"]["SubNumber"] = "3"
            s["1600sub0"].update(DefaultValue="2", HighLimit="2")
            s["1600sub2"] = var("Mapped object 2", "0x0006", "rw", "0")
        self.finds(edit, "[1600] ARRAY sub-indexes 1.. differ in DataType")

    def test_unknown_data_type(self):
        self.finds(lambda s: s["2001"].update(DataType="0x0030"),
                   "[2001] DataType=0x0030: unknown data type")

    def test_unknown_access_type(self):
        self.finds(lambda s: s["2001"].update(AccessType="read"),
                   "[2001] AccessType=read: unknown access type "
                   "(expected one of ro, wo, rw, rwr, rww, const)")

    def test_unknown_object_type(self):
        self.finds(lambda s: s["2001"].update(ObjectType="0x3"),
                   "[2001] ObjectType=0x3: unknown object type")

    def test_leading_zero_decimal(self):
        self.finds(lambda s: s["2001"].update(LowLimit="010"),
                   "[2001] LowLimit=010: leading zero in a decimal number (octal in CiA 306, "
                   "refused by python canopen): write it without the zero or as 0x hex")

    def test_not_a_number(self):
        self.finds(lambda s: s["DeviceInfo"].update(VendorNumber="0x5G"),
                   "[DeviceInfo] VendorNumber=0x5G: not a number")

    def test_bare_node_id(self):
        self.finds(lambda s: s["1014"].update(DefaultValue="$NODEID"),
                   "[1014] DefaultValue=$NODEID: python canopen cannot read a bare $NODEID: "
                   "write $NODEID+0")

    def test_default_outside_type_range(self):
        self.finds(lambda s: s["1001"].update(DefaultValue="-1"),
                   "[1001] DefaultValue=-1: outside the range of UNSIGNED8 (0..255)")

    def test_node_id_default_outside_range_at_127(self):
        self.finds(lambda s: s["1001"].update(DefaultValue="$NODEID+200"),
                   "[1001] DefaultValue=$NODEID+200: outside the range of UNSIGNED8 (0..255) "
                   "with node-id 127")

    def test_signed_hex_default(self):
        self.finds(lambda s: s["2000sub1"].update(DefaultValue="0xFFF6", LowLimit="-100"),
                   "[2000sub1] DefaultValue=0xFFF6: hex default above the INTEGER16 maximum "
                   "(python canopen does not read it as negative): write it in decimal")

    def test_limit_order(self):
        self.finds(lambda s: s["2001"].update(LowLimit="2000"),
                   "[2001] LowLimit=2000: above HighLimit")

    def test_default_below_low_limit(self):
        self.finds(lambda s: s["2001"].update(DefaultValue="5"),
                   "[2001] DefaultValue=5: below LowLimit")

    def test_default_above_high_limit(self):
        self.finds(lambda s: s["2000sub1"].update(DefaultValue="101"),
                   "[2000sub1] DefaultValue=101: above HighLimit")

    def test_node_id_default_against_limits(self):
        self.finds(lambda s: s["2001"].update(DefaultValue="$NODEID+900"),
                   "[2001] DefaultValue=$NODEID+900: above HighLimit with node-id 127")

    def test_mapped_string_longer_than_a_pdo(self):
        self.finds(lambda s: s["1008"].update(DefaultValue="123456789", PDOMapping="1"),
                   "[1008] PDOMapping=1: 72 bits: more than a PDO's 64")

    def test_mapped_domain(self):
        self.finds(lambda s: s.update({"2001": var("D", "0x000F", "rw", "01", mapping=1)}),
                   "[2001] PDOMapping=1: a DOMAIN cannot be PDO-mapped")

    def test_pdo_mapping_value(self):
        self.finds(lambda s: s["2001"].update(PDOMapping="2"),
                   "[2001] PDOMapping=2: must be 0 or 1")

    def test_cob_id_beyond_11_bits_at_node_127(self):
        self.finds(lambda s: s["1800sub1"].update(DefaultValue="$NODEID+0x7F0"),
                   "[1800sub1] DefaultValue=$NODEID+0x7F0: 0x86F is not an 11-bit identifier "
                   "with node-id 127")

    def test_cob_id_bit_29(self):
        self.finds(lambda s: s["1400sub1"].update(DefaultValue="0x20000200"),
                   "[1400sub1] DefaultValue=0x20000200: bit 29 set: 29-bit identifiers are not "
                   "supported")

    def test_nr_of_pdos(self):
        self.finds(lambda s: s["DeviceInfo"].update(NrOfRXPDO="2"),
                   "[DeviceInfo] NrOfRXPDO=2: 1 objects 1400..15FF present")
        self.finds(lambda s: s["DeviceInfo"].update(NrOfTXPDO="0"),
                   "[DeviceInfo] NrOfTXPDO=0: 1 objects 1800..19FF present")

    def test_pdo_without_mapping(self):
        def edit(s):
            for name in ("1A00", "1A00sub0", "1A00sub1"):
                s.pop(name)
            s["OptionalObjects"]["SupportedObjects"] = "5"
            s["OptionalObjects"].pop("6")
        self.finds(edit, "[1800] PDO without its mapping object 1A00")

    def test_baud_rate_keys(self):
        self.finds(lambda s: s["DeviceInfo"].pop("BaudRate_800"),
                   "[DeviceInfo] BaudRate_800: missing")
        self.finds(lambda s: s["DeviceInfo"].update(BaudRate_125="2"),
                   "[DeviceInfo] BaudRate_125=2: must be 0 or 1")

        def none(s):
            for rate in edstool.BAUD_RATES:
                s["DeviceInfo"]["BaudRate_%d" % rate] = "0"
        self.finds(none, "[DeviceInfo] BaudRate_*: no baud rate supported")

    def test_dummy_usage(self):
        self.finds(dummy_usage(Dummy0005="2"), "[DummyUsage] Dummy0005=2: must be 0 or 1")
        self.finds(dummy_usage(Dummy0005="0x1"), "[DummyUsage] Dummy0005=0x1: must be 0 or 1")
        self.finds(dummy_usage(Dummy0008="1"), "[DummyUsage] Dummy0008=1: not a dummy entry: the "
                                               "keys are Dummy0001..Dummy0007")

        def lower_case(s):
            dummy_usage()(s)
            s["DummyUsage"]["dummy0005"] = s["DummyUsage"].pop("Dummy0005")
        self.finds(lower_case, "[DummyUsage] dummy0005=0: spell it Dummy0005 (python canopen "
                               "reads keys case-sensitively)")

        def missing(s):
            dummy_usage()(s)
            s["DummyUsage"].pop("Dummy0003")
        self.finds(missing, "[DummyUsage] Dummy0003: missing (python canopen reads "
                            "Dummy0001..Dummy0007)")

    def test_boolean_dummy_is_valid_cia_306(self):
        self.assertEqual(self.check("--strict", self.eds(dummy_usage(Dummy0001="1"))),
                         (0, "", ""))

    def test_key_spelling(self):
        def edit(s):
            s["2001"]["Accesstype"] = s["2001"].pop("AccessType")
        self.finds(edit, "[2001] Accesstype: spell it AccessType (python canopen reads keys "
                         "case-sensitively)")

    def test_sub_section_spelling(self):
        def edit(s):
            s["2000SUB1"] = s.pop("2000sub1")
        self.finds(edit, "[2000SUB1] write the section name as 2000sub1 (python canopen only "
                         "reads 'sub')")

    def test_missing_parameter_name(self):
        self.finds(lambda s: s["2001"].pop("ParameterName"), "[2001] ParameterName: missing")

    def test_missing_file_info_key_is_warning(self):
        path = self.eds(lambda s: s["FileInfo"].pop("CreatedBy"))
        self.assertEqual(self.check(path)[:2], (0, path + ": [FileInfo] CreatedBy: warning: "
                                                         "missing\n"))
        self.assertEqual(self.check("--strict", path)[0], 1)

    def test_every_file_is_checked(self):
        good = self.eds()
        bad = self.eds(lambda s: s["1001"].update(DefaultValue="-1"), name="bad.eds")
        code, out, _ = self.check(bad, good)
        self.assertEqual(code, 1)
        self.assertEqual(out.count("\n"), 1)
        self.assertTrue(out.startswith(bad + ": "))

    def test_usage(self):
        self.assertEqual(self.check()[0], 2)


if __name__ == "__main__":
    unittest.main()
