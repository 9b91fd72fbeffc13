"""Seed 000 in fixed point (flightmode.detector.fixed_point, ``nmv-fixed``): the vectorised integer
detector against a literal transcription of the firmware loop (eq. 2-3 running sums, add the new,
drop the oldest), chunk invariance, the threshold register's rounding as the only difference from
the floating detector, and that difference counted on the pattern flight."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.detector import fixed_point as fp
from flightmode.detector import interface
from flightmode.errors import DetectorError

FS = 100.0


def firmware_loop(t, acc_g, n_win, k, s2, need, frac_bits=fp.FRAC_BITS, lsb=fp.LSB_G):
    """examples/nmv_fixed.c's loop in plain Python integers, one sample at a time (the reference)."""
    reg = [round(k * s * 2**frac_bits) for s in s2]  # Python's round: half to even, as rint
    ring = [[0] * n_win for _ in range(3)]
    s1, sq = [0, 0, 0], [0, 0, 0]
    pos = since = run = 0
    decision, t_prev, out, ds = False, None, [], []
    for i in range(len(t)):
        if t_prev is not None and t[i] - t_prev > 1.5 * (1.0 / FS):  # a gap resets everything
            ring = [[0] * n_win for _ in range(3)]
            s1, sq, pos, since, run, decision = [0, 0, 0], [0, 0, 0], 0, 0, 0, False
        t_prev = t[i]
        for a in range(3):
            c = min(127, max(-128, round(acc_g[i][a] / lsb)))
            if since >= n_win:  # eq. 2-3: the oldest leaves
                s1[a] -= ring[a][pos]
                sq[a] -= ring[a][pos] ** 2
            ring[a][pos] = c
            s1[a] += c
            sq[a] += c * c
        pos = (pos + 1) % n_win
        since += 1
        if since % n_win == 0:
            d = [n_win * sq[a] - s1[a] ** 2 for a in range(3)]
            ds.append(d)
            temp = all(d[a] * 2**frac_bits < reg[a] * n_win * n_win for a in range(3))
            run = run + 1 if temp else 0
            decision = temp and run >= need
        out.append(decision)
    return np.array(out), np.array(ds, np.int64).reshape(-1, 3)


