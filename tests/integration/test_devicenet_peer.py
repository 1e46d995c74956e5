# SPDX-License-Identifier: Apache-2.0
"""atv312d --devicenet on real SocketCAN against a DeviceNet master the project did not write:
devicenet-py 0.0.1 (PyPI, on python-can; scripts/setup installs it). Its duplicate MAC ID check
beside a drive and against one, the allocation of the predefined master/slave connection set,
Get/Set_Attribute_Single of the Identity and of a drive parameter, the polled connection's
attributes, poll I/O with assemblies 21/71 to 1200 rpm, and the release; its UCMM Open of an
explicit connection (instances 10-14), a Get and a Set on it and Close; each session's candump
trace decoded frame by frame by `cotrace --devicenet`.

devicenet-py disagrees with the DeviceNet specification in three places that these tests meet
(docs/devicenet.md, "Checked against devicenet-py"): its Allocate goes to the explicit
connection (message 4), which does not exist before an Allocate, instead of the Group 2 Only
Unconnected Explicit Request port (message 6); it puts the allocator's MAC ID in the top six bits
of its byte; it does not acknowledge the fragments of a response. Where a test needs to go on, it
uses devicenet-py's own message classes on the right port, and acknowledges fragments itself.
Every wait has a deadline."""

import os
import re
import subprocess
import threading
import time

import can
import pytest
from devicenet.cid import DeviceNetCID
from devicenet.devicenet import DeviceNet
from devicenet.dtypes import DeviceNetDatatype
from devicenet.enums import DeviceNetBodyFormat, DeviceNetFragmentationType, DeviceNetServiceCode, DeviceNetState
from devicenet.enums import DeviceNetMessageGroup
from devicenet.enums import DeviceNetConnectionObjectAttributes as ConnectionAttribute
from devicenet.fields import DeviceNetAllocationChoiceByte, DeviceNetExplicitHeader, DeviceNetFragmentProtocol
from devicenet.helpers import CanFilter
from devicenet.messages import (
    DeviceNetAllocateMasterSlaveConnectionRequestMessage,
    DeviceNetAllocateMasterSlaveConnectionResponseMessage,
    DeviceNetDataMessage,
    DeviceNetExplicitMessageGenericService,
    DeviceNetExplicitRequestMessage,
)

from conftest import BOOT_TIMEOUT, IFACE, REPLY_TIMEOUT, ROOT, ctl_state, wait_state

COTRACE = os.environ.get("COTRACE") or str(ROOT / "build" / "apps" / "cotrace" / "cotrace")

# devicenet-py's Duplicate MAC ID check carries these: a vendor and serial number of the test's.
PEER_VENDOR = 0x0123
PEER_SERIAL = 0x11223344

EXPLICIT = DeviceNetAllocationChoiceByte(explicit_message=True)
POLLED = DeviceNetAllocationChoiceByte(polled=True)
EXPLICIT_AND_POLLED = DeviceNetAllocationChoiceByte(explicit_message=True, polled=True)

# Services devicenet-py has no name for, and the Error_Response a refusal carries (0x94 is 0x14
# with the response bit: devicenet-py reads it as a response of service 0x14).
RELEASE = 0x4C
ERROR_RESPONSE = 0x14

# The DeviceNet object (0x03) and its allocation information; the Identity (0x01).
DEVICENET_CLASS, ALLOCATION_INFORMATION = 0x03, 5
IDENTITY_CLASS = 0x01
# ACC (address 9001) through the application objects: class 8Eh, instance 1, attribute 2, 0.1 s.
ACC_CLASS, ACC_ATTRIBUTE = 0x8E, 2


