# SPDX-License-Identifier: Apache-2.0
"""tools/vcan-run on this host, its sandbox booted for real (ctest tools_vcan_run): the command's
exit status and vcan0; the caller's stdin, piped (byte for byte, to its end) and typed on a
terminal (an interactive shell with ^C and job control); --forward from the host's loopback to a
server in the guest; and a host made to look like one whose XSAVE area is larger than User-Mode
Linux's, as the CPUs with AMX that CI runs on, where the sandbox must boot all the same and say how,
or, where the wrapper that makes that possible cannot be had, say why it cannot.

On a host with vcan of its own the command runs there and the sandbox's own checks do not apply.
Each test boots the sandbox once (3-5 s)."""

import os
import pty
import re
import select
import socket
import subprocess
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
VCAN_RUN = str(ROOT / "tools" / "vcan-run")
UML = ["--mode", "uml"]


def vcan_run(*args, input=None, env=None):
    """vcan-run with ARGS; its stdin is `input` (bytes, piped), or /dev/null."""
    return subprocess.run([VCAN_RUN, *args], input=input,
                          stdin=subprocess.DEVNULL if input is None else None, capture_output=True,
                          timeout=120, env=env)


def test_exit_status_and_vcan0():
    result = vcan_run(*UML, "sh", "-c", "ip -br link show vcan0; exit 7")
    assert result.returncode == 7, result.stderr
    assert re.match(rb"vcan0\s+UNKNOWN\s+<NOARP,UP,LOWER_UP>", result.stdout), result.stdout


def test_piped_stdin_arrives_byte_for_byte_to_its_end():
    data = bytes(range(256)) * 64 + b"\r\n\x03\x04\x1a\x00 last line without newline"
    proc = vcan_run(*UML, "sh", "-c", "od -An -v -tx1 | tr -d ' \\n'", input=data)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.decode() == data.hex()


def test_piped_script_runs_in_a_shell():
    proc = vcan_run(*UML, "bash", input=b"ip -br link show vcan1\nexit 3\n")
    assert proc.returncode == 3, proc.stderr
    assert proc.stdout.startswith(b"vcan1 ")


def test_empty_stdin_ends_at_once():
    proc = vcan_run(*UML, "--timeout", "60", "cat", input=b"")
    assert (proc.returncode, proc.stdout) == (0, b""), proc.stderr


class Terminal:
    """vcan-run on a pseudo-terminal, as a person types into it."""

    def __init__(self, *args):
        self.pid, self.fd = pty.fork()
        if self.pid == 0:
            os.execv(VCAN_RUN, [VCAN_RUN, *args])
        self.seen = b""

    def expect(self, text, timeout):
        deadline = time.monotonic() + timeout
        while text not in self.seen:
            left = deadline - time.monotonic()
            assert left > 0, f"no {text!r} within {timeout} s; the terminal shows {self.seen!r}"
            if select.select([self.fd], [], [], left)[0]:
                try:
                    self.seen += os.read(self.fd, 4096)
                except OSError:  # the other side closed
                    break
        assert text in self.seen, f"no {text!r}; the terminal shows {self.seen!r}"
        self.seen = self.seen[self.seen.index(text) + len(text):]

    def type(self, text):
        os.write(self.fd, text)

    def exit_status(self, timeout):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                return os.waitstatus_to_exitcode(status)
            try:
                os.read(self.fd, 4096)
            except OSError:
                time.sleep(0.05)
        os.kill(self.pid, 9)
        raise AssertionError(f"vcan-run did not exit within {timeout} s")


def test_interactive_shell_on_a_terminal():
    term = Terminal(*UML, "bash", "--norc", "--noprofile", "-i")
    term.expect(b"# ", 60)
    term.type(b"echo typed$((6*7)); tty; ip -br link show vcan0\n")
    term.expect(b"typed42\r\n/dev/tty1\r\nvcan0 ", 10)
    term.expect(b"# ", 10)
    term.type(b"sleep 100\n")
    term.expect(b"sleep 100\r\n", 10)
    time.sleep(0.5)  # bash has started sleep: ^C must reach it, not the line being typed
    started = time.monotonic()
    term.type(b"\x03")
    term.expect(b"^C", 5)
    term.expect(b"# ", 5)
    assert time.monotonic() - started < 5
    term.type(b"sleep 100 &\njobs\n")
    term.expect(b"Running", 10)
    term.type(b"kill %1; exit 5\n")
    assert term.exit_status(30) == 5


