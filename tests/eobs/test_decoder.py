"""The data decoder's output formats (seed 003 sections 5.2, 5.3), against the note's examples."""

from __future__ import annotations

import re

import numpy as np
import pytest

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.decoder import (
    day_number,
    format_all_data,
    format_average_std,
    format_columns,
    format_dft,
    time_fields,
)
from flightmode.eobs.spectrum import burst_hp_std


def test_day_numbers_and_weekdays_of_the_notes_examples():
    # footnote 4: "Day number is the number of days since 4.March.2007"; examples: "ACC,99,11.6.2007,Mo"
    # and "1185, 1.6.2010, Tu"
    assert day_number(np.datetime64("2007-03-04T12:00")) == 0
    assert time_fields(np.datetime64("2007-06-11T21:01:00")) == ["99", "11.6.2007", "Mo", "21:01:00"]
    assert time_fields(np.datetime64("2010-06-01T18:51:04.9")) == ["1185", "1.6.2010", "Tu", "18:51:04"]


def test_option_3_all_data_one_line_per_burst():
    # section 5.2: "ACC,99,11.6.2007,Mo,21:01:00,1530,1488,1170,1522,1498,1166,1528,1493,...."; 5.3 prints the
    # same with a space after each comma. The note's line is cut after 8 samples: the 9th here is ours.
    raw = np.array([[1530, 1488, 1170], [1522, 1498, 1166], [1528, 1493, 1170]])
    b = AccBurst("99", np.datetime64("2007-06-11T21:01:00"), "XYZ", 10.0, raw, 0)
    assert format_all_data([b], sep=",").startswith(
        "ACC,99,11.6.2007,Mo,21:01:00,1530,1488,1170,1522,1498,1166,1528,1493,"
    )
    assert format_all_data([b]).startswith(
        "ACC, 99, 11.6.2007, Mo, 21:01:00, 1530, 1488, 1170, 1522, 1498, 1166, 1528, 1493, "
    )
    assert format_all_data([b, b]).count("\n") == 2


def test_option_6_columns_reproduces_the_notes_example():
    note = (
        "day number, date, day of week, time of day, sample\n"
        "1185, 1.6.2010, Tu, 18:51:04, 1867\n"
        "1185, 1.6.2010, Tu, 18:51:04, 1867\n"
        "1185, 1.6.2010, Tu, 18:51:04, 1868\n"
        "1185, 1.6.2010, Tu, 18:51:04, 1868\n"
        "1185, 1.6.2010, Tu, 18:51:04, 1869\n"
    )
    b = AccBurst(
        "1",
        np.datetime64("2010-06-01T18:51:04"),
        "Z",
        10.0,
        np.array([[1867], [1867], [1868], [1868], [1869]]),
        0,
    )
    assert format_columns([b]) == note
    two = AccBurst("1", np.datetime64("2010-06-01T18:51:04"), "XY", 10.0, np.array([[1, 2], [3, 4]]), 0)
    assert format_columns([two]).splitlines() == [
        "day number, date, day of week, time of day, sample X, sample Y",
        "1185, 1.6.2010, Tu, 18:51:04, 1, 2",
        "1185, 1.6.2010, Tu, 18:51:04, 3, 4",
    ]


def _z_burst_like_the_notes(rng) -> AccBurst:
    """A Z burst of N = 330 samples (the DFT example's 166 values) around the example's average 1872."""
    z = 1872 + np.round(20 * rng.standard_normal(330) + 15 * np.sin(np.arange(330) / 3.0)).astype(int)
    z += 1872 - int(np.floor(z.mean() + 0.5))  # make the rounded average exactly the note's 1872
    return AccBurst("1", np.datetime64("2010-06-01T18:51:04"), "Z", 10.0, z[:, None], 0)


def test_option_9_and_dft_lines_have_the_notes_form():
    """Option 9's example "1185, 1.6.2010, Tu, 18:51:04, 1872, 27.906608" and the DFT example
    "ACCF, 1185, 1.6.2010, Tu, 18:51:04, Z, 166, 27.907, 1872, 2, 1, 3, ..." are the same burst: the
    DFT's r_0 is the average and its std the option-9 std to 3 decimals. The note gives neither the
    raw data nor the high-pass cut-off, so its 27.906608 cannot be recomputed; the form is checked."""
    b = _z_burst_like_the_notes(np.random.default_rng(5))
    cutoff_hz = 0.5  # ours: the note does not say
    opt9 = format_average_std([b], cutoff_hz).splitlines()
    assert opt9[0] == "Day number, Date, day of week, time of day, average value, standard deviation"
    assert re.fullmatch(r"1185, 1\.6\.2010, Tu, 18:51:04, 1872, \d+\.\d{6}", opt9[1]), opt9[1]
    std = float(opt9[1].split(", ")[-1])
    assert std == pytest.approx(burst_hp_std(b, cutoff_hz)[0], abs=5e-7)  # printed to 6 decimals
    (dft,) = format_dft([b], cutoff_hz).splitlines()
    fields = dft.split(", ")
    assert fields[:7] == ["ACCF", "1185", "1.6.2010", "Tu", "18:51:04", "Z", "166"]
    assert fields[7] == f"{std:.3f}" and fields[8] == "1872" and len(fields) == 8 + 166
    assert all(re.fullmatch(r"\d+", v) for v in fields[8:])
    # two axes: one ACCF line per axis; option 9 an average and a std per axis
    xy = AccBurst("1", np.datetime64("2010-06-01T18:51:04"), "XY", 10.0, np.tile(b.raw, (1, 2)), 0)
    assert [ln.split(", ")[5] for ln in format_dft([xy], cutoff_hz).splitlines()] == ["X", "Y"]
    assert (
        format_average_std([xy], cutoff_hz)
        .splitlines()[0]
        .endswith("average value X, standard deviation X, average value Y, standard deviation Y")
    )
