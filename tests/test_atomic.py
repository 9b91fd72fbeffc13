"""flightmode.atomic: a file or folder appears whole at its final name or not at all; a writer that
fails midway leaves neither the file nor its temporary."""

from __future__ import annotations

import json

import pytest

from flightmode import atomic


def _entries(folder):
    return sorted(p.name for p in folder.iterdir())


def test_tmp_name_is_hidden_beside_the_target_and_fresh(tmp_path):
    a, b = atomic.tmp_name(tmp_path / "x.parquet"), atomic.tmp_name(tmp_path / "x.parquet")
    assert a.parent == tmp_path and a.name.startswith(".x.parquet.tmp-") and a != b
    assert a.match(atomic.TMP_GLOB)


def test_text_bytes_json_are_written_exactly(tmp_path):
    atomic.write_text("a\nb\n", tmp_path / "sub" / "t.txt")  # the parent is made
    assert (tmp_path / "sub" / "t.txt").read_bytes() == b"a\nb\n"
    atomic.write_bytes(b"\x00\xff", tmp_path / "b.bin")
    assert (tmp_path / "b.bin").read_bytes() == b"\x00\xff"
    atomic.write_json({"k": [1, 2]}, tmp_path / "d.json")
    assert (tmp_path / "d.json").read_text() == json.dumps({"k": [1, 2]}, indent=2) + "\n"
    assert _entries(tmp_path) == ["b.bin", "d.json", "sub"]  # no temporary left


def test_parquet_reads_back_the_same_table(tmp_path):
    pa = pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    t = pa.table({"x": [1.5, 2.5], "s": ["a", "b"]})
    atomic.write_parquet(t, tmp_path / "t.parquet")
    assert pq.read_table(tmp_path / "t.parquet").equals(t)
    assert pq.ParquetFile(tmp_path / "t.parquet").metadata.row_group(0).column(0).compression == "ZSTD"


def test_parquet_pages_carry_checksums_and_a_flipped_bit_is_refused(tmp_path):
    """write_parquet writes a CRC-32 per page and read_parquet checks it. Uncompressed here, so that
    the flipped bit lands in a float the file would otherwise hand back changed (checked below): with
    zstd the decoder might fail on its own and prove nothing."""
    import numpy as np
    import pyarrow as pa
    import pyarrow.parquet as pq

    from flightmode.errors import InputDataError

    x = np.arange(20_000, dtype=np.float64)
    p = atomic.write_parquet(pa.table({"x": x}), tmp_path / "t.parquet", compression="none")
    assert atomic.read_parquet(p, "test table")["x"].to_numpy().tolist() == x.tolist()
    data = bytearray(p.read_bytes())
    data[len(data) // 2] ^= 0x10  # inside the only column's data page (160 kB of the file's ~160 kB)
    p.write_bytes(bytes(data))
    assert not np.array_equal(pq.read_table(p)["x"].to_numpy(), x)  # unchecked: wrong numbers, no error
    with pytest.raises(
        InputDataError, match=r"t\.parquet: not a readable Parquet file, the test table damaged"
    ):
        atomic.read_parquet(p, "test table")
    with pytest.raises(InputDataError, match=r"nothing\.parquet: missing \(the test table\)"):
        atomic.read_parquet(tmp_path / "nothing.parquet", "test table")


def test_a_write_that_fails_midway_leaves_no_file_and_no_temporary(tmp_path):
    target = tmp_path / "out.bin"

    def half(tmp):
        tmp.write_bytes(b"half a file")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError, match="disk full"):
        atomic.write_with(target, half)
    assert _entries(tmp_path) == []


def test_a_failed_rewrite_keeps_the_old_file(tmp_path):
    target = tmp_path / "out.txt"
    atomic.write_text("old", target)

    def half(tmp):
        tmp.write_text("new but cut")
        raise KeyboardInterrupt  # BaseException too: a Ctrl-C mid-write

    with pytest.raises(KeyboardInterrupt):
        atomic.write_with(target, half)
    assert target.read_text() == "old" and _entries(tmp_path) == ["out.txt"]


def test_a_json_document_that_cannot_be_encoded_leaves_nothing(tmp_path):
    with pytest.raises(TypeError):
        atomic.write_json({"x": object()}, tmp_path / "d.json")
    assert _entries(tmp_path) == []


def test_staged_folder_appears_whole_and_replaces_the_old_one(tmp_path):
    final = tmp_path / "run"
    with atomic.staged_folder(final) as stage:
        (stage / "a.txt").write_text("1")
        assert not final.exists() and stage.name.startswith(".run.tmp-")
    assert _entries(final) == ["a.txt"]
    with atomic.staged_folder(final) as stage:
        (stage / "b.txt").write_text("2")
    assert _entries(final) == ["b.txt"] and _entries(tmp_path) == ["run"]  # the old folder removed


def test_a_staged_folder_that_fails_leaves_the_old_one_and_no_stage(tmp_path):
    final = tmp_path / "run"
    final.mkdir()
    (final / "keep.txt").write_text("kept")
    with pytest.raises(ValueError), atomic.staged_folder(final) as stage:
        (stage / "half.txt").write_text("x")
        raise ValueError("the flight diverged")
    assert _entries(tmp_path) == ["run"] and _entries(final) == ["keep.txt"]
