"""Damaged bags: a corrupt chunk, a truncated file and a smashed record header still replay
their readable messages, and the skipped messages are counted exactly."""

from __future__ import annotations

from pathlib import Path

import pytest
from ais_replay_helpers import make_states, write_bag
from mcap.reader import make_reader
from shiproute_ais_replay.bag.bagreader import BagReader
from shiproute_ais_replay.errors import BagFormatError
from shiproute_ais_replay.replay.engine import ReplayConfig, ReplayEngine

N = 1500


@pytest.fixture
def chunked_bag(tmp_path: Path) -> tuple[Path, Path, list]:
    """ShipState-only bag in ~20 small chunks; returns (dir, .mcap, chunk indexes)."""
    path = write_bag(tmp_path / "v", make_states(N), chunk_bytes=8000, with_fix=False)
    mcap_file = path / "v.mcap"
    with mcap_file.open("rb") as f:
        chunks = sorted(make_reader(f).get_summary().chunk_indexes,
                        key=lambda c: c.chunk_start_offset)
    assert len(chunks) >= 10
    return path, mcap_file, chunks


def _messages_in(mcap_file: Path, chunk) -> int:
    """Messages in a chunk of the 1 Hz test bag: one per second of its time span."""
    return (chunk.message_end_time - chunk.message_start_time) // 10**9 + 1


def _read_all(path: Path) -> tuple[list[int], dict]:
    reader = BagReader(path)
    times = [m.time_ns for m in reader.messages()]
    return times, reader.report()


def _patch(path: Path, offset: int, data: bytes) -> None:
    with path.open("r+b") as f:
        f.seek(offset)
        f.write(data)


def test_corrupt_chunk_is_skipped_and_counted(chunked_bag):
    path, mcap_file, chunks = chunked_bag
    bad = chunks[4]
    lost = _messages_in(mcap_file, bad)
    # overwrite bytes in the middle of the chunk's compressed records
    mid = bad.chunk_start_offset + bad.chunk_length // 2
    _patch(mcap_file, mid, b"\xff" * 64)
    times, rep = _read_all(path)
    assert len(times) == N - lost
    assert rep["chunks_skipped"] == 1
    assert rep["messages_skipped"] == lost
    assert times == sorted(times)
    # the neighbours of the bad chunk are intact
    assert bad.message_start_time - 10**9 in times and bad.message_end_time + 10**9 in times


def test_truncated_bag_replays_complete_chunks(chunked_bag):
    path, mcap_file, chunks = chunked_bag
    cut = chunks[7].chunk_start_offset + chunks[7].chunk_length // 3
    with mcap_file.open("r+b") as f:
        f.truncate(cut)
    expected = chunks[7].message_start_time  # first lost message time
    times, rep = _read_all(path)
    assert times and max(times) < expected
    assert len(times) == (expected - times[0]) // 10**9  # 1 Hz, nothing lost before the cut
    assert rep["truncated"] is True
    assert rep["messages_skipped"] == N - len(times)  # metadata.yaml knows the total


def test_smashed_record_header_resyncs_at_next_chunk(chunked_bag):
    path, mcap_file, chunks = chunked_bag
    bad = chunks[3]
    lost = _messages_in(mcap_file, bad)
    _patch(mcap_file, bad.chunk_start_offset, b"\x6e" + (2**62).to_bytes(8, "little"))
    times, rep = _read_all(path)
    assert rep["resyncs"] >= 1
    # everything but the smashed chunk comes back
    assert len(times) == N - lost
    assert rep["messages_skipped"] == lost


def test_replay_engine_publishes_readable_part_of_corrupt_bag(chunked_bag):
    path, mcap_file, chunks = chunked_bag
    lost = _messages_in(mcap_file, chunks[2])
    _patch(mcap_file, chunks[2].chunk_start_offset + chunks[2].chunk_length // 2, b"\0" * 32)
    engine = ReplayEngine(path, ReplayConfig(rate=0.0))
    events = []
    engine.run(events.append, lambda _ns: None)
    assert len(events) == N - lost
    st = engine.status()
    assert st["messages_skipped"] == lost and st["finished"]


def test_not_an_mcap_file_is_a_clear_error(tmp_path: Path):
    bad = tmp_path / "x.mcap"
    bad.write_bytes(b"hello world, not mcap")
    with pytest.raises(BagFormatError, match=r"x\.mcap"):
        list(BagReader(bad).messages())


def test_info_scans_truncated_bare_mcap_without_summary(tmp_path: Path):
    from shiproute_ais_replay.cli import bag_info

    path = write_bag(tmp_path / "t.mcap", make_states(400), chunk_bytes=4000, with_fix=False)
    size = path.stat().st_size
    with path.open("r+b") as f:
        f.truncate(size * 2 // 3)
    info = bag_info(path)
    assert info["scan"]["truncated"] is True
    n = info["message_count"]
    assert 0 < n < 400
    assert info["duration_s"] == pytest.approx(n - 1)  # 1 Hz, contiguous from the start


def test_engine_start_offset_and_loop(tmp_path: Path):
    path = write_bag(tmp_path / "l", make_states(100), with_fix=False)
    engine = ReplayEngine(path, ReplayConfig(rate=0.0, start_offset_s=90.0, loop=True))
    events = []

    def emit(ev):
        events.append(ev.time_ns)
        if len(events) == 25:
            engine.stop()

    engine.run(emit, lambda _ns: None)
    t0 = events[0]
    assert [(t - t0) // 10**9 for t in events[:12]] == [*range(10), 0, 1]  # 90..99, 90, 91
    assert engine.loops == 2
