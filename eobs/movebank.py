"""The Movebank e-obs CSV format: read and write, byte for byte (seed 003 section 5.4).

Two layouts of the same fields are read:

* the data decoder's Movebank option ('m', file ``tagXXX_acc.txt``), whose first line the note gives
  as ``key-bin-checksum,tag-serial-number,start-timestamp,acceleration-sampling-frequency-per-axis,
  acceleration-axes,accelerations-raw`` (the note's text wraps this header after
  "acceleration-sampling-": a line break of the PDF, read here as one column name);
* Movebank's own export, where the same fields carry an ``eobs:`` prefix next to Movebank's columns
  (``sensor-type-id``, ``timestamp``, ``location-long`` ...) and GPS fixes share the file as rows
  without acceleration (empty ``eobs:acceleration-axes`` and ``eobs:accelerations-raw``). The export
  names no ``tag-serial-number``; the burst's tag id is ``tag-local-identifier`` or, in an export
  without it (the albatross study), ``individual-local-identifier``.

The fields (section 5.4): ``key-bin-checksum`` "a checksum of the original binary data";
``tag-serial-number`` the tag id; ``start-timestamp`` when the burst begins;
``acceleration-sampling-frequency-per-axis`` in Hz; ``acceleration-axes`` X and/or Y and/or Z;
``accelerations-raw`` the samples "between 0 and 4095", one per enabled axis in alphabetical order
(written space-separated, as Movebank writes them; the note shows no data line).

The checksum: the note does not say how it is computed (nor over which bytes of the binary file,
which a CSV does not hold), so it is not verified: it is only checked to be an unsigned 32-bit
integer, the width of every value in Movebank's files. Simulated bursts carry 0.

Byte-exact round trip: a row keeps the text of every column it does not model; the modelled columns
(the six above) are written back from the typed burst, with the file's newline, BOM, final newline
and timestamp style (separator, fraction digits, UTC-offset suffix, read from the first burst). The
reader re-renders every line it accepts and refuses, naming the line and the column, text it would
not write back identically (``5.00`` for a rate written ``5.0``, a leading zero in a sample, a field
quoted without need), so ``format_movebank(read_movebank(p)) == p.read_bytes()`` for every file it
reads. Fields quoted over several lines are not supported (Movebank's e-obs fields have none).
"""

from __future__ import annotations

import csv
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flightmode.eobs.burst import AXES_SETS, UINT32_MAX, AccBurst
from flightmode.eobs.tag import ADC_MAX_COUNT, ADC_MIN_COUNT
from flightmode.errors import InputDataError, did_you_mean

# seed 003 section 5.4, the decoder's first line (its line wrap joined)
DECODER_COLUMNS = (
    "key-bin-checksum",
    "tag-serial-number",
    "start-timestamp",
    "acceleration-sampling-frequency-per-axis",
    "acceleration-axes",
    "accelerations-raw",
)
EOBS_PREFIX = "eobs:"
# Movebank export: the note's fields but the tag id carry the prefix; the tag id is one of these
EXPORT_TAG_ID_COLUMNS = ("tag-local-identifier", "individual-local-identifier")

_TS = re.compile(
    r"(\d{4}-\d{2}-\d{2})([ T])(\d{2}:\d{2}:\d{2})(?:\.(\d{1,9}))?(Z|[+-]\d{2}:?\d{2})?", re.ASCII
)
_RAW_FAST = re.compile(r"\d+(?: \d+)*", re.ASCII)
_INT = re.compile(r"[+-]?\d+", re.ASCII)


@dataclass(frozen=True, slots=True)
class Columns:
    """Where the six modelled fields sit in a header (indices into it)."""

    checksum: int
    tag_id: int
    start: int
    rate: int
    axes: int
    raw: int
    decoder_layout: bool  # True: the decoder's unprefixed header; False: Movebank's export

    def indices(self) -> tuple[int, ...]:
        return (self.checksum, self.tag_id, self.start, self.rate, self.axes, self.raw)


