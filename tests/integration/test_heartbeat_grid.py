"""The daemon's drives beat on one time grid (CO_NODE_HEARTBEAT_GRID, docs/atv312d.md): the heartbeats
of drives whose 1017h were written at different times leave in the same wake-up, each drive stays
periodic, and a drive's first beat comes no later than one period after its write. Times are the
kernel's receive timestamps of candump."""

import time

from conftest import PERIODIC_LATENESS, assert_periodic, cansend

PERIOD = 0.100
# Frames of one sendmmsg reach candump microseconds apart; a wake-up for each drive would put
# their heartbeats as far apart as the writes (40 ms here).
SAME_WAKE_UP = 0.002
BEATS = 10
SPACING = 0.040


def write_1017(dump, node, ms):
    """1017h = ms by an expedited SDO write; returns the reply, stamped when the write was handled."""
    cansend(f"{0x600 + node:03X}#2B171000{ms.to_bytes(2, 'little').hex().upper()}0000")
    return dump.expect(0x580 + node, "6017100000000000")


def phase_apart(a, b):
    """How far apart in the period two instants are (0 when a whole number of periods)."""
    offset = (b - a) % PERIOD
    return min(offset, PERIOD - offset)


def heartbeats(dump, since, nodes, count):
    """The first `count` heartbeats of each node after the mark `since`, with their kernel
    timestamps (those the SDO waits skipped included)."""
    beats = {node: [] for node in nodes}

    def take(frame):
        node = frame.can_id - 0x700
        if node in beats and len(beats[node]) < count:
            assert frame.data == b"\x7f", frame
            beats[node].append(frame)

    for frame in dump.seen[since:]:
        take(frame)
    deadline = time.monotonic() + (count + 2) * PERIOD + 1.0
    while any(len(b) < count for b in beats.values()):
        frame = dump.next_frame(deadline - time.monotonic())
        assert frame is not None, f"heartbeats by the deadline: {beats}"
        take(frame)
    return beats


def test_drives_written_at_different_times_beat_in_the_same_wake_up(dump, start_daemon):
    start_daemon(dump, "--node-id", "4-5")
    since = dump.mark()
    first = write_1017(dump, 4, 100)
    # The second write well inside the period, away from the first's phase (a loaded machine may
    # delay it by about a period: then it is written again, which keeps its phase on the grid).
    for _ in range(3):
        time.sleep(SPACING)
        second = write_1017(dump, 5, 100)
        if phase_apart(first.timestamp, second.timestamp) >= SPACING / 2:
            break
    assert phase_apart(first.timestamp, second.timestamp) >= SPACING / 2, (first, second)

    beats = heartbeats(dump, since, (4, 5), BEATS + 1)
    # The first beat after a write comes within one period of it (CiA 301: the protocol begins
    # with the write; docs/error-control.md).
    assert beats[4][0].timestamp - first.timestamp <= PERIOD + PERIODIC_LATENESS, (first, beats[4][0])
    assert beats[5][0].timestamp - second.timestamp <= PERIOD + PERIODIC_LATENESS, (second, beats[5][0])
    # Drive 4 may have beaten once before drive 5's write: from drive 5's first beat on, each beat
    # of one has its twin of the other in the same wake-up.
    fours = [b for b in beats[4] if b.timestamp > beats[5][0].timestamp - PERIOD / 2][:BEATS]
    fives = beats[5][:BEATS]
    gaps = [round(abs(a.timestamp - b.timestamp) * 1000, 3) for a, b in zip(fours, fives)]
    assert len(fours) == BEATS and max(gaps) <= SAME_WAKE_UP * 1000, f"ms between twin beats: {gaps}"
    assert_periodic(fours, PERIOD, "heartbeat of drive 4")
    assert_periodic(fives, PERIOD, "heartbeat of drive 5")
