# SPDX-License-Identifier: Apache-2.0
"""The daemon's drives beat on one time grid (CO_NODE_HEARTBEAT_GRID, docs/atv312d.md): the heartbeats
of drives whose 1017h were written at different times leave in the same wake-up, each drive stays
periodic, and a drive's first beat comes no later than one period after its write. The wake-up is
the daemon's own count (its loop's frames sent and write calls, from the status SIGUSR1 logs);
times are the kernel's receive timestamps of candump."""

import re
import signal
import time

from conftest import BOOT_TIMEOUT, IFACE, MARKER_ID, PERIODIC_LATENESS, assert_periodic

PERIOD = 0.100
BEATS = 10
SPACING = 0.040
# The loop's line of the status (docs/atv312d.md, "Status surface"), whole lines only: the log is
# read while the daemon may be writing it.
LOOP_COUNTERS = re.compile(
    rf"status: {re.escape(IFACE)}: CAN [^;]*; frames received \d+, sent (\d+), [^;]*; wake-ups \d+, "
    r"sendmmsg calls (\d+)\n"
)
# This test's own frames on the bus: the 1017h writes and candump's readiness marker.
OWN_IDS = (0x604, 0x605, MARKER_ID)


def write_1017(bus, dump, node, ms):
    """1017h = ms by an expedited SDO write; returns the reply, stamped when the write was handled.
    Sent from this process: a cansend started for it under User-Mode Linux reached the bus only
    at the guest's next timer wake-up (drive 4's heartbeat), so every write had drive 4's phase."""
    bus.send(f"{0x600 + node:03X}#2B171000{ms.to_bytes(2, 'little').hex().upper()}0000")
    return dump.expect(0x580 + node, "6017100000000000")


def loop_counters(daemon):
    """(frames sent, write calls) of the daemon's loop at one instant: SIGUSR1 logs the status at
    once. Write calls are `sendmmsg calls` there, a lone frame's `send` included."""
    logged = len(LOOP_COUNTERS.findall(daemon.log()))
    daemon.proc.send_signal(signal.SIGUSR1)
    deadline = time.monotonic() + BOOT_TIMEOUT
    while len(found := LOOP_COUNTERS.findall(daemon.log())) == logged:
        assert time.monotonic() < deadline, f"no status logged after SIGUSR1:\n{daemon.log()}"
        time.sleep(0.01)
    sent, calls = found[logged]
    return int(sent), int(calls)


def daemon_frames(dump, count):
    """The first `count` frames the daemon sent, waited for with a deadline: candump shows one
    socket's frames in the order it wrote them, so frame n is the one that took its loop's count
    of frames sent to n."""

    def sent():
        return [f for f in dump.seen if f.can_id not in OWN_IDS]

    # Heartbeats are what is left to come: two a period.
    deadline = time.monotonic() + ((count - len(sent())) / 2 + 2) * PERIOD + 1.0
    while len(frames := sent()) < count:
        assert dump.next_frame(deadline - time.monotonic()) is not None, f"{count} frames by the deadline: {frames}"
    return frames[:count]


def phase_apart(a, b):
    """How far apart in the period two instants are (0 when a whole number of periods)."""
    offset = (b - a) % PERIOD
    return min(offset, PERIOD - offset)


def heartbeats(dump, since, after, count):
    """The heartbeats of drives 4 and 5 since the mark `since` (those the SDO waits skipped
    included), with their kernel timestamps, until each drive has sent `count` after the instant
    `after`."""
    beats = {4: [], 5: []}

    def take(frame):
        if frame.can_id - 0x700 in beats:
            assert frame.data == b"\x7f", frame
            beats[frame.can_id - 0x700].append(frame)

    def enough():
        return all(len([b for b in sent if b.timestamp > after]) >= count for sent in beats.values())

    for frame in dump.seen[since:]:
        take(frame)
    deadline = time.monotonic() + (count + 2) * PERIOD + 1.0
    while not enough():
        frame = dump.next_frame(deadline - time.monotonic())
        assert frame is not None, f"heartbeats by the deadline: {beats}"
        take(frame)
    return beats


def test_drives_written_at_different_times_beat_in_the_same_wake_up(bus, dump, start_daemon):
    daemon = start_daemon(dump, "--node-id", "4-5")
    since = dump.mark()
    first = write_1017(bus, dump, 4, 100)
    # The second write well inside the period, away from the first's phase (a loaded machine may
    # delay it by about a period: then it is written again, which keeps its phase on the grid).
    for _ in range(3):
        time.sleep(SPACING)
        second = write_1017(bus, dump, 5, 100)
        if phase_apart(first.timestamp, second.timestamp) >= SPACING / 2:
            break
    assert phase_apart(first.timestamp, second.timestamp) >= SPACING / 2, (first, second)

    # The window: from after drive 5's last SDO reply (a lone frame, already counted) until at least
    # BEATS twins more; the test sends nothing meanwhile. Drives woken apart would write each beat
    # by itself (`send`: as many calls as frames); one wake-up for both writes the twins in one call.
    sent_before, calls_before = loop_counters(daemon)
    daemon_frames(dump, sent_before + 2 * BEATS)
    sent_after, calls_after = loop_counters(daemon)
    window = daemon_frames(dump, sent_after)[sent_before:]
    twins = [{f.can_id for f in window[i : i + 2]} for i in range(0, len(window), 2)]
    assert len(window) % 2 == 0 and twins == [{0x704, 0x705}] * len(twins), f"not twin heartbeats: {window}"
    assert all(f.data == b"\x7f" for f in window), window
    assert len(twins) >= BEATS and calls_after - calls_before == len(twins), (
        f"{calls_after - calls_before} write calls for {len(window)} heartbeats ({len(twins)} twins)"
    )

    beats = heartbeats(dump, since, second.timestamp, BEATS)
    # Drive 4 may have beaten before drive 5's (last) write: from that write on, each beat of one
    # has its twin of the other in the same wake-up.
    fours = [b for b in beats[4] if b.timestamp > second.timestamp][:BEATS]
    fives = [b for b in beats[5] if b.timestamp > second.timestamp][:BEATS]
    # The first beat after a write comes within one period of it (CiA 301: the protocol begins
    # with the write; docs/error-control.md).
    assert beats[4][0].timestamp - first.timestamp <= PERIOD + PERIODIC_LATENESS, (first, beats[4][0])
    assert fives[0].timestamp - second.timestamp <= PERIOD + PERIODIC_LATENESS, (second, fives[0])
    # No band on the stamps of twins: frames of one call reach candump when the kernel delivers
    # them, 4.5 ms apart in a loaded CI run, while beats of wake-ups a write's phase apart (20 ms
    # at least) may come each up to PERIODIC_LATENESS late: no band would both always pass the
    # one and always fail the other. The counters above decide.
    assert_periodic(fours, PERIOD, "heartbeat of drive 4")
    assert_periodic(fives, PERIOD, "heartbeat of drive 5")