def find_columns(header: tuple[str, ...]) -> Columns:
    """Locate the modelled fields; InputDataError (line 1) naming a missing required column."""
    if len(set(header)) != len(header):
        dup = next(h for i, h in enumerate(header) if h in header[:i])
        raise InputDataError(f"line 1: header names column {dup!r} twice")
    decoder = not any(h.startswith(EOBS_PREFIX) for h in header)  # the decoder's file has no prefixed column
    names: tuple[str, ...]
    if decoder:
        names = DECODER_COLUMNS
    else:
        tag = next((c for c in EXPORT_TAG_ID_COLUMNS if c in header), EXPORT_TAG_ID_COLUMNS[0])
        names = tuple(tag if c == "tag-serial-number" else EOBS_PREFIX + c for c in DECODER_COLUMNS)
    for name in names:
        if name not in header:
            required = ", ".join(names) if decoder else ", ".join(n for n in names if n != names[1])
            extra = "" if decoder else f" and one of {' / '.join(EXPORT_TAG_ID_COLUMNS)}"
            raise InputDataError(
                f"line 1: header has no column {name!r}{did_you_mean(name, header)}; an e-obs Movebank file "
                f"needs {required}{extra} (seed 003 section 5.4)"
            )
    # names holds the six fields in Columns' order (mypy cannot tell a list's length: unpacked by name)
    checksum, tag_id, start, rate, axes, raw = (header.index(n) for n in names)
    return Columns(checksum, tag_id, start, rate, axes, raw, decoder)


@dataclass(frozen=True, slots=True)
class TimestampStyle:
    """How a file writes the start timestamp: ``YYYY-MM-DD<sep>HH:MM:SS[.f...]<suffix>``.

    suffix: '' (no zone: read as UTC), 'Z', or a UTC offset such as '+00:00' (times are held in UTC
    and written back in the offset's local time)."""

    sep: str = " "
    fraction_digits: int = 3
    suffix: str = ""

    @property
    def offset(self) -> np.timedelta64:
        s = self.suffix
        if s in ("", "Z"):
            return np.timedelta64(0, "m")
        sign = -1 if s[0] == "-" else 1
        hh, mm = int(s[1:3]), int(s[-2:])
        return np.timedelta64(sign * (60 * hh + mm), "m")

    @property
    def pattern(self) -> str:
        frac = "." + "f" * self.fraction_digits if self.fraction_digits else ""
        return f"YYYY-MM-DD{self.sep}HH:MM:SS{frac}{self.suffix}"

    def format(self, t: np.datetime64) -> str:
        """The text of ``t`` (UTC) in this style; InputDataError if the style cannot hold it exactly."""
        # numpy's stubs reject np.datetime64(datetime64, unit), numpy's documented unit conversion
        # (fixed in numpy/numpy#31883: unused-ignore keeps a numpy with the fix quiet)
        t_ns = np.datetime64(t, "ns")  # type: ignore[call-overload, unused-ignore]
        local = t_ns + self.offset
        secs = local.astype("datetime64[s]")
        frac_ns = int((local - secs) // np.timedelta64(1, "ns"))
        text = str(secs).replace("T", self.sep)
        digits = f"{frac_ns:09d}"
        if digits[self.fraction_digits :].strip("0"):
            raise InputDataError(
                f"start time {np.datetime_as_string(t_ns)} has more sub-second digits than "
                f"the file's timestamps hold ({self.fraction_digits})"
            )
        if self.fraction_digits:
            text += "." + digits[: self.fraction_digits]
        return text + self.suffix


def parse_timestamp(text: str) -> tuple[np.datetime64, TimestampStyle] | None:
    """(UTC time in ns, its style), or None if ``text`` is not such a timestamp."""
    m = _TS.fullmatch(text)
    if m is None:
        return None
    date, sep, clock, frac, suffix = m.groups()
    style = TimestampStyle(sep=sep, fraction_digits=len(frac or ""), suffix=suffix or "")
    try:
        t = np.datetime64(f"{date}T{clock}", "ns")
    except ValueError:
        return None
    if frac:
        t = t + np.timedelta64(int(frac.ljust(9, "0")), "ns")
    return t - style.offset, style


@dataclass(frozen=True, slots=True, eq=False)
class MovebankRow:
    """One data line: the text of each column, None where the burst writes the column; burst None
    for a row without acceleration (a GPS fix in Movebank's export)."""

    text: tuple[str | None, ...]
    burst: AccBurst | None = None

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MovebankRow):
            return NotImplemented
        return self.text == other.text and self.burst == other.burst

    __hash__ = None  # type: ignore[assignment]

    def get(self, header: tuple[str, ...], column: str) -> str | None:
        """The stored text of ``column`` (None for a column the burst writes)."""
        if column not in header:
            raise InputDataError(f"no column {column!r}{did_you_mean(column, header)}")
        return self.text[header.index(column)]