def _stream(rng, n, gap_at=None):
    """A bag at rest, then shaken, then at rest again, quantised levels near count boundaries."""
    t = np.arange(n) / FS
    if gap_at is not None:
        t[gap_at:] += 7.3  # a 7.3 s hole in the stream
    a = np.array([0.02, -0.03, 1.0]) + rng.normal(0.0, 0.006, (n, 3))
    a[n // 3 : n // 2] += rng.normal(0.0, 0.05, (n // 2 - n // 3, 3))
    return t, a


@pytest.mark.parametrize("gap_at", [None, 1234])
def test_vectorised_equals_the_firmware_loop(gap_at):
    # integers are exact: the prefix-sum form and the running add/drop form give the same D and the
    # same decisions, bit for bit (no tolerance), including a reset at a gap in mid-window
    rng = np.random.default_rng(1)
    t, a = _stream(rng, 4000, gap_at)
    s2 = [0.2, 0.15, 0.3]
    det = fp.FixedNMV(FS, window_s=1.0, k=4.0, time_threshold_s=3.0, sigma2_counts=s2)
    got = det.checks(t, a)
    ref, ref_d = firmware_loop(t, a, 100, 4.0, s2, 3)
    np.testing.assert_array_equal(got["decisions"], ref)
    np.testing.assert_array_equal(got["d"], ref_d)
    assert got["decisions"].any() and not got["decisions"].all()  # both outcomes exercised


def test_chunks_change_nothing():
    rng = np.random.default_rng(2)
    t, a = _stream(rng, 3000, 1500)
    whole = fp.FixedNMV(FS, sigma2_counts=0.2).push(t, a)
    for step in (1, 7, 100, 999):
        det = fp.make(FS, list(interface.ACC_CHANNELS), sigma2_counts=0.2)
        parts = [det.push(t[i : i + step], a[i : i + step]) for i in range(0, t.shape[0], step)]
        np.testing.assert_array_equal(np.concatenate(parts), whole)


def test_counts_as_the_lis302dl_gives_them():
    # 18 mg per count, two's complement 8 bits: +-2.3 g saturates at -128 and +127
    c = fp.to_counts(np.array([0.0, 0.018, -0.036, 1.0, 2.5, -2.5, 0.0271]))
    assert c.tolist() == [0, 1, -2, 56, 127, -128, 2]  # 1 g = 55.6 counts -> 56; 0.0271 g -> 1.51 -> 2


def test_the_register_is_the_only_difference_from_the_floating_detector():
    # a threshold k sigma^2 put 0.1 LSB above a check's MV whose register rounds down to at most the
    # MV: the floating detector calls that axis below the threshold, the integer one not; the
    # comparison counts it, 0.1 LSB from the threshold (within one LSB, the module's bound)
    rng = np.random.default_rng(3)
    t, a = _stream(rng, 6000)
    det = fp.FixedNMV(FS, sigma2_counts=1.0)
    d = det.checks(t, a)["d"][:, 2]  # z: N^2 MV
    mv = d / 100**2  # counts^2
    lsb = 2.0**-fp.FRAC_BITS
    frac = mv / lsb - np.floor(mv / lsb)
    pick = int(np.flatnonzero((mv > 0.05) & (frac < 0.35))[0])
    k = 4.0
    s2 = np.array([1e3, 1e3, (mv[pick] + 0.1 * lsb) / k])  # x, y never decide: far above
    r = fp.compare_fixed_float(t, a, FS, k=k, sigma2_counts=s2)
    hits = [x for x in r["axis_disagreements"] if x["check"] == pick]
    assert len(hits) == 1 and hits[0]["axis"] == "z"
    assert hits[0]["lsb_from_threshold"] == pytest.approx(0.1, abs=1e-6)  # float MV error ~1e-13 counts^2
    assert r["within_one_lsb"] and r["final_explained"]
    assert r["temporary_disagreements"] >= 1


def test_errors_name_the_sample():
    det = fp.FixedNMV(FS)
    t = np.arange(10) / FS
    a = np.zeros((10, 3))
    a[6, 1] = np.nan
    with pytest.raises(DetectorError, match="sample 6"):
        det.push(t, a)
    t[4] = t[3]
    with pytest.raises(DetectorError, match="not increasing at sample 4"):
        fp.FixedNMV(FS).push(t, np.zeros((10, 3)))
    with pytest.raises(DetectorError, match="acc_y_g"):
        fp.make(FS, ["acc_x_g", "acc_z_g"])
    with pytest.raises(DetectorError, match="sigma2_counts"):
        fp.FixedNMV(FS, sigma2_counts=[0.1, 0.0, 0.1])


def pattern_stream(pattern_run):
    """(t, acc in g, sigma^2 in counts^2 from the unit's 60 s bench recording) of the pattern flight."""
    from flightmode.runs.pipeline import stream_rest
    from flightmode.runs.run_io import read_samples

    cols, info = read_samples(pattern_run[0])
    rest, _, _ = stream_rest("preset", cols, info)
    s2 = fp.sigma2_counts_of_rest(rest, 100)
    return cols["t_s"], cols["acc_g"], s2


def test_fixed_against_floating_on_the_pattern_flight(pattern_run, record_property):
    # the integer detector and seed 000's floating NMV (flight_mode.detect) on the flight's 8-bit
    # samples: every disagreement is a comparison within one LSB of the threshold (the register's
    # rounding, half an LSB, is the only difference), and the final statics differ only after one
    t, acc, s2 = pattern_stream(pattern_run)
    r = fp.compare_fixed_float(t, acc, FS, sigma2_counts=s2)
    assert r["checks"] == t.shape[0] // 100
    assert r["within_one_lsb"], r["axis_disagreements"]
    assert r["final_explained"]
    # the counts are the figure; a few in 4,451 checks (the register is 1/85 of the threshold wide)
    assert r["temporary_disagreements"] <= len(r["axis_disagreements"])
    assert r["final_disagreements"] <= r["checks_needed"] * r["temporary_disagreements"]
    for key in ("checks", "temporary_disagreements", "final_disagreements", "sample_disagreements"):
        record_property(key, r[key])
    record_property("axis_disagreements", len(r["axis_disagreements"]))
    # and the interface's nmv-fixed against the built-in nmv (interface, g^2) on the same samples:
    # the samples that differ are exactly the ones the comparison counted
    counts = fp.to_counts(acc)
    x8 = counts * fp.LSB_G
    ch = list(interface.ACC_CHANNELS)
    fixed = interface.decisions("nmv-fixed", fp.make(FS, ch, sigma2_counts=s2), t, x8)
    nmv = interface.build(interface.load("nmv"), FS, ch, {"sigma2": (s2 * fp.LSB_G**2).tolist()})
    floating = interface.decisions("nmv", nmv, t, x8)
    assert int(np.sum(fixed != floating)) == r["sample_disagreements"]
    assert math.isclose(fixed.mean(), floating.mean(), abs_tol=r["sample_disagreements"] / t.shape[0])


def test_compare_across_a_gap():
    # a gap resets both detectors alike: with no check differing, no sample differs either (the
    # per-sample decisions fall to False at the reset in both)
    rng = np.random.default_rng(5)
    t, a = _stream(rng, 4000, 1234)
    r = fp.compare_fixed_float(t, a, FS, time_threshold_s=3.0, sigma2_counts=[0.2, 0.15, 0.3])
    assert r["final_static_checks_fixed"] > 0 and r["within_one_lsb"]
    assert r["final_disagreements"] == 0 and r["sample_disagreements"] == 0
