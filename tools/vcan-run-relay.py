#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""vcan-run-relay: the byte streams between vcan-run and its User-Mode Linux guest: the caller's
stdin when it is a pipe or a file, and --forward's TCP connections.

The guest has no network to the host; what joins them are console lines, byte streams (pipes on the
host, ttys in raw mode in the guest). A line has no end of its own: the host's end of input would
hang the guest's tty up, which throws away what the guest has not read yet. So both ends of each
line run this program and speak in frames:

    type (1 byte) | connection (1 byte) | length (2 bytes, big-endian) | payload

    HELLO   the guest is ready (forward): nothing is sent to it before, the line drops it
    OPEN    a new connection (forward); payload: the guest's port (2 bytes)
    DATA    payload: bytes of the stream or of a connection
    CLOSE   the stream or the connection ended on the side that sends it

stdin-host copies its stdin onto the line once the guest has created the --ready file (the line
drops what comes earlier), stdin-guest copies the line to its stdout until CLOSE; forward-host
listens on the host's loopback ports and forward-guest connects to the same ports in the guest.
"""

import argparse
import os
import selectors
import socket
import struct
import sys
import time

HELLO, OPEN, DATA, CLOSE = 1, 2, 3, 4
HEADER = struct.Struct(">BBH")
MAX_PAYLOAD = 16384
MAX_CONNECTIONS = 256


class Line:
    """The console line: frames written whole, read back from a byte stream."""

    def __init__(self, read_fd, write_fd):
        self.read_fd, self.write_fd = read_fd, write_fd
        self.pending = b""

    def send(self, kind, conn, payload=b""):
        frame = HEADER.pack(kind, conn, len(payload)) + payload
        while frame:
            frame = frame[os.write(self.write_fd, frame):]

    def receive(self):
        """The frames that arrived whole; None once the line is closed."""
        data = os.read(self.read_fd, 65536)
        if not data:
            return None
        self.pending += data
        frames = []
        while len(self.pending) >= HEADER.size:
            kind, conn, length = HEADER.unpack_from(self.pending)
            if len(self.pending) < HEADER.size + length:
                break
            frames.append((kind, conn, self.pending[HEADER.size:HEADER.size + length]))
            self.pending = self.pending[HEADER.size + length:]
        return frames


class Relay:
    """Connections on one side, frames on the line, one selector for both."""

    def __init__(self):
        self.line = None
        self.selector = selectors.DefaultSelector()
        self.sockets = {}  # connection number -> socket

    def attach(self, line):
        self.line = line
        self.selector.register(line.read_fd, selectors.EVENT_READ, self.from_line)

    def add(self, conn, sock):
        self.sockets[conn] = sock
        self.selector.register(sock, selectors.EVENT_READ, lambda: self.from_socket(conn))

    def drop(self, conn, tell_other_side):
        sock = self.sockets.pop(conn, None)
        if sock is None:
            return
        self.selector.unregister(sock)
        sock.close()
        if tell_other_side:
            self.line.send(CLOSE, conn)

    def from_socket(self, conn):
        sock = self.sockets.get(conn)
        if sock is None:
            return  # dropped by an earlier event of the same wake-up
        try:
            data = sock.recv(MAX_PAYLOAD)
        except OSError:
            data = b""
        if data:
            self.line.send(DATA, conn, data)
        else:
            self.drop(conn, tell_other_side=True)

    def from_line(self):
        frames = self.line.receive()
        if frames is None:
            raise SystemExit(0)  # the other side is gone: so is every connection
        for kind, conn, payload in frames:
            self.on_frame(kind, conn, payload)

    def on_frame(self, kind, conn, payload):
        if kind == DATA and conn in self.sockets:
            try:
                self.sockets[conn].sendall(payload)
            except OSError:
                self.drop(conn, tell_other_side=True)
        elif kind == CLOSE:
            self.drop(conn, tell_other_side=False)

    def run(self):
        while True:
            for key, _ in self.selector.select():
                key.data()


class HostRelay(Relay):
    def __init__(self, ports):
        super().__init__()
        self.next_conn = 0
        self.listeners = []
        for host_port, guest_port in ports:
            listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            try:
                listener.bind(("127.0.0.1", host_port))
            except OSError as error:
                sys.exit(f"vcan-run: error: --forward {host_port}:{guest_port}: cannot listen on "
                         f"127.0.0.1:{host_port}: {error.strerror}")
            listener.listen(16)
            self.listeners.append((listener, guest_port))
        self.guest_ready = False

    def start_listening(self):
        for listener, guest_port in self.listeners:
            self.selector.register(listener, selectors.EVENT_READ,
                                   lambda l=listener, p=guest_port: self.accept(l, p))

    def accept(self, listener, guest_port):
        sock, _ = listener.accept()
        conn = self.free_connection()
        if conn is None:
            sock.close()
            return
        self.add(conn, sock)
        self.line.send(OPEN, conn, struct.pack(">H", guest_port))

    def free_connection(self):
        for _ in range(MAX_CONNECTIONS):
            conn = self.next_conn
            self.next_conn = (self.next_conn + 1) % MAX_CONNECTIONS
            if conn not in self.sockets:
                return conn
        return None

    def on_frame(self, kind, conn, payload):
        if kind == HELLO and not self.guest_ready:
            self.guest_ready = True
            self.start_listening()
        else:
            super().on_frame(kind, conn, payload)


class GuestRelay(Relay):
    def on_frame(self, kind, conn, payload):
        if kind != OPEN:
            super().on_frame(kind, conn, payload)
            return
        (port,) = struct.unpack(">H", payload)
        try:
            sock = socket.create_connection(("127.0.0.1", port))
        except OSError:
            self.line.send(CLOSE, conn)  # nothing listens there (yet): the host's client is closed
            return
        self.add(conn, sock)


def port_pair(text):
    host, _, guest = text.partition(":")
    try:
        pair = int(host), int(guest or host)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not PORT or HOSTPORT:GUESTPORT") from None
    if not all(1 <= p <= 65535 for p in pair):
        raise argparse.ArgumentTypeError(f"'{text}': ports are 1 to 65535")
    return pair


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("role", choices=("stdin-host", "stdin-guest", "forward-host", "forward-guest"))
    parser.add_argument("--line", required=True, metavar="IN:OUT",
                        help="the console line: where frames come from and go to, each a file "
                             "descriptor number or a path (a FIFO, opened read-write)")
    parser.add_argument("--ready", metavar="FILE",
                        help="forward-host: created once the ports listen; stdin-host: waited for "
                             "before anything is sent")
    parser.add_argument("ports", nargs="*", type=port_pair, metavar="HOSTPORT[:GUESTPORT]")
    args = parser.parse_intermixed_args()
    if args.role == "stdin-host":
        copy_stdin_to_line(open_line(args.line), args.ready)
    elif args.role == "stdin-guest":
        copy_line_to_stdout(open_line(args.line))
    elif args.role == "forward-host":
        relay = HostRelay(args.ports)  # listening first: a port in use fails before the boot
        if args.ready:
            open(args.ready, "w").close()
        relay.attach(open_line(args.line))
        relay.run()
    else:
        line = open_line(args.line)
        line.send(HELLO, 0)
        relay = GuestRelay()
        relay.attach(line)
        relay.run()


def copy_stdin_to_line(line, ready):
    while not os.path.exists(ready):
        time.sleep(0.02)
    while True:
        data = os.read(0, MAX_PAYLOAD)
        if not data:
            line.send(CLOSE, 0)
            return
        line.send(DATA, 0, data)


def copy_line_to_stdout(line):
    while True:
        frames = line.receive()
        if frames is None:
            return
        for kind, _, payload in frames:
            if kind == CLOSE:
                return
            try:
                while payload:
                    payload = payload[os.write(1, payload):]
            except BrokenPipeError:
                return  # the command stopped reading: the rest is not wanted


def open_line(text):
    """IN:OUT, each a descriptor number or a path; a FIFO is opened read-write, so that opening it
    never waits for the other end."""
    ends = []
    for end in text.split(":"):
        ends.append(int(end) if end.isdigit() else os.open(end, os.O_RDWR | os.O_NOCTTY))
    if len(ends) != 2:
        sys.exit(f"vcan-run-relay: error: --line wants IN:OUT, got '{text}'")
    return Line(*ends)


if __name__ == "__main__":
    main()