def test_forward_reaches_a_server_in_the_guest():
    with socket.socket() as probe:  # a free port of the host's, used in the guest too
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    server = ("import socket\n"
              "s = socket.create_server(('127.0.0.1', %d))\n"
              "for n in range(2):\n"
              "    c, _ = s.accept()\n"
              "    data = c.recv(100)\n"
              "    c.sendall(b'guest got ' + data + bytes(range(256)) * 400)\n"
              "    c.close()\n") % port
    proc = subprocess.Popen([VCAN_RUN, *UML, "--timeout", "100", "--forward", str(port),
                             "python3", "-c", server], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    try:
        expected = b"guest got hello" + bytes(range(256)) * 400
        replies = []
        deadline = time.monotonic() + 90
        while len(replies) < 2:
            assert time.monotonic() < deadline, "no answer through --forward within 90 s"
            try:
                with socket.create_connection(("127.0.0.1", port), timeout=10) as conn:
                    conn.sendall(b"hello")
                    reply = b""
                    while chunk := conn.recv(65536):
                        reply += chunk
            except OSError:
                reply = b""
            if reply:  # an empty one: the guest's server is not listening yet
                replies.append(reply)
            else:
                time.sleep(0.2)
        assert replies == [expected, expected]
        _, err = proc.communicate(timeout=60)
        assert proc.returncode == 0, err
        assert f"vcan-run: the guest's 127.0.0.1:{port} is the host's 127.0.0.1:{port}".encode() in err
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_forward_port_in_use_is_refused_before_the_boot():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        result = vcan_run(*UML, "--forward", str(port), "true")
    assert result.returncode == 125
    assert f"cannot listen on 127.0.0.1:{port}: Address already in use".encode() in result.stderr


def host_with_a_larger_xsave_area(**more):
    """The environment that makes this host look like one whose XSAVE area is larger than UML's:
    SHORT_XSTATE shortens every write of UML's FPU state below this host's area, which the host
    kernel refuses (EFAULT), as it refuses UML's 2,696 bytes on hosts with AMX."""
    shim = os.environ.get("SHORT_XSTATE")
    assert shim, "SHORT_XSTATE names tests/tools/short_xstate.c's module (ctest sets it)"
    return dict(os.environ, LD_PRELOAD=shim, **more)


def test_host_whose_xsave_area_is_larger_than_umls():
    """UML panics at boot there without uml-xstate: vcan-run boots all the same and says once what
    it did."""
    env = host_with_a_larger_xsave_area()
    result = vcan_run(*UML, "sh", "-c", "ip -br link show vcan0 >/dev/null && echo booted", env=env)
    assert (result.returncode, result.stdout) == (0, b"booted\n"), result.stderr
    notes = re.findall(rb"vcan-run: this host's XSAVE area is (\d+) bytes and User-Mode Linux writes "
                       rb"back 832: each of its FPU state writes is completed with the process's "
                       rb"own last (\d+) bytes", result.stderr)
    assert len(notes) == 1, result.stderr
    area, rest = (int(n) for n in notes[0])
    assert area - 832 == rest


def test_without_the_wrapper_the_cause_is_named(tmp_path):
    """Where uml-xstate cannot be had (here: no cache of it, and a `cc` that fails to build it),
    UML panics at its first FPU state write: vcan-run exits 125 and says why, and what to do."""
    (tmp_path / "bin").mkdir()
    failing_cc = tmp_path / "bin" / "cc"
    failing_cc.write_text("#!/bin/sh\necho 'cc: not here' >&2\nexit 1\n")
    failing_cc.chmod(0o755)
    env = host_with_a_larger_xsave_area(XDG_CACHE_HOME=str(tmp_path / "cache"),
                                        PATH=f"{tmp_path / 'bin'}:{os.environ['PATH']}")
    result = vcan_run(*UML, "echo", "not run", env=env)
    assert (result.returncode, result.stdout) == (125, b""), result.stderr
    assert (b"vcan-run: User-Mode Linux could not restore a process's FPU state: this host's XSAVE "
            b"area is larger than UML's, and the wrapper that makes up for it (uml-xstate, "
            b"D-TEST-UML-XSTATE) could not be had: install a C compiler (cc) for vcan-run to build "
            b"it, or vcan-run's package\n") in result.stderr, result.stderr
