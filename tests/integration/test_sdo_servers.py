# SPDX-License-Identifier: Apache-2.0
"""The CiA 401 I/O node's second SDO server, 1201h (docs/sdo.md, "Several SDO servers"), on real
SocketCAN with python canopen as two clients: one on the default channel 60Ah/58Ah, one on the
COB-IDs a master gives 1201h (68Ah/6CAh), reading and writing at the same time, block and
segmented transfers each; CiA 301's rules of 1201h's COB-IDs; reset communication makes it not
valid again."""

import threading

import canopen
import pytest
from canopen.sdo.exceptions import SdoAbortedError, SdoCommunicationError

from conftest import IFACE, NMT_RESET_COMMUNICATION, ROOT

IO = 10
IO401_EDS = ROOT / "eds" / "IO401.eds"
REQUEST_2 = 0x680 + IO  # client -> server of 1201h
RESPONSE_2 = 0x6C0 + IO  # server -> client
NOT_VALID = 0x80000000
SDO_ABORT_VALUE_RANGE = 0x06090030
ROUNDS = 20


@pytest.fixture
def io_node(bus, start_daemon):
    start_daemon(bus, "--node-id", IO, "--model", "io")
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=IFACE)
    node = canopen.RemoteNode(IO, str(IO401_EDS))
    net.add_node(node)
    yield node
    net.disconnect()


def second_server(node):
    """1201h given the COB-IDs 68Ah and 6CAh through the default channel, and a client on them."""
    assert node.sdo[0x1201][1].raw == NOT_VALID | 0x680
    assert node.sdo[0x1201][2].raw == NOT_VALID | 0x6C0
    node.sdo[0x1201][1].raw = REQUEST_2
    node.sdo[0x1201][2].raw = RESPONSE_2
    client = node.add_sdo(REQUEST_2, RESPONSE_2)
    client.network = node.network  # add_sdo after add_node subscribes but does not assign it
    return client


def block_upload(sdo, index):
    with sdo.open(index, 0, "rb", block_transfer=True) as f:
        return f.read()


def block_download(sdo, index, sub, data):
    with sdo.open(index, sub, "wb", size=len(data), block_transfer=True) as f:
        f.write(data)


def test_two_clients_at_once(bus, io_node):
    """Two threads, one a client each: on the default channel a block upload of 1008h and a
    segmented download of 1017h, on 1201h a segmented upload of 1008h and a block download of
    6200h:01, round after round; every transfer completes with its own value, and the two
    channels' answers alternate on the bus."""
    second = second_server(io_node)
    errors = []

    def default_client():
        try:
            for n in range(ROUNDS):
                assert block_upload(io_node.sdo, 0x1008) == b"IO401"
                io_node.sdo.download(0x1017, 0, (100 + n).to_bytes(2, "little"), force_segment=True)
                assert io_node.sdo.upload(0x1017, 0) == (100 + n).to_bytes(2, "little")
        except Exception as e:  # reported by the main thread
            errors.append(("default", e))

    def second_client():
        try:
            for n in range(ROUNDS):
                assert second.upload(0x1008, 0) == b"IO401"
                block_download(second, 0x6200, 1, bytes([n]))
                assert second.upload(0x6200, 1) == bytes([n])
        except Exception as e:  # reported by the main thread
            errors.append(("1201h", e))

    threads = [threading.Thread(target=default_client, daemon=True), threading.Thread(target=second_client, daemon=True)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=60)
    assert not any(t.is_alive() for t in threads)
    assert errors == []
    assert io_node.sdo[0x1017].raw == 100 + ROUNDS - 1
    assert second[0x6200][1].raw == ROUNDS - 1
    answers = [f.can_id for f in bus.collect(0.3) if f.can_id in (0x580 + IO, RESPONSE_2)]
    # One client after the other would switch once; at once, their transfers interleave.
    assert sum(1 for a, b in zip(answers, answers[1:]) if a != b) >= 2


def test_cob_id_rules_and_reset(bus, io_node):
    """A valid COB-ID keeps its CAN-ID (0x06090030), bit 29 and a restricted CAN-ID are refused;
    after reset communication 1201h is not valid again and its client gets no answer."""
    second = second_server(io_node)
    for value in (REQUEST_2 + 1, 0x20000000 | REQUEST_2, NOT_VALID | 0x605):
        with pytest.raises(SdoAbortedError) as aborted:
            io_node.sdo[0x1201][1].raw = value
        assert aborted.value.code == SDO_ABORT_VALUE_RANGE
    assert second[0x1018][4].raw == 0x40100000 + IO
    bus.nmt(NMT_RESET_COMMUNICATION, IO)
    bus.expect(0x700 + IO, b"\x00")
    assert io_node.sdo[0x1201][1].raw == NOT_VALID | 0x680
    second.RESPONSE_TIMEOUT = 0.3
    second.MAX_RETRIES = 1
    with pytest.raises(SdoCommunicationError):
        second.upload(0x1018, 4)