class Master(DeviceNet):
    """devicenet-py's DeviceNet node, changed in one thing: how long it waits for an answer.

    devicenet-py reads the bus until 100 ms pass without a frame and takes what came as the answer.
    The drive answers within a millisecond, but inside User-Mode Linux on a loaded machine a
    wake-up can take longer; so after each send the first frame is waited for up to REPLY_TIMEOUT
    (the deadline of every other integration test), and devicenet-py's 100 ms of silence end the
    wait after it. Where nothing answers (a MAC ID nobody has) the wait is REPLY_TIMEOUT, the
    second the specification gives a duplicate MAC ID check."""

    def __init__(self, bus, mac_id):
        self.answer_due = False
        super().__init__(bus, mac_id, vendor_id=PEER_VENDOR, serial_number=PEER_SERIAL)

    def send(self, cid, msg):
        super().send(cid, msg)
        self.answer_due = True

    def recv(self, timeout=0.1):
        if self.answer_due:
            self.answer_due = False
            timeout = max(timeout, REPLY_TIMEOUT)
        return super().recv(timeout)

    def exchange(self, cid, message, slave):
        """Sends message on cid and returns the payloads of the slave's explicit responses (group 2
        message 3), each fragment acknowledged as the fragmentation protocol asks (success, the
        fragment's count): devicenet-py reassembles fragments but acknowledges none."""
        payloads = []

        def on_response(_cid, payload):
            payloads.append(payload)
            header = DeviceNetExplicitHeader.unpack(payload[:1])
            if header.frag:
                count = DeviceNetFragmentProtocol.unpack(payload[1:2]).fragmentation_count
                ack = DeviceNetFragmentProtocol(DeviceNetFragmentationType.FRAGMENT_ACKNOWLEDGE, count)
                self.send(DeviceNetCID.master_explicit_request(slave),
                          DeviceNetDataMessage(header.pack() + ack.pack() + b"\x00"))

        response_filter = CanFilter(id=DeviceNetCID.slave_explicit_response(slave).pack(), mask=0x7FF,
                                    callback=on_response)
        self.register_callback(response_filter)
        self.send(cid, message)
        self.handle_messages()
        self.deregister_callback(response_filter)
        assert payloads, f"MAC ID {slave}: no response to {message}"
        return payloads

    def request(self, slave, service, class_id, instance, data=b"", unconnected=False):
        """Any service, built with devicenet-py's request class (8/8 body format), on the explicit
        connection (message 4) or the Group 2 Only Unconnected port (message 6); returns the
        response's (service, data) as devicenet-py unpacks it, fragments reassembled."""
        message = DeviceNetExplicitRequestMessage(service_code=service, mac_id=self.mac_id, class_id=class_id,
                                                  instance_id=instance, message=data)
        cid = (DeviceNetCID.group_2_unconnected_explicit_request(slave) if unconnected
               else DeviceNetCID.master_explicit_request(slave))
        response = DeviceNetExplicitMessageGenericService.unpack(self.exchange(cid, message, slave))
        assert response.is_response and response.mac_id == self.mac_id, response
        return response.service_code, response.message

    def get(self, slave, class_id, instance, attribute, dtype):
        service, data = self.request(slave, DeviceNetServiceCode.GET_ATTRIBUTE_SINGLE, class_id, instance,
                                     bytes([attribute]))
        assert service == DeviceNetServiceCode.GET_ATTRIBUTE_SINGLE, (service, data)
        return DeviceNetDatatype.decode(data, dtype)

    def allocate_unconnected(self, slave, choice):
        """devicenet-py's Allocate request on message 6, where the specification puts it; its
        response unpacked by devicenet-py: the body format."""
        message = DeviceNetAllocateMasterSlaveConnectionRequestMessage(mac_id=self.mac_id, allocation_choice=choice,
                                                                       allocator_id=self.mac_id)
        payloads = self.exchange(DeviceNetCID.group_2_unconnected_explicit_request(slave), message, slave)
        return DeviceNetAllocateMasterSlaveConnectionResponseMessage.unpack(payloads[0]).message_body_format


@pytest.fixture
def peer():
    """peer(mac_id): devicenet-py's node on its own python-can socket of vcan0, offline."""
    buses = []

    def make(mac_id):
        bus = can.Bus(interface="socketcan", channel=IFACE)
        buses.append(bus)
        return Master(bus, mac_id)

    yield make
    for bus in buses:
        bus.shutdown()


def check_frame(mac_id, data):
    """The duplicate MAC ID check's frame of mac_id (group 2 message 7)."""
    return 0x400 | mac_id << 3 | 7, data


