# SPDX-License-Identifier: Apache-2.0
"""A CANopen SDO server the project did not write: python canopen's LocalNode on SocketCAN, in a
process of its own, for comaster's SDO client (test_comaster.py).

    sdo_server_helper.py IFACE NODE_ID

Its dictionary: 2000h UNSIGNED32, 2001h VISIBLE_STRING, 2002h DOMAIN and 2003h INTEGER16,
read-write; 1000h (device type 0) read-only; TPDO1 (1800h, 1A00h) for a DCF's PDO configuration
(LocalNode stores every write of the right length: it has no rule of a valid PDO). It prints
'ready' once it listens, and runs until SIGTERM."""

import signal
import sys

import canopen
from canopen.objectdictionary import (DOMAIN, INTEGER16, UNSIGNED8, UNSIGNED16, UNSIGNED32, VISIBLE_STRING,
                                     ODRecord, ObjectDictionary, ODVariable)


def variable(name, index, sub, data_type, default, access="rw"):
    var = ODVariable(name, index, sub)
    var.data_type = data_type
    var.access_type = access
    var.default = default
    return var


def record(name, index, subs, count_access="ro"):
    rec = ODRecord(name, index)
    for sub, (sub_name, data_type, default) in enumerate(subs):
        rec.add_member(variable(sub_name, index, sub, data_type, default, count_access if sub == 0 else "rw"))
    return rec


def dictionary(node_id):
    od = ObjectDictionary()
    od.add_object(variable("Device type", 0x1000, 0, UNSIGNED32, 0, "ro"))
    for index, name, data_type, default in ((0x2000, "Counter", UNSIGNED32, 0x12345678),
                                            (0x2001, "Label", VISIBLE_STRING, "LocalNode label"),
                                            (0x2002, "Blob", DOMAIN, b""),
                                            (0x2003, "Offset", INTEGER16, 0)):
        od.add_object(variable(name, index, 0, data_type, default))
    od.add_object(record("TPDO1 parameter", 0x1800, [
        ("Highest sub-index", UNSIGNED8, 5), ("COB-ID", UNSIGNED32, 0x180 + node_id),
        ("Transmission type", UNSIGNED8, 255), ("Inhibit time", UNSIGNED16, 0),
        ("Reserved", UNSIGNED8, 0), ("Event timer", UNSIGNED16, 0)]))
    od.add_object(record("TPDO1 mapping", 0x1A00, [
        ("Number of mapped objects", UNSIGNED8, 1), ("Object 1", UNSIGNED32, 0x20000020),
        ("Object 2", UNSIGNED32, 0)], count_access="rw"))
    return od


def main():
    iface, node_id = sys.argv[1], int(sys.argv[2])
    network = canopen.Network()
    network.connect(interface="socketcan", channel=iface)
    node = canopen.LocalNode(node_id, dictionary(node_id))
    network.add_node(node)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    print("ready", flush=True)
    try:
        signal.pause()
    finally:
        network.disconnect()


if __name__ == "__main__":
    main()
