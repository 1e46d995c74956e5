#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The configure step of scripts/run-tests and scripts/demo (scripts/configure-build), on the
# build directories a person may already have (issue 27):
#   - one made by a plain `cmake -S . -B DIR` (Unix Makefiles) is configured with its own
#     generator, not refused for not being Ninja;
#   - a new one gets Ninja;
#   - one cmake refuses (made from another source tree) gives cmake's message and one line naming
#     it, exit 1: from scripts/run-tests as from scripts/demo, never a Python traceback.
# Configured without tests and install rules, so that each configure takes a second or two.
# Usage: test_configure_build.sh SOURCE_DIR
set -euo pipefail
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fast=(-DCO_BUILD_TESTS=OFF -DCO_INSTALL=OFF)
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
generator_of() { sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' "$1/CMakeCache.txt"; }

# A plain cmake build directory: Unix Makefiles, no build type.
cmake -S "$src" -B "$work/make" -G "Unix Makefiles" "${fast[@]}" >"$work/log" 2>&1 ||
  { cat "$work/log"; fail "cmake could not configure $work/make"; }
"$src/scripts/configure-build" "$work/make" -DCMAKE_BUILD_TYPE=Debug "${fast[@]}" >"$work/log" 2>&1 ||
  { cat "$work/log"; fail "configure-build refused a Makefiles build directory"; }
[ "$(generator_of "$work/make")" = "Unix Makefiles" ] ||
  fail "the Makefiles build directory changed generator"
grep -qx 'CMAKE_BUILD_TYPE:STRING=Debug' "$work/make/CMakeCache.txt" ||
  fail "the arguments were not applied"
echo "ok: a Makefiles build directory is configured with its own generator"

"$src/scripts/configure-build" "$work/new" "${fast[@]}" >"$work/log" 2>&1 ||
  { cat "$work/log"; fail "configure-build could not configure a new build directory"; }
[ "$(generator_of "$work/new")" = Ninja ] ||
  fail "a new build directory is not Ninja: $(generator_of "$work/new")"
echo "ok: a new build directory gets Ninja"

# A build directory of another project: cmake refuses it.
mkdir -p "$work/other"
echo 'cmake_minimum_required(VERSION 3.20)
project(other NONE)' >"$work/other/CMakeLists.txt"
cmake -S "$work/other" -B "$work/foreign" >/dev/null 2>&1 || fail "cmake could not configure $work/other"
if "$src/scripts/configure-build" "$work/foreign" >"$work/log" 2>&1; then
  fail "configure-build accepted the build directory of another source tree"
fi
grep -q "^configure-build: cmake could not configure $work/foreign" "$work/log" ||
  { cat "$work/log"; fail "no line naming the directory"; }
echo "ok: configure-build names a build directory cmake refuses"

# The scripts stop at that line (the focused run of run-tests, the demo before anything runs).
for script in run-tests demo; do
  status=0
  BUILD_DIR=$work/foreign "$src/scripts/$script" >"$work/log" 2>&1 || status=$?
  [ "$status" -ne 0 ] || fail "scripts/$script succeeded with a foreign build directory"
  ! grep -q Traceback "$work/log" || { cat "$work/log"; fail "scripts/$script: a traceback"; }
  grep -q "$work/foreign" "$work/log" ||
    { cat "$work/log"; fail "scripts/$script does not name the directory"; }
  echo "ok: scripts/$script stops with a message naming the directory (exit $status)"
done