def drive_check(mac_id, response=False):
    """The drive's check request or response: port 0, vendor 0x00F3, serial 0x31200000 + MAC ID."""
    return check_frame(mac_id, f"{0x80 if response else 0:02X}F300{mac_id:02X}002031")


def peer_check(mac_id, response=False):
    """devicenet-py's check request or response: port 0, the test's vendor and serial number."""
    identity = PEER_VENDOR.to_bytes(2, "little") + PEER_SERIAL.to_bytes(4, "little")
    return check_frame(mac_id, f"{0x80 if response else 0:02X}{identity.hex().upper()}")


def test_devicenet_py_checks_its_mac_id_and_the_drive_defends_its_own(start_dn, peer, dump):
    _, sock = start_dn([25])
    master = peer(0)
    mark = dump.mark()
    master.connect()
    assert master.state == DeviceNetState.ONLINE
    # Its two requests, at least a second apart, and nobody answers MAC ID 0.
    first = dump.expect(*peer_check(0), since=mark)
    second = dump.expect(*peer_check(0), timeout=3.0)
    assert second.timestamp - first.timestamp >= 1.0, (first, second)
    # MAC ID 25 is the drive's: the drive, online, answers the request with its response form.
    claimer = peer(25)
    with pytest.raises(RuntimeError, match="MAC already in use"):
        claimer.connect()
    assert claimer.state == DeviceNetState.COMMUNICATION_FAULT
    dump.expect(*peer_check(25))
    dump.expect(*drive_check(25, response=True))
    state = ctl_state(sock, 25)
    assert (state["ms"], state["ns"]) == ("green", "flashing-green")


def test_a_drive_checking_a_mac_id_devicenet_py_holds_stays_off_the_bus(start_daemon, peer, dump, tmp_path):
    master = peer(40)
    master.connect(quick_connect=True)
    dump.expect(*peer_check(40))
    # devicenet-py answers other nodes' checks of its MAC ID while it reads the bus.
    stop = threading.Event()

    def answer_checks():
        while not stop.is_set():
            master.handle_messages()

    answering = threading.Thread(target=answer_checks)
    answering.start()
    try:
        sock = tmp_path / "dn.sock"
        start_daemon(dump, "--devicenet", "--mac-id", 40, "--control", sock, boot_ids=[])
        dump.expect(*drive_check(40), timeout=BOOT_TIMEOUT)
        dump.expect(*peer_check(40, response=True))
        # A duplicate: the card stays offline, NS solid red, and sends no second request.
        state = wait_state(sock, 40, ns="red")
        assert state["ms"] == "green"
        dump.expect_none(0x547, 1.5)
    finally:
        stop.set()
        answering.join(timeout=5)


def test_devicenet_py_allocator_mac_id_is_refused_above_63(start_dn, peer, dump):
    start_dn([25])
    master = peer(16)
    master.connect(quick_connect=True)
    # devicenet-py packs its MAC ID 16 into the allocator byte as 0x40 (16 << 2): not a MAC ID, an
    # invalid parameter. Its response class takes no error response: the payload as it came.
    payloads = master.exchange(DeviceNetCID.group_2_unconnected_explicit_request(25),
                               DeviceNetAllocateMasterSlaveConnectionRequestMessage(
                                   mac_id=16, allocation_choice=EXPLICIT, allocator_id=16), 25)
    assert payloads == [bytes.fromhex("109420FF")]
    dump.expect(0x4CE, "104B03010140")
    dump.expect(0x4CB, "109420FF")


def decoded_trace(dump, since, path):
    """The frames candump saw since a mark, as `candump -L` wrote them, decoded by cotrace
    --devicenet: [(frame, meaning)], one per frame."""
    frames = dump.seen[since:]
    path.write_text("".join(f"({f.timestamp:.6f}) {IFACE} {f}\n" for f in frames))
    done = subprocess.run([COTRACE, "--devicenet", str(path)], capture_output=True, text=True, timeout=30)
    assert (done.returncode, done.stderr) == (0, ""), done.stderr
    lines = [re.fullmatch(r"\(\d+\.\d{6}\) \S+ (\S+) +(.*)", line).groups() for line in done.stdout.splitlines()]
    assert [frame for frame, _ in lines] == [str(f) for f in frames]
    return lines


