"""Movebank e-obs CSV (seed 003 section 5.4): byte-exact round trips, the typed bursts, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.movebank import (
    DECODER_COLUMNS,
    TimestampStyle,
    bursts_to_file,
    format_movebank,
    parse_movebank,
    read_movebank,
    write_movebank,
)
from flightmode.errors import InputDataError, SensorError

# seed 003 section 5.4, the decoder's first line (wrapped in the note after "acceleration-sampling-")
NOTE_HEADER = (
    "key-bin-checksum,tag-serial-number,start-timestamp,acceleration-sampling-frequency-per-axis,"
    "acceleration-axes,accelerations-raw"
)


def test_the_decoder_header_is_the_notes():
    assert ",".join(DECODER_COLUMNS) == NOTE_HEADER


def test_real_file_round_trips_byte_for_byte(real_movebank, tmp_path):
    data = real_movebank.read_bytes()
    f = read_movebank(real_movebank)
    assert format_movebank(f) == data
    out = write_movebank(f, tmp_path / "again.csv")
    assert out.read_bytes() == data
    assert read_movebank(out) == f


def test_real_file_content(real_movebank):
    """What the file holds (FACTS.md, e-obs): 9 tags (animals), each with one GPS fix and 5 bursts
    of 2-axis XY data at 5 Hz per axis, 120 interleaved counts = 60 per axis, one burst every 15 min."""
    f = read_movebank(real_movebank)
    assert len(f.rows) == 54 and len(f.bursts) == 45
    gps = [r for r in f.rows if r.burst is None]
    assert len(gps) == 9
    assert {r.get(f.header, "sensor-type-id") for r in gps} == {"653"}  # Movebank's id of 'gps'
    for b in f.bursts:
        assert (b.axes, b.rate_hz, b.raw.shape) == ("XY", 5.0, (60, 2))
        assert b.duration_s == 12.0 and b.total_rate_hz == 10.0  # the note's 10 Hz minimum (section 4.1)
    first = f.bursts[0]
    assert first.tag_id == "4266-84831108" and first.checksum == 1951106657
    assert first.start_time == np.datetime64("2008-07-27T00:00:56", "ns")
    np.testing.assert_array_equal(first.raw[:2], [[1856, 1900], [1816, 1931]])  # "1856 1900 1816 1931 ..."
    assert f.timestamp_style == TimestampStyle(sep=" ", fraction_digits=0, suffix="+00:00")
    by_tag: dict[str, list] = {}
    for b in f.bursts:
        by_tag.setdefault(b.tag_id, []).append(b.start_time)
    assert len(by_tag) == 9
    for times in by_tag.values():
        # ACC interval 15 min: after a first burst at the GPS fix, the bursts start on the quarter
        # hours, all to the second but one (tag 1163-1163 at 00:30:03)
        later_s = np.sort(np.array(times))[1:] - np.datetime64("2008-07-27T00:00:00", "ns")
        off_s = (later_s / np.timedelta64(1, "s")) % 900
        assert len(times) == 5 and np.all(np.minimum(off_s, 900 - off_s) <= 3)


def _burst(axes: str, n: int, rng, t="2014-05-11T10:00:00.250", rate=3.33, tag="2242") -> AccBurst:
    return AccBurst(
        tag, np.datetime64(t), axes, rate, rng.integers(0, 4096, (n, len(axes))), int(rng.integers(0, 2**32))
    )


def test_simulated_bursts_write_and_read_back_identically(tmp_path):
    rng = np.random.default_rng(3)
    bursts = [
        _burst(a, n, rng)
        for a, n in [("XYZ", 166), ("XY", 249), ("XZ", 1), ("YZ", 7), ("X", 33), ("Y", 2), ("Z", 264)]
    ]
    bursts.append(_burst("XYZ", 264, rng, rate=33.33, t="2014-05-11T10:00:01"))
    f = bursts_to_file(bursts)
    p = write_movebank(f, tmp_path / "tag2242_acc.txt")
    text = p.read_text()
    assert text.splitlines()[0] == NOTE_HEADER
    assert text.splitlines()[1].split(",")[2:5] == ["2014-05-11 10:00:00.250", "3.33", "XYZ"]
    back = read_movebank(p)
    assert back.bursts == tuple(bursts) and back == f
    assert format_movebank(back) == p.read_bytes()


def test_crlf_bom_and_no_final_newline_round_trip():
    text = "\ufeff" + NOTE_HEADER + "\r\n1,2242,2014-05-11 10:00:00Z,5.0,XY,0 4095 2048 2047"
    f = parse_movebank(text.encode())
    assert (f.newline, f.final_newline, f.bom) == ("\r\n", False, True)
    assert f.bursts[0].start_time == np.datetime64("2014-05-11T10:00:00")
    assert format_movebank(f) == text.encode()


def test_a_utc_offset_is_held_in_utc_and_written_back():
    f = parse_movebank(NOTE_HEADER + "\n1,2242,2014-05-11 12:00:00.5+02:00,5.0,Z,100\n")
    assert f.bursts[0].start_time == np.datetime64("2014-05-11T10:00:00.500")
    assert format_movebank(f).decode().endswith("2014-05-11 12:00:00.5+02:00,5.0,Z,100\n")


def test_a_burst_the_style_cannot_hold_is_refused():
    rng = np.random.default_rng(0)
    f = bursts_to_file([_burst("X", 3, rng, t="2014-05-11T10:00:00.0001")])  # 0.1 ms; the style holds ms
    with pytest.raises(InputDataError, match="more sub-second digits than the file's timestamps hold"):
        format_movebank(f)


GOOD = "7,2242,2014-05-11 10:00:00.000,10.0,XY,2048 2049 2050 2051"


def _text(bad_line: str, header: str = NOTE_HEADER) -> str:
    return f"{header}\n{GOOD}\n{bad_line}\n"


# (the bad data line 3 or header, the one-line message expected)
BAD = [
    pytest.param(
        _text(GOOD, NOTE_HEADER.replace(",accelerations-raw", "")),
        r"line 1: header has no column 'accelerations-raw'.*seed 003 section 5.4",
        id="missing-column",
    ),
    pytest.param(
        _text(GOOD, NOTE_HEADER.replace("tag-serial-number", "tag-serial-numbr")),
        r"line 1: header has no column 'tag-serial-number' \(did you mean \"tag-serial-numbr\"\?\)",
        id="misspelt-column",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,2048 2049 2050"),
        r"line 3: accelerations-raw holds 3 samples, not a multiple of the 2 axes 'XY'",
        id="odd-count",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XYZ,1 2 3 4"),
        r"line 3: accelerations-raw holds 4 samples, not a multiple of the 3 axes 'XYZ'",
        id="count-xyz",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,2048 4096 2050 2051"),
        r"line 3: accelerations-raw sample #2 is 4096, outside the ADC's 0-4095",
        id="above-4095",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,2048 2049 -1 2051"),
        r"line 3: accelerations-raw sample #3 is -1, outside the ADC's 0-4095",
        id="negative",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,2048 2049 2050 2O51"),
        r"line 3: accelerations-raw sample #4 is '2O51', not an integer count",
        id="non-numeric",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,2048  2050 2051"),
        r"line 3: accelerations-raw sample #2 is '', not an integer count",
        id="double-space",
    ),
    pytest.param(
        _text("4294967296,2242,2014-05-11 10:00:01.000,10.0,XY,1 2"),
        r"line 3: key-bin-checksum '4294967296' is not an unsigned 32-bit integer",
        id="checksum-too-big",
    ),
    pytest.param(
        _text("-1,2242,2014-05-11 10:00:01.000,10.0,XY,1 2"),
        r"line 3: key-bin-checksum '-1' is not an unsigned 32-bit integer",
        id="checksum-negative",
    ),
    pytest.param(
        _text("ab12,2242,2014-05-11 10:00:01.000,10.0,XY,1 2"),
        r"line 3: key-bin-checksum 'ab12' is not an unsigned 32-bit integer .*does not say how",
        id="checksum-text",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,YX,1 2"),
        r"line 3: acceleration-axes 'YX' must be X, Y and/or Z in alphabetical order",
        id="axes-order",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XW,1 2"),
        r"line 3: acceleration-axes 'XW' must be",
        id="axes-unknown",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,0,XY,1 2"),
        r"line 3: acceleration-sampling-frequency-per-axis '0' is not a sampling frequency",
        id="rate-zero",
    ),
    pytest.param(
        _text("7,2242,11.6.2007 21:01:00,10.0,XY,1 2"),
        r"line 3: start-timestamp '11.6.2007 21:01:00' is not a timestamp",
        id="timestamp",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01,10.0,XY,1 2"),
        r"line 3: start-timestamp '2014-05-11 10:00:01' is not written like the first burst's "
        r"\(YYYY-MM-DD HH:MM:SS.fff\)",
        id="mixed-timestamps",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY"),
        r"line 3: 5 fields, the header \(line 1\) has 6",
        id="short-line",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,"),
        r"line 3: acceleration-axes is 'XY' but accelerations-raw is empty",
        id="no-samples",
    ),
    pytest.param(
        _text("7,tag9,2014-05-11 10:00:01.000,10.0,XY,1 2"),
        r"line 3: tag-serial-number 'tag9' is not a tag id \(the decoder writes the tag number\)",
        id="tag",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.00,XY,1 2"),
        r"line 3: column 'acceleration-sampling-frequency-per-axis' reads '10.00' but would be written "
        r"back as '10.0'",
        id="not-canonical-rate",
    ),
    pytest.param(
        _text("7,2242,2014-05-11 10:00:01.000,10.0,XY,0100 2"),
        r"line 3: column 'accelerations-raw' reads '0100 2' but would be written back as '100 2'",
        id="not-canonical-sample",
    ),
    pytest.param(_text(""), r"line 3: empty line", id="empty-line"),
]


@pytest.mark.parametrize("text, message", BAD)
def test_bad_input_raises_one_line_naming_the_line(text, message):
    with pytest.raises(InputDataError, match=message) as e:
        parse_movebank(text, source="tag2242_acc.txt")
    assert str(e.value).startswith("tag2242_acc.txt: line ") and "\n" not in str(e.value)


def test_bad_real_file_lines_name_the_file_and_line(real_movebank, tmp_path):
    lines = real_movebank.read_text().split("\n")
    bad = tmp_path / "bad.csv"
    # line 5 of the file (a burst): its 7th count made 5000
    fields = lines[4].split(",")
    counts = fields[20].split(" ")
    counts[6] = "5000"
    fields[20] = " ".join(counts)
    bad.write_text("\n".join(lines[:4] + [",".join(fields)] + lines[5:]))
    with pytest.raises(
        InputDataError, match=rf"^{bad}: line 5: eobs:accelerations-raw sample #7 is 5000, outside"
    ):
        read_movebank(bad)
    header = lines[0].replace("eobs:acceleration-axes,", "")
    bad.write_text("\n".join([header] + lines[1:]))
    with pytest.raises(InputDataError, match=r"line 1: header has no column 'eobs:acceleration-axes'"):
        read_movebank(bad)
    # a GPS row (line 2) with a checksum that is not an unsigned 32-bit integer
    fields = lines[1].split(",")
    fields[5] = "39265179390"
    bad.write_text("\n".join([lines[0], ",".join(fields)] + lines[2:]))
    with pytest.raises(
        InputDataError, match=r"line 2: eobs:key-bin-checksum '39265179390' is not an unsigned 32-bit"
    ):
        read_movebank(bad)


def test_a_burst_refuses_what_the_note_does_not_allow():
    t = np.datetime64("2014-05-11T10:00:00")
    with pytest.raises(SensorError, match="alphabetical order"):
        AccBurst("1", t, "ZX", 10.0, np.zeros((2, 2), int), 0)
    with pytest.raises(SensorError, match="outside the ADC's 0-4095"):
        AccBurst("1", t, "X", 10.0, np.full((2, 1), 4096), 0)
    with pytest.raises(SensorError, match=r"shape must be \(n >= 1, 2\)"):
        AccBurst("1", t, "XY", 10.0, np.zeros(4, int), 0)
    with pytest.raises(SensorError, match="unsigned 32-bit"):
        AccBurst("1", t, "X", 10.0, np.zeros((2, 1), int), 2**32)
