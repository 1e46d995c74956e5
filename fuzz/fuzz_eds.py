#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""atheris harness of the EDS parser and generator (tools/edstool.py, docs/fuzzing.md): the input
is a whole EDS file, run through check --strict, generate and dump in this process and held to
the invariants of fuzz/eds_invariants.py. Arguments are libFuzzer's:
    fuzz/fuzz_eds.py -runs=0 fuzz/corpus/eds              replay the corpus (ctest, label fuzz)
    fuzz/fuzz_eds.py -max_total_time=60 -dict=fuzz/eds.dict NEW fuzz/corpus/eds"""
import os
import sys
import tempfile

import atheris

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
with atheris.instrument_imports(include=["edstool", "eds_invariants"]):
    import eds_invariants

WORK = tempfile.mkdtemp(prefix="fuzz_eds.")
PATH = os.path.join(WORK, "input.eds")
OUT_DIR = os.path.join(WORK, "gen")


def test_one_input(data):
    with open(PATH, "wb") as f:
        f.write(data)
    eds_invariants.check_commands(PATH, OUT_DIR)


def main():
    atheris.Setup(sys.argv, test_one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