def assert_trace(lines, expected, ramp=()):
    """The decoded trace is the session: each (frame, meaning) is one of expected, or its meaning
    matches one of the ramp's patterns (the poll responses while the speed changes); and every
    expected one is there."""
    unexplained = [line for line in lines if line not in expected and not any(re.fullmatch(p, line[1]) for p in ramp)]
    assert unexplained == []
    assert set(expected) - set(lines) == set()


def ucmm_exchange(master, cid, message, response_id):
    """Sends message (devicenet-py's classes) on a group 3 CAN-ID and returns the payload of the
    first frame on response_id."""
    payloads = []
    response_filter = CanFilter(id=response_id, mask=0x7FF, callback=lambda _cid, payload: payloads.append(payload))
    master.register_callback(response_filter)
    master.send(cid, message)
    master.handle_messages()
    master.deregister_callback(response_filter)
    assert payloads, f"no response on {response_id:03X} to {message}"
    return payloads[0]


def test_devicenet_py_opens_by_ucmm_and_gets_and_sets_on_the_connection(start_dn, peer, dump, tmp_path):
    """devicenet-py's own Open Explicit Messaging Connection (IEC 62026-3's UCMM, group 3 message
    6) reaches the drive's explicit server instances 10-14: group 3, devicenet-py's source message
    ID 1, answered on group 3 message 5 with instance 10; its request class then reads the vendor
    ID and sets ACC on the connection (641h, the drive answering on 619h), and Close ends it."""
    mark = dump.mark()
    _, sock = start_dn([25])
    master = peer(1)
    master.connect(quick_connect=True)
    assert master.open_explicit_messaging_connection_request(25, DeviceNetBodyFormat.DEVICENET_8_8,
                                                             DeviceNetMessageGroup.MESSAGE_GROUP_3, 1)
    dump.expect(0x781, "194B0031", since=mark)
    dump.expect(0x759, "01CB00100A00")
    assert ctl_state(sock, 25)["ns"] == "green"
    to_drive = DeviceNetCID(DeviceNetMessageGroup.MESSAGE_GROUP_3, message_id=1, mac_id=1)
    get_vendor = DeviceNetExplicitRequestMessage(service_code=DeviceNetServiceCode.GET_ATTRIBUTE_SINGLE, mac_id=25,
                                                 class_id=IDENTITY_CLASS, instance_id=1, message=bytes([1]))
    response = DeviceNetExplicitMessageGenericService.unpack([ucmm_exchange(master, to_drive, get_vendor, 0x619)])
    assert (response.is_response, response.mac_id, response.message) == (True, 1, bytes([0xF3, 0x00]))
    set_acc = DeviceNetExplicitRequestMessage(service_code=DeviceNetServiceCode.SET_ATTRIBUTE_SINGLE, mac_id=25,
                                              class_id=ACC_CLASS, instance_id=1,
                                              message=bytes([ACC_ATTRIBUTE]) + (10).to_bytes(2, "little"))
    assert ucmm_exchange(master, to_drive, set_acc, 0x619) == bytes([0x01, 0x90])
    dump.expect(0x641, "19108E01020A00")
    close = DeviceNetDataMessage(bytes([25, 0x4C, 10, 0]))
    ucmm = DeviceNetCID(DeviceNetMessageGroup.MESSAGE_GROUP_3, message_id=6, mac_id=1)
    assert ucmm_exchange(master, ucmm, close, 0x759) == bytes([0x01, 0xCC])
    dump.expect(0x759, "01CC")
    assert_trace(decoded_trace(dump, mark, tmp_path / "ucmm.log"), [
        ("781#194B0031", "G3 msg 6 from 1: UCMM request to 25: Open Explicit Messaging Connection request: "
                         "body format 0, group 3, source message ID 1"),
        ("759#01CB00100A00", "G3 msg 5 from 25: UCMM response to 1: Open Explicit Messaging Connection response: "
                             "body format 0, destination message ID 1, source message ID 0, instance 10"),
        ("641#190E010101", "G3 msg 1 from 1: UCMM connection request to 25: Get_Attribute_Single Identity (0x01) "
                           "instance 1 attribute 1"),
        ("619#018EF300", "G3 msg 0 from 25: UCMM connection response to 1: Get_Attribute_Single Identity (0x01) "
                         "instance 1 attribute 1 = F3 00 (243)"),
        ("781#194C0A00", "G3 msg 6 from 1: UCMM request to 25: Close Connection request: instance 10"),
        ("759#01CC", "G3 msg 5 from 25: UCMM response to 1: Close Connection response"),
    ], ramp=(r"G2 msg 7 .*", r"G3 msg 1 from 1: UCMM connection request to 25: Set_Attribute_Single .*",
             r"G3 msg 0 from 25: UCMM connection response to 1: Set_Attribute_Single .*"))
    wait_state(sock, 25, ns="flashing-green")


