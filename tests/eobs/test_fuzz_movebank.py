"""Property-based fuzzing of the Movebank e-obs reader (issue 54, item 5): any bytes (empty, not UTF-8,
a BOM alone), CSV of random structure under the real column names, and valid files (the decoder's
layout and Movebank's export, simulated bursts of any axes, rate and length) with bytes flipped,
inserted, deleted or cut off. Whatever the input, the reader returns a file or raises InputDataError
naming the source on one line; a file it returns writes back byte for byte. The number of examples:
tests/fuzz.py (FLIGHTMODE_FUZZ_EXAMPLES; 200 in CI).
"""

from __future__ import annotations

import numpy as np
from hypothesis import event, example, given
from hypothesis import strategies as st

from flightmode.eobs.burst import AXES_SETS, AccBurst
from flightmode.eobs.movebank import (
    DECODER_COLUMNS,
    EOBS_PREFIX,
    bursts_to_file,
    format_movebank,
    parse_movebank,
    read_movebank,
)
from flightmode.errors import FlightmodeError, InputDataError
from tests.fuzz import fuzz_settings

# Movebank's export layout, cut down from the albatross study's (public Movebank study 2911040): a GPS
# fix without acceleration, then a 2-axis burst
EXPORT = (
    b"sensor-type-id,individual-local-identifier,eobs:key-bin-checksum,eobs:start-timestamp,timestamp,"
    b"eobs:acceleration-axes,eobs:acceleration-sampling-frequency-per-axis,eobs:accelerations-raw,"
    b"location-long,location-lat\n"
    b"653,4266-84831108,3926517939,2008-07-27 00:00:00+00:00,2008-07-27 00:00:56.000000000+00:00,,,,"
    b"-78.6763552,-9.06721\n"
    b"2365683,4266-84831108,1951106657,2008-07-27 00:00:56+00:00,2008-07-27 00:00:56.000000000+00:00,XY,5.0,"
    b"1856 1900 1816 1931,,\n"
)
DECODER = ",".join(DECODER_COLUMNS) + "\n7,2242,2014-05-11 10:00:00.000,10.0,XY,2048 2049 2050 2051\n"
COLUMNS = (*DECODER_COLUMNS, *(EOBS_PREFIX + c for c in DECODER_COLUMNS), "tag-local-identifier", "timestamp")


def _read(data: bytes | str) -> None:
    try:
        f = parse_movebank(data, source="<fuzz>")
    except InputDataError as e:
        assert str(e).startswith("<fuzz>: ") and "\n" not in str(e), str(e)
        event("InputDataError")
        return
    event("read")
    raw = data.encode() if isinstance(data, str) else data
    assert format_movebank(f) == raw  # what it accepts it writes back byte for byte


@st.composite
def bursts(draw):
    axes = draw(st.sampled_from(AXES_SETS))
    n = draw(st.integers(1, 12))
    raw = np.array(draw(st.lists(st.integers(0, 4095), min_size=n * len(axes), max_size=n * len(axes))))
    ms = draw(st.integers(0, 10**12))  # start times from 1970 to 2001, to the millisecond
    rate = draw(st.sampled_from([1.0, 5.0, 10.0, 20.0, 33.33, 100.0]))
    return AccBurst(
        str(draw(st.integers(0, 99999))),
        np.datetime64(ms, "ms").astype("datetime64[ns]"),
        axes,
        rate,
        raw.reshape(n, len(axes)),
        draw(st.integers(0, 2**32 - 1)),
    )


@st.composite
def valid_files(draw) -> bytes:
    kind = draw(st.sampled_from(["simulated", "export", "decoder"]))
    if kind == "export":
        return EXPORT
    if kind == "decoder":
        return DECODER.encode()
    return format_movebank(bursts_to_file(draw(st.lists(bursts(), min_size=1, max_size=4))))


@st.composite
def damaged_files(draw) -> bytes:
    """A valid file with 1-3 byte edits: a byte changed, bytes inserted (any, or CSV's own , " \\r
    \\n), a slice deleted, the file cut short."""
    b = bytearray(draw(valid_files()))
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(b)))
        op = draw(st.sampled_from(["set", "insert", "delete", "cut"]))
        if op == "set" and i < len(b):
            b[i] = draw(st.integers(0, 255))
        elif op == "insert":
            b[i:i] = draw(
                st.one_of(st.binary(max_size=6), st.sampled_from([b",", b'"', b"\r", b"\n", b"\xff"]))
            )
        elif op == "delete":
            del b[i : i + draw(st.integers(1, 20))]
        else:
            del b[i:]
    return bytes(b)


field = st.one_of(
    st.text(max_size=10), st.sampled_from(["", "XY", "XYZ", "5.0", "0", "4095", "2014-05-11 10:00:00"])
)


@st.composite
def random_csv(draw) -> str:
    header = draw(st.lists(st.one_of(st.sampled_from(COLUMNS), st.text(max_size=8)), min_size=1, max_size=8))
    rows = draw(st.lists(st.lists(field, min_size=0, max_size=len(header) + 1), max_size=4))
    nl = draw(st.sampled_from(["\n", "\r\n"]))
    return nl.join(",".join(r) for r in [header, *rows]) + draw(st.sampled_from(["", nl]))


@fuzz_settings()
@given(st.binary(max_size=200))
@example(b"")
@example(b"\n")
@example(b"\xef\xbb\xbf")  # a BOM alone
@example(b"\xff\xfe" + ",".join(DECODER_COLUMNS).encode("utf-16-le"))  # UTF-16
@example(",".join(DECODER_COLUMNS).encode() + b"\n7,2242,2014-05-11 10:00:00\xe9,10.0,XY,1 2\n")  # Latin-1
def test_movebank_reader_any_bytes(data):
    _read(data)


@fuzz_settings()
@given(random_csv())
def test_movebank_reader_random_csv(text):
    _read(text)


@fuzz_settings()
@given(damaged_files())
def test_movebank_reader_damaged_files(data):
    _read(data)


def test_empty_and_non_utf8_files_name_the_file(tmp_path):
    """The file reader on disk: an empty file and a Latin-1 one are one-line InputDataErrors naming the
    file; a folder is one too."""
    for name, data, says in [
        ("empty.csv", b"", "line 1: empty"),
        ("latin1.csv", DECODER.replace("2242", "caf\xe9").encode("latin-1"), "line 2: not UTF-8"),
    ]:
        p = tmp_path / name
        p.write_bytes(data)
        try:
            read_movebank(p)
        except FlightmodeError as e:
            assert str(e).startswith(f"{p}: {says}"), str(e)
        else:
            raise AssertionError(f"{name} was read")
    try:
        read_movebank(tmp_path)
    except InputDataError as e:
        assert str(e).startswith(f"{tmp_path}: cannot read"), str(e)
