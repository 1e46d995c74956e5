#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Runs one check on every *.eds of a directory, found when the test runs so a new EDS is never
skipped; fails when there is none.

  every_eds.py check DIR     tools/edstool.py check --strict on every file
  every_eds.py canopen DIR   python canopen's import_od on every file, under 'python -W error',
                             failing on any warning it logs too"""
import glob
import logging
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
EDSTOOL = os.path.join(HERE, "..", "..", "tools", "edstool.py")


def run_check(files):
    return subprocess.call([sys.executable, EDSTOOL, "check", "--strict"] + files)


class Recorder(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.records = []

    def emit(self, record):
        self.records.append(record)


def run_canopen(files):
    try:
        import canopen
    except ImportError as e:
        print("FAIL: python canopen cannot be imported by %s (%s): run scripts/setup and configure "
              "with -DPython3_EXECUTABLE=$PWD/.venv/bin/python" % (sys.executable, e))
        return 1
    if not sys.warnoptions or "error" not in sys.warnoptions:
        print("FAIL: run under 'python -W error' so import warnings are errors")
        return 1
    recorder = Recorder()
    logging.getLogger("canopen").addHandler(recorder)
    failed = 0
    for path in files:
        problems = import_problems(canopen, recorder, path)
        for problem in problems:
            print("FAIL: %s: %s" % (path, problem))
        if not problems:
            print("ok: %s" % path)
        failed |= bool(problems)
    return failed


def import_problems(canopen, recorder, path):
    recorder.records.clear()
    try:
        od = canopen.import_od(path, 1)
    except Exception as e:  # any failure of the importer is the finding
        return ["%s: %s" % (type(e).__name__, e)]
    problems = ["canopen logged: %s" % r.getMessage() for r in recorder.records]
    lost = ["%04X:%02X" % (var.index, var.subindex) for var in iter_variables(od)
            if var.default is None and getattr(var, "default_raw", None) is not None]
    if lost:
        problems.append("canopen could not read the DefaultValue of %s" % ", ".join(lost))
    return problems


def iter_variables(od):
    import canopen.objectdictionary as objd
    for obj in od.values():
        if isinstance(obj, objd.ODVariable):
            yield obj
        else:
            yield from obj.values()


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("check", "canopen"):
        print(__doc__)
        return 2
    files = sorted(glob.glob(os.path.join(sys.argv[2], "*.eds")))
    if not files:
        print("FAIL: no *.eds in %s" % sys.argv[2])
        return 1
    return run_check(files) if sys.argv[1] == "check" else run_canopen(files)


if __name__ == "__main__":
    sys.exit(main())