def test_devicenet_py_allocates_reads_the_identity_and_sets_acc(start_dn, peer, dump, tmp_path):
    mark = dump.mark()
    _, sock = start_dn([25])
    master = peer(0)
    master.connect(quick_connect=True)
    # devicenet-py's Allocate goes to message 4, which no explicit connection consumes yet: the
    # drive, a Group 2 only server, does not answer.
    with pytest.raises(RuntimeError, match="No response to connection request"):
        master.master_slave_connect(25, EXPLICIT_AND_POLLED)
    dump.expect(0x4CC, "004B03010300")
    # The same request on message 6: the explicit connection. Then devicenet-py's own Allocate,
    # through it, adds the polled connection.
    assert master.allocate_unconnected(25, EXPLICIT) == DeviceNetBodyFormat.DEVICENET_8_8
    dump.expect(0x4CE, "004B03010100")
    dump.expect(0x4CB, "00CB00")
    assert master.master_slave_connect(25, POLLED) == DeviceNetBodyFormat.DEVICENET_8_8
    dump.expect(0x4CC, "004B03010200")
    dump.expect(0x4CB, "00CB00")
    assert master.get(25, DEVICENET_CLASS, 1, ALLOCATION_INFORMATION, DeviceNetDatatype.OCTETSTRING) == bytes(
        [0x03, 0])
    # The Identity: vendor 243, device type 2 (AC drive), product code 6153, revision 1.1, serial
    # number, and the product name in two fragments that devicenet-py reassembles.
    assert master.get(25, IDENTITY_CLASS, 1, 1, DeviceNetDatatype.UINT) == 243
    assert master.get(25, IDENTITY_CLASS, 1, 2, DeviceNetDatatype.UINT) == 2
    assert master.get(25, IDENTITY_CLASS, 1, 3, DeviceNetDatatype.UINT) == 6153
    assert master.get(25, IDENTITY_CLASS, 1, 4, DeviceNetDatatype.OCTETSTRING) == bytes([1, 1])
    assert master.get(25, IDENTITY_CLASS, 1, 6, DeviceNetDatatype.UDINT) == 0x31200019
    fragments = dump.mark()
    assert master.get(25, IDENTITY_CLASS, 1, 7, DeviceNetDatatype.SHORT_STRING) == "ATV312"
    dump.expect(0x4CC, "000E010107", since=fragments)
    dump.expect(0x4CB, "80008E0641545633")
    dump.expect(0x4CC, "80C000")
    dump.expect(0x4CB, "80813132")
    dump.expect(0x4CC, "80C100")
    # ACC through the application objects: 3.0 s, set to 1.0 s, read back; one out of range refused.
    assert master.get(25, ACC_CLASS, 1, ACC_ATTRIBUTE, DeviceNetDatatype.UINT) == 30
    assert master.request(25, DeviceNetServiceCode.SET_ATTRIBUTE_SINGLE, ACC_CLASS, 1,
                          bytes([ACC_ATTRIBUTE]) + (10).to_bytes(2, "little")) == (
        DeviceNetServiceCode.SET_ATTRIBUTE_SINGLE, b"")
    dump.expect(0x4CC, "00108E01020A00")
    dump.expect(0x4CB, "0090")
    assert master.get(25, ACC_CLASS, 1, ACC_ATTRIBUTE, DeviceNetDatatype.UINT) == 10
    assert master.request(25, DeviceNetServiceCode.SET_ATTRIBUTE_SINGLE, ACC_CLASS, 1,
                          bytes([ACC_ATTRIBUTE]) + (65535).to_bytes(2, "little")) == (
        ERROR_RESPONSE, bytes([0x09, 0xFF]))
    # Release both on the explicit connection: the response, then nothing allocated.
    assert master.request(25, RELEASE, DEVICENET_CLASS, 1, bytes([0x03])) == (RELEASE, b"")
    dump.expect(0x4CC, "004C030103")
    dump.expect(0x4CB, "00CC")
    wait_state(sock, 25, ns="flashing-green")

    lines = decoded_trace(dump, mark, tmp_path / "peer-explicit.log")
    to, frm = "G2 msg 4 to 25: explicit request from 0: ", "G2 msg 3 from 25: explicit response to 0: "
    identity = "Get_Attribute_Single Identity (0x01) instance 1 attribute"
    acc = "Set_Attribute_Single class 0x8E instance 1 attribute 2"
    assert_trace(lines, [
        ("4CF#00F30019002031", "G2 msg 7 from 25: duplicate MAC ID check request, port 0, vendor 0x00F3, "
                               "serial number 0x31200019"),
        ("407#00230144332211", "G2 msg 7 from 0: duplicate MAC ID check request, port 0, vendor 0x0123, "
                               "serial number 0x11223344"),
        ("4CC#004B03010300", to + "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1, choice 0x03 "
                                  "(explicit, polled), allocator 0"),
        ("4CE#004B03010100", "G2 msg 6 to 25: unconnected request from 0: Allocate_Master/Slave_Connection_Set "
                             "DeviceNet (0x03) instance 1, choice 0x01 (explicit), allocator 0"),
        ("4CC#004B03010200", to + "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1, choice 0x02 "
                                  "(polled), allocator 0"),
        ("4CB#00CB00", frm + "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: message body "
                             "format 8/8"),
        ("4CC#000E030105", to + "Get_Attribute_Single DeviceNet (0x03) instance 1 attribute 5"),
        ("4CB#008E0300", frm + "Get_Attribute_Single DeviceNet (0x03) instance 1 attribute 5 = 03 00 (3)"),
        ("4CC#000E010101", to + identity + " 1"),
        ("4CB#008EF300", frm + identity + " 1 = F3 00 (243)"),
        ("4CC#000E010102", to + identity + " 2"),
        ("4CB#008E0200", frm + identity + " 2 = 02 00 (2)"),
        ("4CC#000E010103", to + identity + " 3"),
        ("4CB#008E0918", frm + identity + " 3 = 09 18 (6153)"),
        ("4CC#000E010104", to + identity + " 4"),
        ("4CB#008E0101", frm + identity + " 4 = 01 01 (257)"),
        ("4CC#000E010106", to + identity + " 6"),
        ("4CB#008E19002031", frm + identity + " 6 = 19 00 20 31 (824180761)"),
        ("4CC#000E010107", to + identity + " 7"),
        ("4CB#80008E0641545633", frm + "fragment 0 (first), 6 bytes"),
        ("4CC#80C000", to + "fragment 0 acknowledged: success"),
        ("4CB#80813132", frm + "fragment 1 (last), 2 bytes, message of 8 bytes: " + identity + ' 7 = "ATV312"'),
        ("4CC#80C100", to + "fragment 1 acknowledged: success"),
        ("4CC#000E8E0102", to + "Get_Attribute_Single class 0x8E instance 1 attribute 2"),
        ("4CB#008E1E00", frm + "Get_Attribute_Single class 0x8E instance 1 attribute 2 = 1E 00 (30)"),
        ("4CC#00108E01020A00", to + acc + " = 0A 00 (10)"),
        ("4CB#0090", frm + acc + ": done"),
        ("4CB#008E0A00", frm + "Get_Attribute_Single class 0x8E instance 1 attribute 2 = 0A 00 (10)"),
        ("4CC#00108E0102FFFF", to + acc + " = FF FF (65535)"),
        ("4CB#009409FF", frm + acc + ": error 0x09 invalid attribute value, additional code 0xFF"),
        ("4CC#004C030103", to + "Release_Group_2_Identifier_Set DeviceNet (0x03) instance 1, choice 0x03 "
                                "(explicit, polled)"),
        ("4CB#00CC", frm + "Release_Group_2_Identifier_Set DeviceNet (0x03) instance 1: done"),
    ])


