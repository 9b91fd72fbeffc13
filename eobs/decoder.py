"""Writers for the data decoder's other output formats (seed 003 sections 5.2 and 5.3).

Every line starts with the burst's time as the decoder writes it: the day number ("the number of
days since 4.March.2007", footnote 4: the examples give day 99 for 11.6.2007 and 1185 for 1.6.2010,
so 4 March 2007 is day 0), the date as d.m.yyyy, the day of the week in two letters (11.6.2007 "Mo",
1.6.2010 "Tu") and the time of day HH:MM:SS. The formats:

* option 3, "All data in one file": one line per burst, ``ACC``, the time, then the raw samples in
  recording order (X Y Z X Y Z ...; section 5.2);
* option 6, "Acceleration data in columns": one line per sample set (one count per enabled axis),
  every line of a burst carrying the burst's time of day;
* option 9, "Acceleration data reduced to one average and one stddev value (after hp filter)": one
  line per burst, the average count and section 12's standard deviation;
* "DFT": one line per burst and axis, ``ACCF``, the time, the axis, the number of DFT values
  (floor(N/2) + 1), the standard deviation, then the DFT values r_n of section 11.

Where the note is garbled or silent (choices, each a parameter where it can be):

* separators: section 5.2 prints ``ACC,99,11.6.2007,...`` without spaces, the examples of 5.3
  ``ACC, 99, 11.6.2007, ...`` with a space after each comma (the PDF's column alignment may have
  added them). ``sep`` defaults to ", " (every 5.3 example); ``sep=","`` gives 5.2's line;
* the 2-axis XZ example of 5.3 repeats the numbers of the XYZ one: a copy in the note, not data;
* the DFT example wraps its one line ("..., 1, 0\\n, 2, 2, ...") at the page width: one line per burst
  and axis here, as the note says "one line represents the DFT of one burst";
* the DFT line's header ("ACCF, day number, ... DFT-Values...") is printed as prose, not in the
  example block: no header is written. Options 6 and 9 print their header inside the example, so
  they get one ("Day number4" in the note is "Day number" with footnote 4's marker);
* the DFT line's "standard deviation" (27.907) is the option-9 value of the same burst (27.906608,
  same day and time, and r_0 1872 is its average 1872), so it is section 12's high-pass std;
* rounding: the average and the DFT values are printed as integers, the std with 6 decimals
  (option 9) or 3 (DFT). Whether the decoder rounds or truncates is not said: we round half up;
* options 6 and 9 show one axis (Z); with more axes, option 6 writes one count per axis on a line
  ("one sample (or up to 3, depending on the number of axes)") and option 9 an average and a std per
  axis, in the axes' order;
* time: the decoder's clock is not named; times are written in UTC, the seconds truncated;
* the high-pass cut-off of section 12 is not given: ``cutoff_hz`` is required.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.spectrum import burst_dft, burst_hp_std

DAY_ZERO = np.datetime64("2007-03-04", "D")  # seed 003 footnote 4: day numbers count from 4 March 2007
_WEEKDAYS = ("Mo", "Tu", "We", "Th", "Fr", "Sa", "Su")  # the note's two-letter days ("Mo", "Tu")
HEADER_COLUMNS = "day number, date, day of week, time of day, sample"  # option 6, as printed
HEADER_AVERAGE_STD = (
    "Day number, Date, day of week, time of day, average value, standard deviation"  # option 9
)


def day_number(t: np.datetime64) -> int:
    """Days since 4 March 2007 (footnote 4) of the UTC date of ``t``."""
    # numpy's stubs reject np.datetime64(datetime64, unit), numpy's documented unit conversion
    # (fixed in numpy/numpy#31883: unused-ignore keeps a numpy with the fix quiet); so below too
    return int((np.datetime64(t, "D") - DAY_ZERO) // np.timedelta64(1, "D"))  # type: ignore[call-overload, unused-ignore]


def time_fields(t: np.datetime64) -> list[str]:
    """[day number, d.m.yyyy, two-letter weekday, HH:MM:SS] of ``t`` (UTC, seconds truncated)."""
    dt = np.datetime64(t, "s").astype(object)  # type: ignore[call-overload, unused-ignore]  # a datetime.datetime
    return [
        str(day_number(t)),
        f"{dt.day}.{dt.month}.{dt.year}",
        _WEEKDAYS[dt.weekday()],
        dt.strftime("%H:%M:%S"),
    ]


def _round_half_up(x: float) -> int:
    return math.floor(x + 0.5)


def _lines(lines: Iterable[str], newline: str) -> str:
    return "".join(line + newline for line in lines)


def format_all_data(bursts: Iterable[AccBurst], sep: str = ", ", newline: str = "\n") -> str:
    """Option 3: ``ACC, day, date, weekday, time, samples...`` per burst (sections 5.2, 5.3)."""
    return _lines(
        (sep.join(["ACC", *time_fields(b.start_time), *map(str, b.interleaved().tolist())]) for b in bursts),
        newline,
    )


def format_columns(
    bursts: Iterable[AccBurst], sep: str = ", ", header: bool = True, newline: str = "\n"
) -> str:
    """Option 6: one line per sample set, the burst's time on each (section 5.3)."""
    bursts = list(bursts)
    out = []
    if header:
        axes = {b.axes for b in bursts}
        if len(axes) == 1 and len(next(iter(axes))) > 1:
            names = [f"sample {a}" for a in next(iter(axes))]
        else:
            names = ["sample"]
        out.append(sep.join(HEADER_COLUMNS.split(", ")[:4] + names))
    for b in bursts:
        when = time_fields(b.start_time)
        out += [sep.join([*when, *map(str, row)]) for row in b.raw.tolist()]
    return _lines(out, newline)


def format_average_std(
    bursts: Iterable[AccBurst], cutoff_hz: float, sep: str = ", ", header: bool = True, newline: str = "\n"
) -> str:
    """Option 9: ``day, date, weekday, time, average, std`` per burst, average and std per axis
    (section 5.3 with section 12's std)."""
    bursts = list(bursts)
    out = []
    if header:
        names = HEADER_AVERAGE_STD.split(", ")
        axes = {b.axes for b in bursts}
        if len(axes) == 1 and len(next(iter(axes))) > 1:
            names = names[:4] + [f"{n} {a}" for a in next(iter(axes)) for n in names[4:]]
        out.append(sep.join(names))
    for b in bursts:
        avg = b.raw.mean(axis=0)
        std = burst_hp_std(b, cutoff_hz)
        vals = [v for j in range(len(b.axes)) for v in (str(_round_half_up(avg[j])), f"{std[j]:.6f}")]
        out.append(sep.join([*time_fields(b.start_time), *vals]))
    return _lines(out, newline)


def format_dft(bursts: Iterable[AccBurst], cutoff_hz: float, sep: str = ", ", newline: str = "\n") -> str:
    """The DFT option: ``ACCF, day, date, weekday, time, axis, number of DFT values, std, r_0 ...``
    per burst and axis (sections 5.3, 11, 12)."""
    out = []
    for b in bursts:
        _, mags = burst_dft(b)
        std = burst_hp_std(b, cutoff_hz)
        when = time_fields(b.start_time)
        for j, axis in enumerate(b.axes):
            values = [str(_round_half_up(r)) for r in mags[:, j]]
            out.append(sep.join(["ACCF", *when, axis, str(mags.shape[0]), f"{std[j]:.3f}", *values]))
    return _lines(out, newline)