@dataclass(frozen=True, slots=True, eq=False)
class MovebankFile:
    """A Movebank e-obs CSV: its header, its rows and what it takes to write it back byte for byte."""

    header: tuple[str, ...]
    rows: tuple[MovebankRow, ...]
    timestamp_style: TimestampStyle = TimestampStyle()
    newline: str = "\n"
    final_newline: bool = True
    bom: bool = False

    def __post_init__(self) -> None:
        cols = find_columns(self.header)
        owned = set(cols.indices())
        if self.newline not in ("\n", "\r\n"):
            raise InputDataError(f"newline {self.newline!r}: must be '\\n' or '\\r\\n'")
        for k, row in enumerate(self.rows):
            if len(row.text) != len(self.header):
                raise InputDataError(f"row {k}: {len(row.text)} fields, the header has {len(self.header)}")
            none_at = {j for j, v in enumerate(row.text) if v is None}
            if none_at != (owned if row.burst is not None else set()):
                raise InputDataError(
                    f"row {k}: a burst row leaves exactly the columns {sorted(owned)} to its burst (None), "
                    f"a row without a burst none; got None at {sorted(none_at)}"
                )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MovebankFile):
            return NotImplemented
        return (self.header, self.rows, self.timestamp_style, self.newline, self.final_newline, self.bom) == (
            other.header,
            other.rows,
            other.timestamp_style,
            other.newline,
            other.final_newline,
            other.bom,
        )

    __hash__ = None  # type: ignore[assignment]

    @property
    def columns(self) -> Columns:
        return find_columns(self.header)

    @property
    def bursts(self) -> tuple[AccBurst, ...]:
        return tuple(r.burst for r in self.rows if r.burst is not None)


def bursts_to_file(bursts, timestamp_style: TimestampStyle = TimestampStyle()) -> MovebankFile:
    """A decoder-layout file (the note's six columns) holding ``bursts``. The note shows no data line,
    so the timestamp style (``YYYY-MM-DD HH:MM:SS.fff``, UTC, no suffix) is ours."""
    rows = tuple(MovebankRow((None,) * len(DECODER_COLUMNS), b) for b in bursts)
    return MovebankFile(DECODER_COLUMNS, rows, timestamp_style)


# ---------------------------------------------------------------------------------------------- write


def _quote(field: str) -> str:
    if any(c in field for c in ',"\r\n'):
        return '"' + field.replace('"', '""') + '"'
    return field


def format_rate(rate_hz: float) -> str:
    """A rate as the file writes it: Python's shortest round-trip float text ('5.0', '33.33')."""
    return repr(float(rate_hz))


def _burst_fields(b: AccBurst, cols: Columns, style: TimestampStyle) -> dict[int, str]:
    return {
        cols.checksum: str(b.checksum),
        cols.tag_id: b.tag_id,
        cols.start: style.format(b.start_time),
        cols.rate: format_rate(b.rate_hz),
        cols.axes: b.axes,
        cols.raw: " ".join(map(str, b.interleaved().tolist())),
    }


def _render(row: MovebankRow, cols: Columns, style: TimestampStyle) -> list[str]:
    out = list(row.text)
    if row.burst is not None:
        for j, v in _burst_fields(row.burst, cols, style).items():
            out[j] = v
    return out  # type: ignore[return-value]