def poll_until(master, slave, output, wanted, timeout):
    """devicenet-py's poll_io with output until the response is wanted; False at the deadline."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if master.poll_io(slave, output) == wanted:
            return True
    return False


def test_devicenet_py_polls_the_drive_to_1200_rpm_and_releases_it(start_dn, peer, dump, tmp_path):
    mark = dump.mark()
    _, sock = start_dn([25])
    master = peer(0)
    master.connect(quick_connect=True)
    assert master.allocate_unconnected(25, EXPLICIT_AND_POLLED) == DeviceNetBodyFormat.DEVICENET_8_8
    # devicenet-py's own Get/Set_Attribute_Single address the polled connection (class 5,
    # instance 2): Configuring until the expected packet rate is set, the predefined identifiers,
    # the assemblies' 4 bytes.
    assert master.get_attribute_single(25, ConnectionAttribute.STATE) == 1
    assert master.get_attribute_single(25, ConnectionAttribute.INSTANCE_TYPE) == 1
    assert master.get_attribute_single(25, ConnectionAttribute.TRANSPORTCLASS_TRIGGER) == b"\x82"
    assert master.get_attribute_single(25, ConnectionAttribute.CP23_PRODUCED_CONNECTION_ID) == 0x3D9
    assert master.get_attribute_single(25, ConnectionAttribute.CP23_CONSUMED_CONNECTION_ID) == 0x4CD
    assert master.get_attribute_single(25, ConnectionAttribute.PRODUCED_CONNECTION_SIZE) == 4
    assert master.get_attribute_single(25, ConnectionAttribute.CONSUMED_CONNECTION_SIZE) == 4
    # 1001 ms is used as 1008 (a multiple of 8 ms), answered so: the connection is Established.
    master.set_attribute_single(25, ConnectionAttribute.EXPECTED_PACKET_RATE, 1001)
    dump.expect(0x4CB, "0090F003")
    assert master.get_attribute_single(25, ConnectionAttribute.EXPECTED_PACKET_RATE) == 1008
    assert master.get_attribute_single(25, ConnectionAttribute.STATE) == 3
    # Assembly 21: Run fwd, NetCtrl, NetRef, 1200 rpm; 71 answers until At reference at 1200 rpm:
    # Running1, Ready, Ctrl from net, Ref from net, At reference, state 4 (Enabled), 1200 rpm.
    run_forward = bytes.fromhex("6100B004")
    assert poll_until(master, 25, run_forward, bytes.fromhex("F404B004"), timeout=8.0)
    state = wait_state(sock, 25, ns="green", supervisor="enabled", cia402="Operation enabled")
    assert state["speed_rpm"] == 1200
    # devicenet-py's poll without data is an idle poll: answered, and the drive keeps its command.
    assert master.poll_io(25) == bytes.fromhex("F404B004")
    dump.expect(0x4CD, "")
    dump.expect(0x3D9, "F404B004")
    # Run fwd off: a ramp stop to Ready (state 3), speed 0.
    assert poll_until(master, 25, bytes.fromhex("6000B004"), bytes.fromhex("F0030000"), timeout=8.0)
    # Release on message 6: the response, then no connection (NS flashing green).
    assert master.request(25, RELEASE, DEVICENET_CLASS, 1, bytes([0x03]), unconnected=True) == (RELEASE, b"")
    dump.expect(0x4CE, "004C030103")
    dump.expect(0x4CB, "00CC")
    wait_state(sock, 25, ns="flashing-green", speed_rpm=0)

    lines = decoded_trace(dump, mark, tmp_path / "peer-poll.log")
    to, frm = "G2 msg 4 to 25: explicit request from 0: ", "G2 msg 3 from 25: explicit response to 0: "
    connection = "Connection (0x05) instance 2 attribute"
    poll_command = "G2 msg 5 to 25: poll command: assembly 21: "
    poll_response = "G1 msg 15 from 25: poll response: assembly 71: "
    assert_trace(lines, [
        ("4CF#00F30019002031", "G2 msg 7 from 25: duplicate MAC ID check request, port 0, vendor 0x00F3, "
                               "serial number 0x31200019"),
        ("407#00230144332211", "G2 msg 7 from 0: duplicate MAC ID check request, port 0, vendor 0x0123, "
                               "serial number 0x11223344"),
        ("4CE#004B03010300", "G2 msg 6 to 25: unconnected request from 0: Allocate_Master/Slave_Connection_Set "
                             "DeviceNet (0x03) instance 1, choice 0x03 (explicit, polled), allocator 0"),
        ("4CB#00CB00", frm + "Allocate_Master/Slave_Connection_Set DeviceNet (0x03) instance 1: message body "
                             "format 8/8"),
        ("4CC#000E050201", to + f"Get_Attribute_Single {connection} 1"),
        ("4CB#008E01", frm + f"Get_Attribute_Single {connection} 1 = 01 (1)"),
        ("4CB#008E01", frm + f"Get_Attribute_Single {connection} 2 = 01 (1)"),
        ("4CC#000E050202", to + f"Get_Attribute_Single {connection} 2"),
        ("4CC#000E050203", to + f"Get_Attribute_Single {connection} 3"),
        ("4CB#008E82", frm + f"Get_Attribute_Single {connection} 3 = 82 (130)"),
        ("4CC#000E050204", to + f"Get_Attribute_Single {connection} 4"),
        ("4CB#008ED903", frm + f"Get_Attribute_Single {connection} 4 = D9 03 (985)"),
        ("4CC#000E050205", to + f"Get_Attribute_Single {connection} 5"),
        ("4CB#008ECD04", frm + f"Get_Attribute_Single {connection} 5 = CD 04 (1229)"),
        ("4CC#000E050207", to + f"Get_Attribute_Single {connection} 7"),
        ("4CB#008E0400", frm + f"Get_Attribute_Single {connection} 7 = 04 00 (4)"),
        ("4CC#000E050208", to + f"Get_Attribute_Single {connection} 8"),
        ("4CB#008E0400", frm + f"Get_Attribute_Single {connection} 8 = 04 00 (4)"),
        ("4CC#0010050209E903", to + f"Set_Attribute_Single {connection} 9 = E9 03 (1001)"),
        ("4CB#0090F003", frm + f"Set_Attribute_Single {connection} 9: done, answered F0 03 (1008)"),
        ("4CC#000E050209", to + f"Get_Attribute_Single {connection} 9"),
        ("4CB#008EF003", frm + f"Get_Attribute_Single {connection} 9 = F0 03 (1008)"),
        ("4CB#008E03", frm + f"Get_Attribute_Single {connection} 1 = 03 (3)"),
        ("4CD#6100B004", poll_command + "Run fwd, NetCtrl, NetRef, Speed reference 1200 rpm"),
        ("4CD#", "G2 msg 5 to 25: poll command: no data (idle)"),
        ("4CD#6000B004", poll_command + "NetCtrl, NetRef, Speed reference 1200 rpm"),
        ("3D9#F404B004", poll_response + "Running1, Ready, Ctrl from net, Ref from net, At reference, Drive state 4 "
                                         "Enabled, Speed actual 1200 rpm"),
        ("3D9#F0030000", poll_response + "Ready, Ctrl from net, Ref from net, At reference, Drive state 3 Ready, "
                                         "Speed actual 0 rpm"),
        ("4CE#004C030103", "G2 msg 6 to 25: unconnected request from 0: Release_Group_2_Identifier_Set DeviceNet "
                           "(0x03) instance 1, choice 0x03 (explicit, polled)"),
        ("4CB#00CC", frm + "Release_Group_2_Identifier_Set DeviceNet (0x03) instance 1: done"),
    ], ramp=[
        # The ramps' responses: accelerating (state 4) and stopping (state 5), the speed between.
        re.escape(poll_response) + r"Running1, Ready, Ctrl from net, Ref from net, Drive state 4 Enabled, "
                                   r"Speed actual \d+ rpm",
        re.escape(poll_response) + r"Running1, Ready, Ctrl from net, Ref from net, Drive state 5 Stopping, "
                                   r"Speed actual \d+ rpm",
    ])

