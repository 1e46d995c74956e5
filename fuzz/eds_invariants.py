# SPDX-License-Identifier: Apache-2.0
"""What tools/edstool.py must hold for any input file, whatever its bytes: the invariants of the
EDS parser's fuzzing, shared by the atheris harness (fuzz/fuzz_eds.py) and the deterministic
mutation test (tests/tools/test_edstool.py). A broken invariant raises AssertionError."""
import contextlib
import io
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
import edstool  # noqa: E402

# Refusals of generate for what CiA 306 allows but the core does not support: check --strict
# need not refuse these.
UNSUPPORTED = ("unsupported data type", "unsupported object type",
               "node-id relative limits cannot be represented",
               "BOOLEAN dummies are not supported: the core maps whole bytes")


def run_in_process(*args):
    """edstool's exit code, stdout and stderr for one command line."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = edstool.main(list(args))
    return code, out.getvalue(), err.getvalue()


def check_table(path):
    """The table generate writes for a file it accepts is one the core can search: keys strictly
    ascending (co_od_find is a binary search), data offsets contiguous, each default no larger
    than its entry."""
    entries, _ = edstool.build_dictionary(edstool.parse_eds(path))
    keys = [(e.index, e.sub) for e in entries]
    assert keys == sorted(set(keys)), "table keys not strictly ascending"
    offset = 0
    for e in entries:
        assert e.offset == 0, "entry laid out before layout()"
        assert 0 < e.size <= edstool.MAX_ENTRY_SIZE, "%04X:%02X size %d" % (e.index, e.sub, e.size)
        assert len(e.default) <= e.size, "%04X:%02X default larger than entry" % (e.index, e.sub)
        offset += e.size
    assert edstool.layout(entries) == offset


def check_commands(path, out_dir):
    """check --strict, generate and dump on one file: each ends with exit code 0 (accepted) or 1
    (refused), never an exception; check prints only findings about the file; a refusal is the
    same one line from generate and dump, which check --strict refuses too unless it is a
    feature the core lacks; an accepted file gives a searchable table."""
    check = run_in_process("check", "--strict", path)
    generate = run_in_process("generate", path, "--prefix", "f", "--out-dir", out_dir)
    dump = run_in_process("dump", path)
    assert check[0] in (0, 1), "check exit %d" % check[0]
    assert all(line.startswith(path + ": ") for line in check[1].splitlines()), check[1]
    assert generate[0] in (0, 1), "generate exit %d: %s" % (generate[0], generate[2])
    assert (dump[0], dump[2]) == (generate[0], generate[2]), "dump and generate disagree"
    if generate[0] == 1:
        assert re.match(r"\A%s: [^\n]*\n\Z" % re.escape(path), generate[2]), generate[2]
        if not generate[2].rstrip().endswith(UNSUPPORTED):
            assert check[0] == 1, "generate refuses what check accepts: " + generate[2]
    else:
        check_table(path)