def format_movebank(f: MovebankFile) -> bytes:
    """The file's bytes (UTF-8)."""
    cols = f.columns
    lines = [",".join(_quote(h) for h in f.header)]
    lines += [",".join(_quote(v) for v in _render(r, cols, f.timestamp_style)) for r in f.rows]
    text = f.newline.join(lines) + (f.newline if f.final_newline else "")
    return (("\ufeff" if f.bom else "") + text).encode("utf-8")


def write_movebank(f: MovebankFile, path: str | os.PathLike) -> Path:
    """Write ``f`` to ``path`` (through a temporary name, renamed into place)."""
    from flightmode.atomic import write_bytes

    return write_bytes(format_movebank(f), Path(path), mkdir=False)


# ----------------------------------------------------------------------------------------------- read


def read_movebank(path: str | os.PathLike) -> MovebankFile:
    """Read a Movebank e-obs CSV; InputDataError ('<path>: line N: what is wrong') on bad input."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as e:
        raise InputDataError(f"{path}: cannot read ({e.strerror})") from None
    return parse_movebank(data, source=str(path))


def parse_movebank(data: bytes | str, source: str = "<text>") -> MovebankFile:
    """Parse the text of a Movebank e-obs CSV (see :func:`read_movebank`)."""
    try:
        return _parse(data)
    except InputDataError as e:
        raise InputDataError(f"{source}: {e}") from None


def _split_line(line: str, n: int) -> list[str]:
    try:
        return next(csv.reader([line], strict=True))
    except (csv.Error, StopIteration) as e:
        raise InputDataError(f"line {n}: not a CSV line ({e})") from None


def _parse(data: bytes | str) -> MovebankFile:
    if isinstance(data, bytes):
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as e:
            bad = data[: e.start].count(b"\n") + 1
            raise InputDataError(f"line {bad}: not UTF-8 text ({e.reason})") from None
    else:
        text = data
    bom = text.startswith("\ufeff")
    if bom:
        text = text[1:]
    first = text.find("\n")
    newline = "\r\n" if first > 0 and text[first - 1] == "\r" else "\n"
    lines = text.split(newline)
    final_newline = len(lines) > 1 and lines[-1] == ""
    if final_newline:
        lines.pop()
    if not lines or lines[0] == "":
        raise InputDataError("line 1: empty: a Movebank e-obs file starts with its header line")
    header = tuple(_split_line(lines[0], 1))
    if ",".join(map(_quote, header)) != lines[0]:  # 'a"b' or '"a"': read, but not written back alike
        raise InputDataError(
            "line 1: the header's quoting would not be written back as it is; only text this reader "
            "writes back byte for byte is accepted"
        )
    cols = find_columns(header)
    owned = set(cols.indices())
    names = header
    style: TimestampStyle | None = None
    rows = []
    for n, line in enumerate(lines[1:], start=2):
        if line == "":
            raise InputDataError(f"line {n}: empty line")
        vals = _split_line(line, n)
        if len(vals) != len(header):
            raise InputDataError(f"line {n}: {len(vals)} fields, the header (line 1) has {len(header)}")
        burst, style = _parse_burst(vals, cols, names, n, style)
        row = MovebankRow(
            tuple(None if (burst is not None and j in owned) else v for j, v in enumerate(vals)), burst
        )
        back = _render(row, cols, style if style is not None else TimestampStyle())
        if back != vals or ",".join(map(_quote, back)) != line:
            j = next((j for j, (a, b) in enumerate(zip(back, vals)) if a != b), None)
            what = (
                f"column {names[j]!r} reads {vals[j]!r} but would be written back as {back[j]!r}"
                if j is not None
                else "its quoting would not be written back as it is"
            )
            raise InputDataError(
                f"line {n}: {what}; only text this reader writes back byte for byte is accepted"
            )
        rows.append(row)
    return MovebankFile(
        header, tuple(rows), style if style is not None else TimestampStyle(), newline, final_newline, bom
    )


def _uint32(text: str, n: int, name: str) -> int:
    if _INT.fullmatch(text) is None or not 0 <= int(text) <= UINT32_MAX:
        raise InputDataError(
            f"line {n}: {name} {text!r} is not an unsigned 32-bit integer (0-{UINT32_MAX}); seed 003 section 5.4 "
            f"does not say how the checksum is computed, so only its form is checked"
        )
    return int(text)


def _parse_burst(
    vals: list[str], c: Columns, names: tuple[str, ...], n: int, style: TimestampStyle | None
) -> tuple[AccBurst | None, TimestampStyle | None]:
    axes, raw_text = vals[c.axes], vals[c.raw]
    if axes == "" and raw_text == "":
        if vals[c.checksum] != "":  # a GPS row: its checksum may be absent, but if present has the same form
            _uint32(vals[c.checksum], n, names[c.checksum])
        return None, style
    if axes == "":
        raise InputDataError(f"line {n}: {names[c.raw]} holds samples but {names[c.axes]} is empty")
    if raw_text == "":
        raise InputDataError(f"line {n}: {names[c.axes]} is {axes!r} but {names[c.raw]} is empty")
    checksum = _uint32(vals[c.checksum], n, names[c.checksum])
    if axes not in AXES_SETS:
        raise InputDataError(
            f"line {n}: {names[c.axes]} {axes!r} must be X, Y and/or Z in alphabetical order "
            f"(seed 003 section 5.2, Table 1): one of {', '.join(AXES_SETS)}"
        )
    tag_id = vals[c.tag_id]
    if tag_id == "" or (c.decoder_layout and not (tag_id.isascii() and tag_id.isdigit())):
        raise InputDataError(
            f"line {n}: {names[c.tag_id]} {tag_id!r} is not a tag id"
            + (" (the decoder writes the tag number)" if c.decoder_layout else "")
        )
    try:
        rate = float(vals[c.rate])
    except ValueError:
        rate = math.nan
    if not (math.isfinite(rate) and rate > 0):
        raise InputDataError(
            f"line {n}: {names[c.rate]} {vals[c.rate]!r} is not a sampling frequency in Hz (> 0)"
        )
    parsed = parse_timestamp(vals[c.start])
    if parsed is None:
        raise InputDataError(
            f"line {n}: {names[c.start]} {vals[c.start]!r} is not a timestamp YYYY-MM-DD HH:MM:SS[.fff][+HH:MM]"
        )
    t, row_style = parsed
    if style is None:
        style = row_style
    elif row_style != style:
        raise InputDataError(
            f"line {n}: {names[c.start]} {vals[c.start]!r} is not written like the first burst's "
            f"({style.pattern}); mixed timestamp styles cannot be written back byte for byte"
        )
    samples = _samples(raw_text, n, names[c.raw])
    k = len(axes)
    if samples.size % k:
        raise InputDataError(
            f"line {n}: {names[c.raw]} holds {samples.size} samples, not a multiple of the {k} axes {axes!r} "
            f"(one sample per axis in turn: seed 003 section 5.4)"
        )
    burst = AccBurst(tag_id, t, axes, rate, samples.reshape(-1, k), checksum)
    return burst, style


def _samples(text: str, n: int, name: str) -> np.ndarray:
    if _RAW_FAST.fullmatch(text) is not None:
        tokens = text.split(" ")
        if max(map(len, tokens)) <= 18:  # fits int64
            v = np.array(tokens, dtype=np.int64)
            bad = np.flatnonzero(v > ADC_MAX_COUNT)
            if bad.size == 0:
                return v
    tokens = text.split(" ")
    for i, tok in enumerate(tokens, start=1):
        if _INT.fullmatch(tok) is None:
            raise InputDataError(f"line {n}: {name} sample #{i} is {tok!r}, not an integer count")
        if not ADC_MIN_COUNT <= int(tok) <= ADC_MAX_COUNT:
            raise InputDataError(
                f"line {n}: {name} sample #{i} is {tok}, outside the ADC's {ADC_MIN_COUNT}-{ADC_MAX_COUNT} "
                f"(seed 003 section 5.4)"
            )
    return np.array([int(tok) for tok in tokens], dtype=np.int64)  # '+5': the round-trip check names it
