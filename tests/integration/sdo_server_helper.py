"""A CANopen SDO server the project did not write: python canopen's LocalNode on SocketCAN, in a
process of its own, for comaster's SDO client (test_comaster.py).

    sdo_server_helper.py IFACE NODE_ID

Its dictionary: 2000h UNSIGNED32, 2001h VISIBLE_STRING and 2002h DOMAIN, read-write. It prints
'ready' once it listens, and runs until SIGTERM."""

import signal
import sys

import canopen
from canopen.objectdictionary import DOMAIN, UNSIGNED32, VISIBLE_STRING, ObjectDictionary, ODVariable


def dictionary():
    od = ObjectDictionary()
    for index, name, data_type, default in ((0x2000, "Counter", UNSIGNED32, 0x12345678),
                                            (0x2001, "Label", VISIBLE_STRING, "LocalNode label"),
                                            (0x2002, "Blob", DOMAIN, b"")):
        var = ODVariable(name, index, 0)
        var.data_type = data_type
        var.access_type = "rw"
        var.default = default
        od.add_object(var)
    return od


def main():
    iface, node_id = sys.argv[1], int(sys.argv[2])
    network = canopen.Network()
    network.connect(interface="socketcan", channel=iface)
    node = canopen.LocalNode(node_id, dictionary())
    network.add_node(node)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    print("ready", flush=True)
    try:
        signal.pause()
    finally:
        network.disconnect()


if __name__ == "__main__":
    main()
