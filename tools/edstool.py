#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""edstool: turns a CiA 306 EDS, or a DCF (a configured device), into the object dictionary table
of the CANopen core, and checks EDS files against the rules of CiA 306 that real tools (python
canopen among them) rely on.

Python 3 standard library only. Exit codes: 0 success, 1 invalid input, 2 usage error."""

import argparse
import math
import os
import re
import struct
import sys

EXIT_OK = 0
EXIT_INVALID = 1
EXIT_USAGE = 2

# CiA 301 table 44: static data types, (name, bytes or None for variable size, kind).
# kind: 'u' unsigned, 'i' signed, 'f' float, 'b' boolean, 'vs' visible string,
# 'os' octet string, 'us' unicode string, 'd' domain, 't' time (not supported by the core).
DATA_TYPES = {
    0x01: ("BOOLEAN", 1, "b"),
    0x02: ("INTEGER8", 1, "i"),
    0x03: ("INTEGER16", 2, "i"),
    0x04: ("INTEGER32", 4, "i"),
    0x05: ("UNSIGNED8", 1, "u"),
    0x06: ("UNSIGNED16", 2, "u"),
    0x07: ("UNSIGNED32", 4, "u"),
    0x08: ("REAL32", 4, "f"),
    0x09: ("VISIBLE_STRING", None, "vs"),
    0x0A: ("OCTET_STRING", None, "os"),
    0x0B: ("UNICODE_STRING", None, "us"),
    0x0C: ("TIME_OF_DAY", 6, "t"),
    0x0D: ("TIME_DIFFERENCE", 6, "t"),
    0x0F: ("DOMAIN", None, "d"),
    0x10: ("INTEGER24", 3, "i"),
    0x11: ("REAL64", 8, "f"),
    0x12: ("INTEGER40", 5, "i"),
    0x13: ("INTEGER48", 6, "i"),
    0x14: ("INTEGER56", 7, "i"),
    0x15: ("INTEGER64", 8, "i"),
    0x16: ("UNSIGNED24", 3, "u"),
    0x18: ("UNSIGNED40", 5, "u"),
    0x19: ("UNSIGNED48", 6, "u"),
    0x1A: ("UNSIGNED56", 7, "u"),
    0x1B: ("UNSIGNED64", 8, "u"),
}

# The types of include/co/co_types.h (co_dtype_t): what the generator can represent.
CORE_TYPES = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A, 0x0B, 0x0F, 0x11, 0x15,
              0x1B}

# CiA 306 object codes.
OBJ_NULL, OBJ_DOMAIN, OBJ_DEFTYPE, OBJ_DEFSTRUCT, OBJ_VAR, OBJ_ARRAY, OBJ_RECORD = 0, 2, 5, 6, 7, 8, 9
OBJECT_TYPES = {OBJ_NULL: "NULL", OBJ_DOMAIN: "DOMAIN", OBJ_DEFTYPE: "DEFTYPE",
                OBJ_DEFSTRUCT: "DEFSTRUCT", OBJ_VAR: "VAR", OBJ_ARRAY: "ARRAY",
                OBJ_RECORD: "RECORD"}

ACCESS_TYPES = ("ro", "wo", "rw", "rwr", "rww", "const")

# Flags of include/co/co_od.h.
READ, WRITE, CONST, TPDO, RPDO, NODEID, ZERO_OK, PROCESS, STREAM = (0x01, 0x02, 0x04, 0x08, 0x10,
                                                                    0x20, 0x40, 0x80, 0x100)
FLAG_NAMES = ((READ, "CO_OD_READ"), (WRITE, "CO_OD_WRITE"), (CONST, "CO_OD_CONST"),
              (TPDO, "CO_OD_TPDO"), (RPDO, "CO_OD_RPDO"), (NODEID, "CO_OD_NODEID"),
              (ZERO_OK, "CO_OD_ZERO_OK"), (PROCESS, "CO_OD_PROCESS"), (STREAM, "CO_OD_STREAM"))
# Words of a hooks file that set a flag rather than name a hook.
HOOK_FLAG_WORDS = {"zero-ok": ZERO_OK, "process-data": PROCESS}

ACCESS_FLAGS = {"ro": READ, "wo": WRITE, "rw": READ | WRITE, "rwr": READ | WRITE,
                "rww": READ | WRITE, "const": READ | CONST}
# PDOMapping=1: which PDO direction each access type may be mapped into.
PDO_FLAGS = {"ro": TPDO, "const": TPDO, "rwr": TPDO, "rww": RPDO, "rw": TPDO | RPDO,
             "wo": RPDO}

OBJECT_LISTS = ("MandatoryObjects", "OptionalObjects", "ManufacturerObjects")

# CiA 306 [DummyUsage]: DummyXXXX=1 declares that a PDO may map the data type XXXXh (0001h-0007h,
# CiA 301 7.4.8.4) as a dummy entry. python canopen reads all seven keys, case-sensitively, as
# decimal integers.
DUMMY_SECTION = "DummyUsage"
DUMMY_TYPES = range(0x01, 0x08)
DUMMY_KEY = re.compile(r"^dummy([0-9a-f]{4})$", re.IGNORECASE)

# A comment line inside an object's section giving the capacity of a string or domain entry,
# invisible to every other EDS reader: ";size=32". Whatever follows '=' is its value, so that
# ";size=32 bytes" is refused rather than ignored.
SIZE_DIRECTIVE = re.compile(r"^;\s*size\s*=\s*(.*?)\s*$", re.IGNORECASE)

NODEID_FORMS = re.compile(r"^(?:\$NODEID\+(?P<after>.+)|(?P<before>.+)\+\$NODEID)$", re.IGNORECASE)
HEX_NUMBER = re.compile(r"^-?0[xX][0-9a-fA-F]+$")
DEC_NUMBER = re.compile(r"^-?(?:0|[1-9][0-9]*)$")
OCTAL_LOOKING = re.compile(r"^-?0[0-9]+$")
# REAL32/REAL64 defaults: decimal only (no NaN, infinity or Python's 1_000), and the struct format
# and largest magnitude of each size.
FLOAT_NUMBER = re.compile(r"^[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$")
REAL_FORMATS = {4: ("<f", "3.4028235e+38"), 8: ("<d", "1.7976931348623157e+308")}
# No CiA 301 integer is wider than 64 bits; nothing wider gets past parse_number.
NUMBER_LIMIT = 1 << 64
# Bytes of a string or domain entry (co_od_entry_t.size is a uint16_t).
MAX_ENTRY_SIZE = 0xFFFF
# Objects an object list can hold: one per 16-bit index but 0000h.
MAX_LISTED = 0xFFFF

# CiA 306's DCF: the section (spelt so by CiA 306) whose NodeID is the node-id $NODEID stands for,
# the value that configures an entry (over its DefaultValue), and the key naming a file that holds
# the value to download into a DOMAIN, which the generator does not read.
COMMISSIONING = "DeviceComissioning"
PARAMETER_VALUE = "ParameterValue"
DOMAIN_FILE_KEY = "DownloadFile"
NODE_ID_RANGE = (1, 127)


class EdsError(Exception):
    """A problem with an input file, reported as 'file: [section] key: message'."""

    def __init__(self, path, section, key, message):
        super().__init__(message)
        self.path = path
        self.section = section
        self.key = key
        self.message = message

    def __str__(self):
        where = self.path + ":"
        if self.section is not None:
            where += " [%s]" % self.section
        if self.key is not None:
            where += " " + self.key + ":"
        return "%s %s" % (where, self.message)


class Key:
    def __init__(self, name, value, line):
        self.name = name
        self.value = value
        self.line = line


class Section:
    def __init__(self, name, line):
        self.name = name
        self.line = line
        self.keys = {}          # lower-case key -> Key, in file order
        self.size_directive = None

    def get(self, key):
        k = self.keys.get(key.lower())
        return None if k is None else k.value

    def has(self, key):
        return key.lower() in self.keys

    def label(self, key):
        """'Key=value' as written, for messages."""
        k = self.keys.get(key.lower())
        return key if k is None else "%s=%s" % (k.name, k.value)


class Eds:
    def __init__(self, path):
        self.path = path
        self.sections = {}      # lower-case name -> Section, in file order
        self.subs = {}          # object index -> {sub-index: Section}, the XXXXsubN sections
        self.node_id = None     # a DCF's [DeviceComissioning] NodeID, as parse_eds read it

    def section(self, name):
        return self.sections.get(name.lower())

    def sub_sections(self, index):
        """{sub-index: Section} of one object."""
        return self.subs.get(index, {})

    def error(self, section, key, message):
        return EdsError(self.path, section, key, message)


def parse_eds(path):
    """Reads an EDS into sections of keys, keeping names as written and rejecting what INI
    readers (python's configparser among them) would refuse: duplicate sections and keys."""
    eds = Eds(path)
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise EdsError(path, None, None, "cannot read: %s" % e.strerror)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise EdsError(path, None, None, "not UTF-8/ASCII text (byte %d)" % e.start)
    current = None
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith(";") or stripped.startswith("#"):
            m = SIZE_DIRECTIVE.match(stripped)
            if m and current is not None:
                current.size_directive = m.group(1)
            continue
        if stripped.startswith("["):
            if not stripped.endswith("]"):
                raise EdsError(path, None, None, "line %d: malformed section header" % number)
            name = stripped[1:-1].strip()
            if name.lower() in eds.sections:
                raise EdsError(path, name, None, "line %d: duplicate section" % number)
            m = SUB_SECTION.match(name)
            if not (m or OBJECT_SECTION.match(name)) and OBJECT_LIKE_SECTION.match(name):
                raise EdsError(path, name, None, "line %d: not an object's section: write its "
                               "index in four hex digits ([1018]), a sub-index's with sub and "
                               "one or two ([1018sub1])" % number)
            current = Section(name, number)
            eds.sections[name.lower()] = current
            if m:
                eds.subs.setdefault(int(m.group(1), 16), {})[int(m.group(2), 16)] = current
            continue
        if "=" not in stripped:
            raise EdsError(path, current.name if current else None, None,
                           "line %d: expected key=value" % number)
        if current is None:
            raise EdsError(path, None, None, "line %d: key outside any section" % number)
        key, value = stripped.split("=", 1)
        key = key.strip()
        # Inline comments as configparser reads them: ';' after whitespace.
        value = re.split(r"\s;", value, maxsplit=1)[0].strip()
        if key.lower() in current.keys:
            raise EdsError(path, current.name, key, "line %d: duplicate key" % number)
        current.keys[key.lower()] = Key(key, value, number)
    eds.node_id = commissioned_node_id(eds)
    return eds


def parse_number(text):
    """An integer as CiA 306 writes it and python canopen reads it: decimal or 0x hex, with an
    optional '-'. Returns (value, is_hex). Raises ValueError with the reason."""
    t = text.strip()
    if HEX_NUMBER.match(t):
        value, is_hex = int(t, 16), True
    elif DEC_NUMBER.match(t):
        # 21 characters hold any 64-bit decimal; int() is slow (and refuses) on thousands of digits.
        value, is_hex = int(t, 10) if len(t) <= 21 else NUMBER_LIMIT, False
    elif OCTAL_LOOKING.match(t):
        raise ValueError("leading zero in a decimal number (octal in CiA 306, refused by python "
                         "canopen): write it without the zero or as 0x hex")
    else:
        raise ValueError("not a number")
    if not -NUMBER_LIMIT < value < NUMBER_LIMIT:
        raise ValueError("wider than 64 bits")
    return value, is_hex


def read_count(eds, sec, key, low, high):
    """A count the file gives (SupportedObjects, CompactSubObj), which the tool loops over:
    required, and within low..high."""
    text = sec.get(key)
    if text is None:
        raise eds.error(sec.name, key, "missing")
    try:
        count, _ = parse_number(text)
    except ValueError as e:
        raise eds.error(sec.name, sec.label(key), str(e))
    if not low <= count <= high:
        raise eds.error(sec.name, sec.label(key), "must be %d..%d" % (low, high))
    return count


def parse_value(text):
    """A numeric value, possibly node-id relative: N, $NODEID+N or N+$NODEID.
    Returns (value, is_hex, nodeid_relative)."""
    t = text.replace(" ", "")
    m = NODEID_FORMS.match(t)
    if m:
        value, is_hex = parse_number(m.group("after") or m.group("before"))
        return value, is_hex, True
    if t.upper() == "$NODEID":
        return 0, False, True
    if "$NODEID" in t.upper():
        raise ValueError("unsupported $NODEID form: use $NODEID+N or N+$NODEID")
    value, is_hex = parse_number(t)
    return value, is_hex, False


def type_range(dtype):
    name, size, kind = DATA_TYPES[dtype]
    if kind == "b":
        return 0, 1
    if kind == "u":
        return 0, (1 << (8 * size)) - 1
    if kind == "i":
        return -(1 << (8 * size - 1)), (1 << (8 * size - 1)) - 1
    return None


def signed_limit(value, is_hex, dtype):
    """python canopen reads a hex limit of a signed type as two's complement; so do we."""
    name, size, kind = DATA_TYPES[dtype]
    if kind == "i" and is_hex and value >= (1 << (8 * size - 1)) and value < (1 << (8 * size)):
        return value - (1 << (8 * size))
    return value


def parse_index(text):
    t = text.strip()
    if t.lower().startswith("0x"):
        t = t[2:]
    if not re.match(r"^[0-9a-fA-F]{1,4}$", t):
        raise ValueError("not a hex index")
    return int(t, 16)


# CiA 306 names an object's section by its index in four hex digits ([1018]) and a sub-index's by
# the index, "sub" and the sub-index in one or two ([1018sub1]), in any case; ASCII only, for 'ſ'
# is 's' to a case-insensitive Unicode match.
SUB_SECTION = re.compile(r"^([0-9a-f]{4})sub([0-9a-f]{1,2})$", re.IGNORECASE | re.ASCII)
OBJECT_SECTION = re.compile(r"^[0-9a-f]{4}$", re.IGNORECASE | re.ASCII)
# A name that starts as a number would (a sign, 0x, hex digits) and stops there or goes on with
# "sub" or a blank is meant as an object's ([0x12], [12], [1018sub], [1018 sub1]); one that goes on
# with a word is a section of another kind ([1F22Value]). The C reader (src/eds/eds_reader.c)
# draws the same line.
OBJECT_LIKE_SECTION = re.compile(r"[+-]?(?:0x)?[0-9a-f]+(?:sub|\s|\Z)", re.IGNORECASE | re.ASCII)


def read_dummy_usage(eds):
    """The data types [DummyUsage] declares as dummies (value 1), and its problems as a list of
    (section, key, message) as written. No section declares none."""
    declared, problems = set(), []
    sec = eds.section(DUMMY_SECTION)
    if sec is None:
        return declared, problems
    for key in sec.keys.values():
        m = DUMMY_KEY.match(key.name)
        dtype = int(m.group(1), 16) if m else None
        label = sec.label(key.name)
        if dtype not in DUMMY_TYPES:
            problems.append((sec.name, label, "not a dummy entry: the keys are "
                                              "Dummy0001..Dummy0007"))
            continue
        if key.name != "Dummy%04X" % dtype:
            problems.append((sec.name, label, "spell it Dummy%04X (python canopen reads keys "
                                              "case-sensitively)" % dtype))
            continue
        if key.value not in ("0", "1"):
            problems.append((sec.name, label, "must be 0 or 1"))
        elif key.value == "1":
            declared.add(dtype)
    for dtype in DUMMY_TYPES:
        if not sec.has("Dummy%04X" % dtype):
            problems.append((sec.name, "Dummy%04X" % dtype,
                             "missing (python canopen reads Dummy0001..Dummy0007)"))
    return declared, problems


# ---------------------------------------------------------------------------------------------
# Generator
# ---------------------------------------------------------------------------------------------

class Entry:
    def __init__(self, index, sub, name, section):
        self.index = index
        self.sub = sub
        self.name = name
        self.section = section
        self.dtype = None
        self.flags = 0
        self.size = 0
        self.offset = 0
        self.default = b""
        self.limits = None
        self.hook = None
        self.stream = None  # the co_od_stream_t of a streamed DOMAIN (then hook is None)


def listed_objects(eds):
    """Indexes listed in the three object lists, with the section/key that lists them."""
    listed = {}
    for list_name in OBJECT_LISTS:
        sec = eds.section(list_name)
        if sec is None:
            continue
        count = read_count(eds, sec, "SupportedObjects", 0, MAX_LISTED)
        for n in range(1, count + 1):
            text = sec.get(str(n))
            if text is None:
                raise eds.error(list_name, str(n), "missing (SupportedObjects=%d)" % count)
            try:
                index = parse_index(text)
            except ValueError as e:
                raise eds.error(list_name, sec.label(str(n)), str(e))
            if index in listed:
                raise eds.error(list_name, sec.label(str(n)), "object listed twice")
            listed[index] = (list_name, str(n))
    return listed


def entry_size(eds, sec, dtype, default_len):
    """Bytes of an entry: fixed for numeric types; for strings and domains the ';size=N'
    directive of the section, or else the default's length."""
    name, size, kind = DATA_TYPES[dtype]
    if size is not None:
        return size
    if sec.size_directive is None:
        if default_len == 0:
            raise eds.error(sec.name, "DefaultValue", "%s with no default value and no ';size=N' "
                            "comment: its size is unknown" % name)
        if default_len > MAX_ENTRY_SIZE:
            raise eds.error(sec.name, "DefaultValue", "larger than %d bytes" % MAX_ENTRY_SIZE)
        return default_len
    key = ";size=" + sec.size_directive
    try:
        size, _ = parse_number(sec.size_directive)
    except ValueError as e:
        raise eds.error(sec.name, key, str(e))
    if not 1 <= size <= MAX_ENTRY_SIZE:
        raise eds.error(sec.name, key, "must be 1..%d" % MAX_ENTRY_SIZE)
    if size < default_len:
        raise eds.error(sec.name, key, "smaller than the default value (%d bytes)" % default_len)
    if kind == "us" and size % 2:
        raise eds.error(sec.name, key, "must be even: UNICODE_STRING characters take 2 bytes")
    return size


def encode_default(eds, sec, key, dtype):
    """The default value `key` of `sec` as stored in the data block (little-endian), and whether
    it is node-id relative."""
    name, size, kind = DATA_TYPES[dtype]
    text = sec.get(key)
    label = sec.label(key)
    if kind == "vs":
        try:
            return (text or "").encode("ascii"), False
        except UnicodeEncodeError:
            raise eds.error(sec.name, label, "VISIBLE_STRING must be ASCII")
    if kind == "us":
        return (text or "").encode("utf-16-le"), False
    if kind in ("os", "d"):
        try:
            return bytes.fromhex(text or ""), False
        except ValueError:
            raise eds.error(sec.name, label, "%s default must be hex bytes, e.g. 01A2FF" % name)
    if text is None or text == "":
        return bytes(size), False
    if kind == "f":
        if not FLOAT_NUMBER.match(text):
            raise eds.error(sec.name, label, "not a finite decimal number like -1.5e3")
        data = pack_real(float(text), size)
        if data is None:
            largest = REAL_FORMATS[size][1]
            raise eds.error(sec.name, label, "outside the range of %s (-%s..%s)"
                            % (name, largest, largest))
        return data, False
    try:
        value, is_hex, nodeid = parse_value(text)
    except ValueError as e:
        raise eds.error(sec.name, label, str(e))
    value, nodeid, where = resolve_node_id(eds, value, nodeid)
    low, high = type_range(dtype)
    if not low <= value <= high:
        raise eds.error(sec.name, label, "outside the range of %s (%d..%d)%s"
                        % (name, low, high, where))
    return (value & ((1 << (8 * size)) - 1)).to_bytes(size, "little"), nodeid


def resolve_node_id(eds, value, nodeid):
    """A $NODEID term of a DCF with a [DeviceComissioning] NodeID added in (CiA 306: $NODEID is
    that node-id): (value, still node-id relative, words for a message)."""
    if not nodeid or eds.node_id is None:
        return value, nodeid, ""
    return value + eds.node_id, False, " with [%s] NodeID=%d" % (COMMISSIONING, eds.node_id)


def pack_real(value, size):
    """The IEEE 754 bytes of a REAL32/REAL64 value, or None beyond the type's range (float() gives
    an infinity beyond REAL64's; struct refuses what rounds beyond REAL32's)."""
    if math.isinf(value):
        return None
    try:
        return struct.pack(REAL_FORMATS[size][0], value)
    except OverflowError:
        return None


def parse_limit(eds, sec, dtype, key):
    text = sec.get(key)
    if text is None or text == "":
        return None
    try:
        value, is_hex, nodeid = parse_value(text)
    except ValueError as e:
        raise eds.error(sec.name, sec.label(key), str(e))
    value = signed_limit(value, is_hex, dtype)
    value, nodeid, where = resolve_node_id(eds, value, nodeid)
    if nodeid:
        raise eds.error(sec.name, sec.label(key), "node-id relative limits cannot be represented")
    low, high = type_range(dtype)
    if not low <= value <= high:
        raise eds.error(sec.name, sec.label(key), "outside the range of %s%s"
                        % (DATA_TYPES[dtype][0], where))
    return value


def compact_value(eds, index, sub):
    """(section, key) of a compact array sub-entry's own default in [XXXXValue], or None."""
    values = eds.section("%04XValue" % index)
    return (values, str(sub)) if values is not None and values.has(str(sub)) else None


def default_key(eds, sec):
    """The key holding an entry's default, for generate and check alike: a DCF's ParameterValue,
    the device's configuration, over DefaultValue. A DownloadFile is refused."""
    if sec.get(DOMAIN_FILE_KEY):
        raise eds.error(sec.name, sec.label(DOMAIN_FILE_KEY), "a value in a file is not read: "
                        "write it as %s, hex bytes" % PARAMETER_VALUE)
    return PARAMETER_VALUE if sec.get(PARAMETER_VALUE) else "DefaultValue"


def build_entry(eds, sec, index, sub, fallback=None, value=None):
    """One table entry from a VAR section or a sub-section. `fallback` is the section whose keys
    a compact array's sub-entries inherit, `value` the (section, key) of the default when it is
    not default_key()'s (compact_value())."""
    src = fallback or sec
    value = value or (src, default_key(eds, src))
    name = src.get("ParameterName") or ""
    if fallback is not None:
        name = "%s %d" % (name, sub)
    entry = Entry(index, sub, name, sec.name)

    dtype_text = src.get("DataType")
    if dtype_text is None:
        raise eds.error(src.name, "DataType", "missing")
    try:
        dtype, _ = parse_number(dtype_text)
    except ValueError as e:
        raise eds.error(src.name, src.label("DataType"), str(e))
    if dtype not in DATA_TYPES or dtype not in CORE_TYPES:
        raise eds.error(src.name, src.label("DataType"), "unsupported data type")
    entry.dtype = dtype

    access = (src.get("AccessType") or "").lower()
    if access not in ACCESS_TYPES:
        raise eds.error(src.name, src.label("AccessType"),
                        "unknown access type (expected one of %s)" % ", ".join(ACCESS_TYPES))
    entry.access = access
    entry.flags = ACCESS_FLAGS[access]
    mapping_text = src.get("PDOMapping") or "0"
    try:
        mapping, _ = parse_number(mapping_text)
    except ValueError as e:
        raise eds.error(src.name, src.label("PDOMapping"), str(e))
    if mapping not in (0, 1):
        raise eds.error(src.name, src.label("PDOMapping"), "must be 0 or 1")
    if mapping:
        entry.flags |= PDO_FLAGS[access]

    entry.default, nodeid = encode_default(eds, *value, dtype)
    if nodeid:
        entry.flags |= NODEID
    entry.size = entry_size(eds, src, dtype, len(entry.default))
    entry.default = entry.default + bytes(entry.size - len(entry.default))

    if DATA_TYPES[dtype][2] not in ("u", "i", "b"):
        for key in ("LowLimit", "HighLimit"):
            if src.get(key):
                raise eds.error(src.name, src.label(key), "limits on %s are not enforced by "
                                "the core" % DATA_TYPES[dtype][0])
        return entry
    low = parse_limit(eds, src, dtype, "LowLimit")
    high = parse_limit(eds, src, dtype, "HighLimit")
    if low is not None or high is not None:
        type_low, type_high = type_range(dtype)
        low = type_low if low is None else low
        high = type_high if high is None else high
        if low > high:
            raise eds.error(src.name, src.label("LowLimit"), "LowLimit above HighLimit")
        entry.limits = (low, high)
    return entry


def object_type_of(eds, sec):
    text = sec.get("ObjectType")
    if text is None:
        return OBJ_VAR  # CiA 306: a missing ObjectType means VAR
    try:
        value, _ = parse_number(text)
    except ValueError as e:
        raise eds.error(sec.name, sec.label("ObjectType"), str(e))
    return value


def compact_entries(eds, sec, index):
    """CiA 306 compact storage of an ARRAY: CompactSubObj=N sub-entries sharing the object's
    keys, with optional per-sub-index defaults in [<index>Value]."""
    count = read_count(eds, sec, "CompactSubObj", 1, 254)
    first = Entry(index, 0, "Highest sub-index supported", sec.name)
    first.dtype = 0x05
    first.flags = READ
    first.access = "ro"
    first.size = 1
    first.default = bytes([count])
    entries = [first]
    for sub in range(1, count + 1):
        entries.append(build_entry(eds, sec, index, sub, fallback=sec,
                                   value=compact_value(eds, index, sub)))
    return entries


def commissioned_node_id(eds):
    """A DCF's [DeviceComissioning] NodeID, or None (an EDS, or a DCF that names no node-id: its
    $NODEID values stay node-id relative, as an EDS's)."""
    sec = eds.section(COMMISSIONING)
    if sec is None or not sec.get("NodeID"):
        return None
    try:
        node_id, _ = parse_number(sec.get("NodeID"))
    except ValueError as e:
        raise eds.error(sec.name, sec.label("NodeID"), str(e))
    if not NODE_ID_RANGE[0] <= node_id <= NODE_ID_RANGE[1]:
        raise eds.error(sec.name, sec.label("NodeID"), "must be %d..%d" % NODE_ID_RANGE)
    return node_id


def build_entries(eds):
    listed = listed_objects(eds)
    present = {}
    for sec in eds.sections.values():
        if OBJECT_SECTION.match(sec.name):
            present[int(sec.name, 16)] = sec
    for index, (list_name, key) in sorted(listed.items()):
        if index not in present:
            raise eds.error(list_name, "%s=0x%04X" % (key, index), "object has no section")
    for index, sec in sorted(present.items()):
        if index not in listed:
            raise eds.error(sec.name, None, "object not listed in any of %s" %
                            "/".join(OBJECT_LISTS))
    for sec in eds.sections.values():
        m = SUB_SECTION.match(sec.name)
        if m and int(m.group(1), 16) not in present:
            raise eds.error(sec.name, None, "sub-index of an object that has no section")

    entries = []
    for index, sec in sorted(present.items()):
        otype = object_type_of(eds, sec)
        subs = eds.sub_sections(index)
        if otype in (OBJ_VAR, OBJ_DOMAIN):
            if subs:
                raise eds.error(sec.name, sec.label("ObjectType"),
                                "a VAR has no sub-index sections")
            entries.append(build_entry(eds, sec, index, 0))
        elif otype == OBJ_ARRAY and sec.has("CompactSubObj"):
            entries.extend(compact_entries(eds, sec, index))
        elif otype in (OBJ_ARRAY, OBJ_RECORD):
            if 0 not in subs:
                raise eds.error(sec.name, None, "%s without a sub-index 0 section"
                                % OBJECT_TYPES[otype])
            for sub, sub_sec in sorted(subs.items()):
                entries.append(build_entry(eds, sub_sec, index, sub))
        else:
            raise eds.error(sec.name, sec.label("ObjectType"), "unsupported object type")
    return entries


HOOK_WORD = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
# A sub-index in a hooks file: 0x hex or decimal, ASCII digits only (int() also takes a sign,
# '_' between digits and other scripts' digits).
HOOK_SUB_INDEX = re.compile(r"(?:0x[0-9a-f]+|[0-9]+)\Z", re.IGNORECASE | re.ASCII)
STREAM_WORD = re.compile(r"^stream=([A-Za-z_][A-Za-z0-9_]*)$")


def make_stream(e, name):
    """A streamed DOMAIN: its value lives in the application (the co_od_stream_t `name`), so the
    entry has no bytes in the data block. Returns an error message, or None."""
    where = "0x%04X:0x%02X" % (e.index, e.sub)
    if DATA_TYPES[e.dtype][2] != "d":
        return "%s is not a DOMAIN: only a DOMAIN can be streamed" % where
    if e.hook is not None or (e.stream is not None and e.stream != name):
        return "%s already has hook %s" % (where, e.hook or e.stream)
    e.stream = name
    e.flags |= STREAM
    e.size = 0
    e.default = b""
    return None


def apply_hooks(entries, path):
    """Reads a hooks file: 'INDEX[:SUB] WORD...' or 'FIRST-LAST WORD...' (every object of the
    range) where WORD is zero-ok, process-data, the name of an extern const co_od_hook_t, or
    stream=NAME, NAME an extern const co_od_stream_t."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise EdsError(path, None, None, "cannot read: %s" % e)
    name = os.path.basename(path)

    def fail(number, message):
        return EdsError(path, None, None, "line %d: %s" % (number, message))

    for number, line in enumerate(lines, 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        words = text.split()
        where, actions = words[0], words[1:]
        if not actions:
            raise fail(number, "'%s' names no hook, zero-ok or process-data" % where)
        index_text, _, sub_text = where.partition(":")
        first_text, dash, last_text = index_text.partition("-")
        try:
            first = parse_index(first_text)
            last = parse_index(last_text) if dash else first
        except ValueError:
            raise fail(number, "'%s' is not a hex index like 0x203C or a range like "
                       "0x3000-0x31FF" % index_text)
        if last < first:
            raise fail(number, "range %s is backwards: write it as 0x%04X-0x%04X"
                       % (index_text, last, first))
        if dash and sub_text:
            raise fail(number, "'%s': a range of objects takes no sub-index" % where)
        sub = None
        if sub_text:
            if not HOOK_SUB_INDEX.match(sub_text):
                raise fail(number, "'%s' is not a sub-index (0x02 or 2)" % sub_text)
            sub = int(sub_text, 16) if sub_text.lower().startswith("0x") else int(sub_text, 10)
        targets = [e for e in entries
                   if first <= e.index <= last and (sub is None or e.sub == sub)]
        if not targets:
            if dash:
                raise fail(number, "no object of 0x%04X-0x%04X is in the EDS" % (first, last))
            what = "0x%04X" % first if sub is None else "0x%04X:0x%02X" % (first, sub)
            raise fail(number, "%s is not in the EDS" % what)
        for word in actions:
            stream = STREAM_WORD.match(word)
            if stream:
                for e in targets:
                    message = make_stream(e, stream.group(1))
                    if message:
                        raise fail(number, message)
            elif word in HOOK_FLAG_WORDS:
                for e in targets:
                    e.flags |= HOOK_FLAG_WORDS[word]
            elif HOOK_WORD.match(word):
                for e in targets:
                    if (e.hook is not None and e.hook != word) or e.stream is not None:
                        raise fail(number, "0x%04X:0x%02X already has hook %s"
                                   % (e.index, e.sub, e.hook or e.stream))
                    e.hook = word
            else:
                raise fail(number, "'%s' is neither zero-ok, process-data nor a C identifier"
                           % word)
    return name


def layout(entries):
    offset = 0
    for e in entries:
        e.offset = offset
        offset += e.size
    return offset


def c_flags(flags):
    names = [n for bit, n in FLAG_NAMES if flags & bit]
    return " | ".join(names) if names else "0"


def c_limit(value, dtype):
    if DATA_TYPES[dtype][2] == "i":
        if value == -(1 << 63):
            return "(uint64_t)INT64_MIN"
        return "(uint64_t)INT64_C(%d)" % value
    return "UINT64_C(%d)" % value


def c_string(text):
    """A C string literal of text: printable ASCII as is, quotes and backslashes escaped, any
    other byte of its UTF-8 form in octal."""
    out = []
    for byte in text.encode("utf-8"):
        ch = chr(byte)
        if ch in '"\\?':
            out.append("\\" + ch)
        elif 0x20 <= byte < 0x7F:
            out.append(ch)
        else:
            out.append("\\%03o" % byte)
    return '"%s"' % "".join(out)


def c_comment(text):
    return text.replace("*/", "* /").replace("/*", "/ *")


def dummy_types(eds):
    """co_od_t.dummy_types from [DummyUsage]: the data types 0002h..0007h an RPDO may map as
    dummies. The core maps whole bytes, so a BOOLEAN dummy (Dummy0001=1) is refused."""
    declared, problems = read_dummy_usage(eds)
    if problems:
        raise eds.error(*problems[0])
    if 0x01 in declared:
        sec = eds.section(DUMMY_SECTION)
        raise eds.error(sec.name, sec.label("Dummy0001"), "BOOLEAN dummies are not supported: "
                        "the core maps whole bytes")
    return sorted(declared)


def build_dictionary(eds):
    """The table entries and dummy types of an EDS, for generate and dump alike, so that both
    refuse the same files."""
    entries = build_entries(eds)
    if not entries:
        raise eds.error(None, None, "no objects")
    if len(entries) > 0xFFFF:
        raise eds.error(None, None, "more than 65535 entries")
    return entries, dummy_types(eds)


def render(entries, eds_name, prefix, data_size, hooks_name, dummies):
    guard = prefix.upper() + "_OD_H"
    macro = prefix.upper()
    banner = ("/* Generated from %s%s by tools/edstool.py: do not edit. */\n"
              % (eds_name, " and " + hooks_name if hooks_name else ""))
    h = [banner,
         "#ifndef %s\n#define %s\n\n" % (guard, guard),
         '#include "co/co_od.h"\n\n',
         "/* Bytes of a node's data block (co_node_config_t.od_data). */\n",
         "#define %s_OD_DATA_SIZE %du\n" % (macro, data_size),
         "/* Entries of the table, sub-indexes included. */\n",
         "#define %s_OD_ENTRIES %du\n\n" % (macro, len(entries)),
         "extern const co_od_t %s_od;\n" % prefix,
         "/* Default values, little-endian, node-id terms excluded. */\n",
         "extern const uint8_t %s_od_defaults[%s_OD_DATA_SIZE];\n\n" % (prefix, macro),
         "#endif\n"]

    producer = any(e.index == 0x1006 for e in entries)
    c = [banner, '#include "%s_od.h"\n\n' % prefix]
    if producer:
        c.append('#include "co/co_sync.h"\n\n')
    c.append("#include <stddef.h>\n#include <stdint.h>\n\n")
    hooks = sorted({e.hook for e in entries if e.hook})
    if hooks:
        c.append("/* Hooks named in %s, defined by the application. */\n" % hooks_name)
        for hook in hooks:
            c.append("extern const co_od_hook_t %s;\n" % hook)
        c.append("\n")
    streams = sorted({e.stream for e in entries if e.stream})
    if streams:
        c.append("/* Streamed DOMAINs named in %s, defined by the application. */\n" % hooks_name)
        for stream in streams:
            c.append("extern const co_od_stream_t %s;\n" % stream)
        c.append("\n")

    limits = {}  # (limits, signed) -> position in the array, in order of first use
    for e in entries:
        if e.limits is not None:
            limits.setdefault((e.limits, DATA_TYPES[e.dtype][2] == "i"), len(limits))
    if limits:
        c.append("static const co_od_limits_t %s_od_limits[] = {\n" % prefix)
        for n, ((low, high), signed) in enumerate(limits):
            dtype = 0x04 if signed else 0x07
            c.append("    {%s, %s}, /* %d: %d..%d */\n"
                     % (c_limit(low, dtype), c_limit(high, dtype), n, low, high))
        c.append("};\n\n")

    c.append("const uint8_t %s_od_defaults[%s_OD_DATA_SIZE] = {\n" % (prefix, macro))
    for e in entries:
        data = e.default
        for start in range(0, len(data), 16):
            chunk = ", ".join("0x%02X" % b for b in data[start:start + 16])
            label = "/* %04X:%02X */ " % (e.index, e.sub) if start == 0 else " " * 14
            c.append("    %s%s,\n" % (label, chunk))
    c.append("};\n\n")

    c.append("static const co_od_entry_t %s_od_entries[%s_OD_ENTRIES] = {\n" % (prefix, macro))
    for e in entries:
        limit = "NULL"
        if e.limits is not None:
            limit = "&%s_od_limits[%d]" % (prefix, limits[(e.limits,
                                                            DATA_TYPES[e.dtype][2] == "i")])
        hook = "&" + e.hook if e.hook else "&%s.hook" % e.stream if e.stream else "NULL"
        c.append("    /* %04X:%02X %s */\n" % (e.index, e.sub, c_comment(e.name)))
        c.append("    {0x%04X, 0x%02X, CO_DT_%s, %s, %d, %d, %s, %s},\n"
                 % (e.index, e.sub, DATA_TYPES[e.dtype][0], c_flags(e.flags), e.size, e.offset,
                    limit, hook))
    c.append("};\n\n")
    c.append("/* ParameterName of each entry, for diagnostics. */\n")
    c.append("static const char *const %s_od_names[%s_OD_ENTRIES] = {\n" % (prefix, macro))
    for e in entries:
        c.append("    %s,\n" % c_string(e.name))
    c.append("};\n\n")
    dummy = " | ".join("CO_OD_DUMMY(CO_DT_%s)" % DATA_TYPES[t][0] for t in dummies) or "0"
    # The code of streamed entries is linked only by a dictionary that has one (docs/sdo.md).
    streaming = "&co_od_streaming" if streams else "NULL"
    # So is the SYNC producer, by a dictionary with its period 1006h (docs/porting.md).
    producer = "co_sync_produce" if producer else "NULL"
    c.append('const co_od_t %s_od = {"%s", %s_od_entries, %s_OD_ENTRIES, %s_OD_DATA_SIZE,\n'
             "    %s_od_defaults, /* [DummyUsage] */ %s, %s_od_names,\n"
             "    /* streamed entries */ %s, /* SYNC producer */ %s};\n"
             % (prefix, prefix, prefix, macro, macro, prefix, dummy, prefix, streaming, producer))
    return "".join(h), "".join(c)


def write_if_changed(path, text):
    """Leaves an unchanged file untouched so the build does not recompile it (whatever the file
    holds: it is compared byte for byte)."""
    data = text.encode("utf-8")
    try:
        with open(path, "rb") as f:
            if f.read() == data:
                return
    except OSError:
        pass
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def omit_objects(entries, indexes):
    """The entries without the objects of indexes (a variant of a device that lacks them: an
    Altivar 31 before firmware V1.2 has no heartbeat objects), each of which must be in the EDS,
    so that a misspelt index is not silently a dictionary with the object still in it."""
    present = {e.index for e in entries}
    for index in indexes:
        if index not in present:
            raise UsageError("--omit %04Xh: no such object in the EDS" % index)
    kept = [e for e in entries if e.index not in indexes]
    if not kept:
        raise UsageError("--omit leaves no objects")
    return kept


def omit_index(text):
    try:
        return parse_index(text)
    except ValueError:
        raise argparse.ArgumentTypeError("%r is not an object index" % text)


def generate(args):
    if not re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", args.prefix):
        raise UsageError("--prefix %r is not a C identifier" % args.prefix)
    eds = parse_eds(args.eds)
    entries, dummies = build_dictionary(eds)
    entries = omit_objects(entries, args.omit)
    hooks_name = apply_hooks(entries, args.hooks) if args.hooks else None
    data_size = layout(entries)
    header, source = render(entries, os.path.basename(args.eds), args.prefix, data_size,
                            hooks_name, dummies)
    try:
        os.makedirs(args.out_dir, exist_ok=True)
        write_if_changed(os.path.join(args.out_dir, args.prefix + "_od.h"), header)
        write_if_changed(os.path.join(args.out_dir, args.prefix + "_od.c"), source)
    except OSError as e:
        raise UsageError("cannot write to %s: %s" % (args.out_dir, e.strerror))
    return EXIT_OK


# ---------------------------------------------------------------------------------------------
# Checker
# ---------------------------------------------------------------------------------------------

FILE_INFO_KEYS = ("FileName", "FileVersion", "FileRevision", "EDSVersion", "Description",
                  "CreationTime", "CreationDate", "CreatedBy")
DEVICE_INFO_KEYS = ("VendorName", "VendorNumber", "ProductName", "ProductNumber",
                    "RevisionNumber", "OrderCode", "SimpleBootUpMaster", "SimpleBootUpSlave",
                    "Granularity", "DynamicChannelsSupported", "GroupMessaging", "NrOfRXPDO",
                    "NrOfTXPDO", "LSS_Supported")
DEVICE_INFO_NUMBERS = ("VendorNumber", "ProductNumber", "RevisionNumber", "SimpleBootUpMaster",
                       "SimpleBootUpSlave", "Granularity", "DynamicChannelsSupported",
                       "GroupMessaging", "NrOfRXPDO", "NrOfTXPDO", "LSS_Supported")
BAUD_RATES = (10, 20, 50, 125, 250, 500, 800, 1000)
MANDATORY_OBJECTS = (0x1000, 0x1001, 0x1018)
# Keys of an object description as CiA 306 spells them; python canopen reads them case-sensitively.
OBJECT_KEYS = ("ParameterName", "ObjectType", "DataType", "AccessType", "DefaultValue",
               "PDOMapping", "LowLimit", "HighLimit", "SubNumber", "CompactSubObj",
               "ObjFlags", "ParameterValue", "Denotation", "StorageLocation")
NODE_IDS = (1, 127)


def is_cob_id_entry(index, sub):
    """COB-ID entries whose default must be a valid 11-bit identifier (CiA 301 7.5.2)."""
    if (index, sub) in ((0x1005, 0), (0x1012, 0), (0x1014, 0)):
        return True
    if 0x1200 <= index <= 0x12FF:
        return sub in (1, 2)
    return 0x1400 <= index <= 0x15FF and sub == 1 or 0x1800 <= index <= 0x19FF and sub == 1


class Checker:
    def __init__(self, path):
        self.path = path
        self.findings = []   # (severity, EdsError)
        self.eds = None

    def error(self, section, key, message):
        self.findings.append(("error", EdsError(self.path, section, key, message)))

    def warning(self, section, key, message):
        self.findings.append(("warning", EdsError(self.path, section, key, message)))

    def shared(self, rule, *args):
        """Runs a rule the generator applies too (it raises EdsError), so that check refuses what
        generate refuses, with the same message: a finding unless check's own rules already
        found an error at that section and key. Returns the rule's result, or None."""
        try:
            return rule(*args)
        except EdsError as e:
            if not any(severity == "error" and (f.section, f.key) == (e.section, e.key)
                       for severity, f in self.findings):
                self.findings.append(("error", e))
            return None

    def number(self, sec, key, required=False, node_id=None):
        """The integer value of a key, or None (missing or reported)."""
        text = sec.get(key)
        if text is None or text == "":
            if required:
                self.error(sec.name, key, "missing")
            return None
        try:
            return parse_number(text)[0]
        except ValueError as e:
            self.error(sec.name, sec.label(key), str(e))
            return None

    def run(self):
        try:
            self.eds = parse_eds(self.path)
        except EdsError as e:
            self.findings.append(("error", e))
            return
        self.check_file_info()
        self.check_device_info()
        self.check_dummy_usage()
        objects = self.check_object_lists()
        self.check_objects(objects)
        self.check_pdo_counts(objects)

    def check_file_info(self):
        sec = self.eds.section("FileInfo")
        if sec is None:
            self.error("FileInfo", None, "required section missing")
            return
        for key in FILE_INFO_KEYS:
            if not sec.has(key):
                self.warning("FileInfo", key, "missing")
        for key in ("FileVersion", "FileRevision"):
            value = self.number(sec, key)
            if value is not None and not 0 <= value <= 255:
                self.error("FileInfo", sec.label(key), "must be an UNSIGNED8")
        version = sec.get("EDSVersion")
        if version is not None and not re.match(r"^[0-9]+\.[0-9]+$", version):
            self.error("FileInfo", sec.label("EDSVersion"), "must read like 4.0")

    def check_device_info(self):
        sec = self.eds.section("DeviceInfo")
        if sec is None:
            self.error("DeviceInfo", None, "required section missing")
            return
        for key in DEVICE_INFO_KEYS:
            if not sec.has(key):
                self.warning("DeviceInfo", key, "missing")
        for key in DEVICE_INFO_NUMBERS:
            self.number(sec, key)
        supported = 0
        for rate in BAUD_RATES:
            key = "BaudRate_%d" % rate
            value = self.number(sec, key, required=True)
            if value is not None and value not in (0, 1):
                self.error("DeviceInfo", sec.label(key), "must be 0 or 1")
            supported += value == 1
        if supported == 0:
            self.error("DeviceInfo", "BaudRate_*", "no baud rate supported")

    def check_dummy_usage(self):
        for section, key, message in read_dummy_usage(self.eds)[1]:
            self.error(section, key, message)

    def check_object_lists(self):
        """{index: Section} of the object sections, after checking they match the lists."""
        present = {}
        for sec in self.eds.sections.values():
            if OBJECT_SECTION.match(sec.name):
                present[int(sec.name, 16)] = sec
        listed = {}
        for list_name in OBJECT_LISTS:
            sec = self.eds.section(list_name)
            if sec is None:
                if list_name == "MandatoryObjects":
                    self.error(list_name, None, "required section missing")
                continue
            count = self.shared(read_count, self.eds, sec, "SupportedObjects", 0, MAX_LISTED)
            numbered = [k.name for k in sec.keys.values() if k.name.lower() != "supportedobjects"]
            if count is not None:
                self.check_list_keys(sec, count, numbered)
            for key in numbered:
                try:
                    index = parse_index(sec.get(key))
                except ValueError as e:
                    self.error(list_name, sec.label(key), str(e))
                    continue
                if index in listed:
                    self.error(list_name, sec.label(key), "already listed in [%s]" % listed[index])
                    continue
                listed[index] = list_name
                if index not in present:
                    self.error(list_name, sec.label(key), "listed object has no section")
                expected = ("MandatoryObjects" if index in MANDATORY_OBJECTS else
                            "ManufacturerObjects" if 0x2000 <= index <= 0x5FFF else
                            "OptionalObjects")
                if list_name != expected:
                    self.error(list_name, sec.label(key), "belongs in [%s]" % expected)
        for index in MANDATORY_OBJECTS:
            if index not in present:
                self.error("%04X" % index, None, "mandatory object missing")
        for index, sec in sorted(present.items()):
            if index not in listed:
                self.error(sec.name, None, "object not listed in any of %s"
                           % "/".join(OBJECT_LISTS))
        for sec in self.eds.sections.values():
            m = SUB_SECTION.match(sec.name)
            if m and int(m.group(1), 16) not in present:
                self.error(sec.name, None, "sub-index of an object that has no section")
        return present

    def check_list_keys(self, sec, count, numbered):
        """Keys 1..count present (one finding per run of missing keys), and no other."""
        first_missing = None
        for n in range(1, count + 2):
            if n <= count and not sec.has(str(n)):
                first_missing = first_missing or n
            elif first_missing is not None:
                keys = "%d..%d" % (first_missing, n - 1) if n - 1 > first_missing else str(n - 1)
                self.error(sec.name, keys, "missing (SupportedObjects=%d)" % count)
                first_missing = None
        wanted = {str(n) for n in range(1, count + 1)}
        for key in numbered:
            if key not in wanted:
                self.error(sec.name, key, "beyond SupportedObjects=%d" % count)

    def check_keys_spelling(self, sec):
        canonical = {k.lower(): k for k in OBJECT_KEYS}
        for key in sec.keys.values():
            right = canonical.get(key.name.lower())
            if right is not None and key.name != right:
                self.error(sec.name, key.name, "spell it %s (python canopen reads keys "
                           "case-sensitively)" % right)

    def check_objects(self, objects):
        for index, sec in sorted(objects.items()):
            self.check_keys_spelling(sec)
            if not sec.get("ParameterName"):
                self.error(sec.name, "ParameterName", "missing")
            otype = self.shared(object_type_of, self.eds, sec)
            if otype is None:
                continue
            if otype not in OBJECT_TYPES:
                self.error(sec.name, sec.label("ObjectType"), "unknown object type")
                continue
            subs = self.eds.sub_sections(index)
            for sub_sec in subs.values():
                self.check_keys_spelling(sub_sec)
                if not sub_sec.name[4:7] == "sub":
                    self.error(sub_sec.name, None, "write the section name as %ssub%s "
                               "(python canopen only reads 'sub')"
                               % (sub_sec.name[:4], sub_sec.name[7:]))
            if otype in (OBJ_DEFTYPE, OBJ_DEFSTRUCT):
                self.warning(sec.name, sec.label("ObjectType"),
                             "python canopen ignores %s objects" % OBJECT_TYPES[otype])
            elif otype in (OBJ_VAR, OBJ_DOMAIN, OBJ_NULL):
                if subs:
                    self.error(sec.name, sec.label("ObjectType"),
                               "a %s has no sub-index sections" % OBJECT_TYPES[otype])
                if sec.has("SubNumber"):
                    self.error(sec.name, sec.label("SubNumber"), "only ARRAY and RECORD have it")
                self.check_variable(sec, index, 0)
            elif otype == OBJ_ARRAY and sec.has("CompactSubObj"):
                self.check_compact(sec, index, subs)
            else:
                self.check_structured(sec, index, otype, subs)

    def check_structured(self, sec, index, otype, subs):
        count = self.number(sec, "SubNumber", required=True)
        if count is not None and count != len(subs):
            self.error(sec.name, sec.label("SubNumber"), "%d sub-index sections found" % len(subs))
        for key in ("DataType", "AccessType", "DefaultValue", "PDOMapping"):
            if sec.has(key):
                self.warning(sec.name, sec.label(key), "ignored on an %s: belongs in the "
                             "sub-index sections" % OBJECT_TYPES[otype])
        if 0 not in subs:
            self.error(sec.name, None, "%s without a sub-index 0 section" % OBJECT_TYPES[otype])
        for sub, sub_sec in sorted(subs.items()):
            self.check_variable(sub_sec, index, sub)
        if 0 in subs:
            self.check_highest_sub(subs[0], max(subs))
        if otype == OBJ_ARRAY:
            types = {s.get("DataType") for n, s in subs.items() if n > 0}
            if len(types) > 1:
                self.error(sec.name, None, "ARRAY sub-indexes 1.. differ in DataType")

    def check_highest_sub(self, sub0, highest):
        dtype = self.number(sub0, "DataType")
        if dtype is not None and dtype != 0x05:
            self.error(sub0.name, sub0.label("DataType"), "sub-index 0 must be UNSIGNED8")
        text = sub0.get("DefaultValue")
        if text is None:
            self.error(sub0.name, "DefaultValue", "missing: must be the highest sub-index (%d)"
                       % highest)
            return
        try:
            value, _, nodeid = parse_value(text)
        except ValueError:
            return  # reported by check_variable
        # A writable sub-index 0 counts the entries in use (1003h errors, PDO mappings, CiA 301
        # 7.4.8): up to the highest sub-index. A read-only one is the highest sub-index.
        writable = (sub0.get("AccessType") or "").lower() not in ("ro", "const")
        if nodeid or value > highest or (not writable and value != highest):
            self.error(sub0.name, sub0.label("DefaultValue"), "%s sub-index present is %d"
                       % ("highest" if not writable else "above the highest", highest))
        limit = self.value_of(sub0, "HighLimit", 0x05) if writable else None
        if limit is not None and limit[0] > highest:
            self.error(sub0.name, sub0.label("HighLimit"), "highest sub-index present is %d"
                       % highest)

    def check_compact(self, sec, index, subs):
        count = self.shared(read_count, self.eds, sec, "CompactSubObj", 1, 254)
        if subs:
            self.error(sec.name, sec.label("CompactSubObj"),
                       "a compact array has no sub-index sections")
        dtype = self.check_variable(sec, index, 1)
        if dtype is None or count is None:
            return
        for sub in range(1, count + 1):
            value = compact_value(self.eds, index, sub)
            if value is not None:
                self.encoded_default(sec, dtype, value)

    def check_variable(self, sec, index, sub):
        """Checks a VAR or a sub-section; returns its data type, or None if unusable."""
        if not sec.get("ParameterName"):
            self.error(sec.name, "ParameterName", "missing")
        dtype = self.number(sec, "DataType", required=True)
        if dtype is not None and dtype not in DATA_TYPES:
            self.error(sec.name, sec.label("DataType"), "unknown data type")
            dtype = None
        access = sec.get("AccessType")
        if access is None:
            self.error(sec.name, "AccessType", "missing")
        elif access.lower() not in ACCESS_TYPES:
            self.error(sec.name, sec.label("AccessType"),
                       "unknown access type (expected one of %s)" % ", ".join(ACCESS_TYPES))
        mapping = self.number(sec, "PDOMapping")
        if mapping is not None and mapping not in (0, 1):
            self.error(sec.name, sec.label("PDOMapping"), "must be 0 or 1")
        if dtype is None:
            return None
        kind = DATA_TYPES[dtype][2]
        if kind in ("vs", "os", "us", "d", "t", "f"):
            self.check_non_integer(sec, dtype, mapping)
            return dtype
        key = self.shared(default_key, self.eds, sec)
        default = self.value_of(sec, key, dtype) if key else None
        low = self.value_of(sec, "LowLimit", dtype)
        high = self.value_of(sec, "HighLimit", dtype)
        # A DCF's $NODEID is its own node-id (CiA 306); an EDS's, any node-id it may be given.
        node_ids = NODE_IDS if self.eds.node_id is None else (self.eds.node_id,)
        for node_id in node_ids:
            d, lo, hi = (None if v is None else v[0] + (node_id if v[1] else 0)
                         for v in (default, low, high))
            where = ""
            if any(v and v[1] for v in (default, low, high)):
                where = resolve_node_id(self.eds, 0, True)[2] or " with node-id %d" % node_id
            type_low, type_high = type_range(dtype)
            for name, v in ((key, d), ("LowLimit", lo), ("HighLimit", hi)):
                if v is not None and not type_low <= v <= type_high:
                    self.error(sec.name, sec.label(name), "outside the range of %s (%d..%d)%s"
                               % (DATA_TYPES[dtype][0], type_low, type_high, where))
            if lo is not None and hi is not None and lo > hi:
                self.error(sec.name, sec.label("LowLimit"), "above HighLimit%s" % where)
            if d is not None and lo is not None and d < lo:
                self.error(sec.name, sec.label(key), "below LowLimit%s" % where)
            if d is not None and hi is not None and d > hi:
                self.error(sec.name, sec.label(key), "above HighLimit%s" % where)
            if d is not None and is_cob_id_entry(index, sub):
                self.check_cob_id(sec, key, d, where)
            if not where:
                break
        self.encoded_default(sec, dtype)
        return dtype

    def encoded_default(self, sec, dtype, value=None):
        """The default value as generate stores it, or None: generate's rules for the default
        (DefaultValue, a DCF's ParameterValue, or `value` as build_entry() takes it) and the size
        of an entry. TIME_OF_DAY and TIME_DIFFERENCE have no encoding (neither the core nor
        generate supports them)."""
        if DATA_TYPES[dtype][2] == "t":
            return None
        key = self.shared(default_key, self.eds, sec)
        if value is None and key is None:
            return None
        encoded = self.shared(encode_default, self.eds, *(value or (sec, key)), dtype)
        if encoded is None:
            return None
        self.shared(entry_size, self.eds, sec, dtype, len(encoded[0]))
        return encoded[0]

    def value_of(self, sec, key, dtype):
        """(value, node-id relative) of a numeric key, or None."""
        text = sec.get(key)
        if text is None or text == "":
            return None
        try:
            value, is_hex, nodeid = parse_value(text)
        except ValueError as e:
            self.error(sec.name, sec.label(key), str(e))
            return None
        if text.replace(" ", "").upper() == "$NODEID":
            self.error(sec.name, sec.label(key),
                       "python canopen cannot read a bare $NODEID: write $NODEID+0")
        if key in ("DefaultValue", PARAMETER_VALUE):
            name, size, kind = DATA_TYPES[dtype]
            if kind == "i" and is_hex and value > type_range(dtype)[1]:
                self.error(sec.name, sec.label(key), "hex default above the %s maximum (python "
                           "canopen does not read it as negative): write it in decimal" % name)
                return None
        else:
            value = signed_limit(value, is_hex, dtype)
        return value, nodeid

    def check_cob_id(self, sec, key, value, where):
        # CiA 301 7.5.2.5: bit 31 valid, bit 30 RTR (PDO) or frame (SYNC), bit 29 frame (29-bit
        # identifier), bits 28..11 zero for an 11-bit identifier.
        if value & (1 << 29):
            self.error(sec.name, sec.label(key),
                       "bit 29 set: 29-bit identifiers are not supported%s" % where)
        elif value & 0x1FFFF800:
            self.error(sec.name, sec.label(key),
                       "0x%X is not an 11-bit identifier%s" % (value & 0x1FFFFFFF, where))

    def check_non_integer(self, sec, dtype, mapping):
        name, _, kind = DATA_TYPES[dtype]
        for key in ("LowLimit", "HighLimit"):
            if sec.get(key):
                self.warning(sec.name, sec.label(key), "limits on %s are not checked" % name)
        default = self.encoded_default(sec, dtype)
        if mapping == 1:
            if kind == "d":
                self.error(sec.name, sec.label("PDOMapping"), "a DOMAIN cannot be PDO-mapped")
            elif default is not None and len(default) > 8:
                self.error(sec.name, sec.label("PDOMapping"),
                           "%d bits: more than a PDO's 64" % (8 * len(default)))

    def check_pdo_counts(self, objects):
        sec = self.eds.section("DeviceInfo")
        if sec is None:
            return
        for key, first, last, mapping in (("NrOfRXPDO", 0x1400, 0x15FF, 0x200),
                                          ("NrOfTXPDO", 0x1800, 0x19FF, 0x200)):
            comm = [i for i in objects if first <= i <= last]
            value = self.number(sec, key)
            if value is not None and value != len(comm):
                self.error("DeviceInfo", sec.label(key), "%d objects %04X..%04X present"
                           % (len(comm), first, last))
            for i in comm:
                if i + mapping not in objects:
                    self.error("%04X" % i, None, "PDO without its mapping object %04X"
                               % (i + mapping))

    def report(self, strict, out):
        errors = 0
        for severity, finding in self.findings:
            if severity == "warning":
                finding.message = "warning: " + finding.message
            out.write("%s\n" % finding)
            errors += severity == "error" or strict
        return errors


def check(args):
    failed = False
    for path in args.eds:
        checker = Checker(path)
        checker.run()
        if checker.report(args.strict, sys.stdout):
            failed = True
    return EXIT_INVALID if failed else EXIT_OK


# ---------------------------------------------------------------------------------------------
# Dump
# ---------------------------------------------------------------------------------------------

def shown_default(e):
    kind = DATA_TYPES[e.dtype][2]
    if kind == "vs":
        return '"%s"' % e.default.rstrip(b"\0").decode("ascii")
    if kind == "us":
        return '"%s"' % e.default.decode("utf-16-le").rstrip("\0")
    if kind in ("os", "d"):
        return e.default.hex().upper() or "(empty)"
    if kind == "f":
        return repr(struct.unpack("<f" if e.size == 4 else "<d", e.default)[0])
    value = int.from_bytes(e.default, "little", signed=kind == "i")
    text = "0x%0*X" % (2 * e.size, value) if kind == "u" and value > 9 else str(value)
    return "$NODEID+" + text if e.flags & NODEID else text


def dump(args):
    entries, _ = build_dictionary(parse_eds(args.eds))
    if args.hooks:
        apply_hooks(entries, args.hooks)
    out = sys.stdout
    out.write("| Index | Sub | Name | Type | Access | PDO | Default | Limits | Size |\n")
    out.write("|---|---|---|---|---|---|---|---|---|\n")
    for e in entries:
        pdo = "/".join(n for bit, n in ((TPDO, "T"), (RPDO, "R")) if e.flags & bit) or "-"
        limits = "%d..%d" % e.limits if e.limits else ""
        if e.flags & ZERO_OK:
            limits += " or 0"
        if e.flags & PROCESS:
            limits += " (process data)"
        if e.hook:
            limits += " (hook %s)" % e.hook
        if e.stream:
            limits += " (stream %s)" % e.stream
        out.write("| %04Xh | %d | %s | %s | %s | %s | %s | %s | %d |\n"
                  % (e.index, e.sub, e.name.replace("|", "/"), DATA_TYPES[e.dtype][0], e.access,
                     pdo, shown_default(e).replace("|", "/"), limits.strip(), e.size))
    return EXIT_OK


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------

class UsageError(Exception):
    pass


class Parser(argparse.ArgumentParser):
    def error(self, message):
        self.print_usage(sys.stderr)
        sys.stderr.write("%s: error: %s\n" % (self.prog, message))
        sys.exit(EXIT_USAGE)


def make_parser():
    parser = Parser(
        description="Generate the CANopen core's object dictionary table from a CiA 306 EDS "
                    "or DCF (its ParameterValues as the defaults, $NODEID its "
                    "[DeviceComissioning] NodeID), or check EDS files.",
        epilog="Exit codes: 0 success, 1 invalid input (messages name file, section and key), "
               "2 usage error. See docs/eds-generator.md.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    gen = sub.add_parser(
        "generate", help="write PREFIX_od.h and PREFIX_od.c from an EDS or a DCF",
        description="Write DIR/PREFIX_od.h and DIR/PREFIX_od.c: the const co_od_t PREFIX_od "
                    "(sorted entries, default-value image, limits, flags) for include/co/co_od.h. "
                    "Files whose content would not change are left untouched.")
    gen.add_argument("eds", metavar="EDS", help="the EDS file, or a DCF")
    gen.add_argument("--prefix", required=True, metavar="NAME",
                     help="C identifier prefixing every generated name (NAME_od, NAME_OD_...)")
    gen.add_argument("--out-dir", required=True, metavar="DIR", help="output directory")
    gen.add_argument("--hooks", metavar="FILE",
                     help="hooks file: lines 'INDEX[:SUB] WORD...', WORD is zero-ok, process-data, "
                          "the name of an extern const co_od_hook_t, or stream=NAME, NAME an "
                          "extern const co_od_stream_t (a streamed DOMAIN)")
    gen.add_argument("--omit", nargs="+", default=[], type=omit_index, metavar="INDEX",
                     help="leave these objects (hex indexes, e.g. 0x1016) out of the dictionary: "
                          "a variant of the device that lacks them")
    gen.set_defaults(run=generate)
    chk = sub.add_parser(
        "check", help="check EDS files against CiA 306",
        description="Check EDS files against CiA 306 and what python canopen needs. Prints one "
                    "line per finding ('file: [section] key: message', the message of a warning "
                    "starting 'warning: '); exits 1 if any error (or, with --strict, any warning).")
    chk.add_argument("eds", metavar="EDS", nargs="+", help="EDS files")
    chk.add_argument("--strict", action="store_true", help="treat warnings as errors")
    chk.set_defaults(run=check)
    dmp = sub.add_parser(
        "dump", help="list the objects of an EDS as a Markdown table",
        description="Print every entry the generator would produce as a Markdown table: index, "
                    "sub-index, name, type, access, PDO direction, default, limits, size.")
    dmp.add_argument("eds", metavar="EDS", help="the EDS file")
    dmp.add_argument("--hooks", metavar="FILE",
                     help="show the hooks, zero-ok and process-data of this file")
    dmp.set_defaults(run=dump)
    return parser


def main(argv=None):
    parser = make_parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except UsageError as e:
        sys.stderr.write("%s: error: %s\n" % (parser.prog, e))
        return EXIT_USAGE
    except EdsError as e:
        sys.stderr.write("%s\n" % e)
        return EXIT_INVALID


if __name__ == "__main__":
    # Names and values from the EDS reach stdout whatever its encoding (stderr already escapes).
    sys.stdout.reconfigure(errors="backslashreplace")
    sys.exit(main())
