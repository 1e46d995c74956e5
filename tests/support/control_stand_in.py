# SPDX-License-Identifier: Apache-2.0
"""A stand-in for a control socket (atv312d's, or a comaster run's), for the tests of the programs
that talk to one: it answers each connection's request line with a fixed reply, or closes without
one, so that every answer a client can get is tested without the daemon or the run."""

import os
import socket
import threading


class StandIn:
    """Listens on `path`; answers the one connection's request line with `reply` (None: closes
    without a word). `requests` holds the lines it was sent."""

    def __init__(self, path, reply):
        self.path = path
        self.requests = []
        self.server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.server.bind(path)
        self.server.listen(1)
        self.thread = threading.Thread(target=self.serve, args=(reply,), daemon=True)
        self.thread.start()

    def serve(self, reply):
        conn, _ = self.server.accept()
        with conn:
            self.requests.append(conn.makefile().readline())
            if reply is not None:
                conn.sendall(reply.encode())

    def close(self):
        self.thread.join(timeout=10)
        self.server.close()
        os.unlink(self.path)
