"""Per-sample decisions scored against the truth labels (detector/decisions.py), by hand on a crafted
stream and against the check-based Evaluation on a real flight."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from flightmode.detector import decisions as dc
from flightmode.detector import evaluation as ev
from flightmode.detector.flight_mode import DetectorParams
from flightmode.errors import DetectorError


def _crafted():
    """30 samples at 10 Hz. In-flight window: samples 10-19 (taxi_out 10-14, cruise 15-19); truly
    static 0-9 and 22-29. Decisions: rest 0-11 (carried 2 samples into the window), 15-16 and 24-29."""
    n = 30
    t = np.arange(n) / 10.0
    window = (np.arange(n) >= 10) & (np.arange(n) < 20)
    truth = (np.arange(n) < 10) | (np.arange(n) >= 22)
    phase = np.array(["gate"] * 10 + ["taxi_out"] * 5 + ["cruise"] * 5 + ["gate"] * 10, dtype=object)
    dec = np.zeros(n, bool)
    dec[:12] = dec[15:17] = dec[24:] = True
    return t, dec, {"in_flight_window": window, "sensor_static": truth, "phase": phase}


def test_hand_computed_figures_of_a_crafted_stream():
    t, dec, lab = _crafted()
    e = dc.score(t, dec, lab)
    # two runs of rest inside the window: samples 10-11 (carried from before pushback) and 15-16,
    # 2 samples x 0.1 s each
    assert e.false_static_count == 2
    assert e.false_static_events[0] == {"t_s": 1.0, "duration_s": pytest.approx(0.2), "phase": "taxi_out"}
    assert e.false_static_events[1] == {"t_s": 1.5, "duration_s": pytest.approx(0.2), "phase": "cruise"}
    assert e.false_static_s == pytest.approx(0.4) and e.longest_false_static_s == pytest.approx(0.2)
    # suspended at sample 12: 0.2 s after the window opened at sample 10
    assert e.suspend_s == pytest.approx(0.2)
    # window ends at 19; the bag truly rests from sample 22 (2.2 s), the first rest decision at/after
    # it is sample 24 (2.4 s)
    assert e.response_s == pytest.approx(0.2) and e.rest_after
    # outside the window truly static: 10 + 8 samples = 1.8 s; missed: samples 22-23 = 0.2 s
    assert e.static_s == pytest.approx(1.8) and e.missed_static_s == pytest.approx(0.2)
    assert e.availability == pytest.approx(1.6 / 1.8)
    # equal at 10 + 3 + 5 + 6 = 24 of 30 samples; phi = (16 x 8 - 4 x 2) / sqrt(20 x 10 x 18 x 12)
    assert e.accuracy == pytest.approx(0.8)
    assert e.correlation == pytest.approx(120 / math.sqrt(20 * 10 * 18 * 12), rel=1e-12)
    assert e.in_flight_samples == 10 and e.in_window_h == pytest.approx(1.0 / 3600)
    s = e.summary()
    assert s["false_static_phases"] == "taxi_out,cruise" and s["availability"] == e.availability


def test_the_grace_drops_only_a_short_carried_over_rest():
    t, dec, lab = _crafted()
    # the carried run lasts 0.2 s: kept at a grace of 0.2 s (not shorter), dropped at 0.3 s; the
    # run at 15-16 started inside the window and is kept whatever the grace
    assert dc.score(t, dec, lab, grace_s=0.2).false_static_count == 2
    e = dc.score(t, dec, lab, grace_s=0.3)
    assert [ev_["t_s"] for ev_ in e.false_static_events] == [1.5]
    assert e.suspend_s == pytest.approx(0.2)  # the latency is still reported


def test_no_window_no_rest_and_bad_shapes():
    t, dec, lab = _crafted()
    lab0 = lab | {"in_flight_window": np.zeros(30, bool)}
    e = dc.score(t, dec, lab0)
    assert e.false_static_count == 0 and math.isnan(e.suspend_s) and e.response_s is None
    e = dc.score(t, np.zeros(30, bool), lab)
    assert e.response_s is None and e.rest_after and e.suspend_s == 0.0 and e.availability == 0.0
    assert math.isnan(e.correlation)  # a constant series: phi undefined
    with pytest.raises(DetectorError, match=r"shape \(29,\).*30 samples"):
        dc.score(t, dec[:-1], lab)
    with pytest.raises(DetectorError, match="label 'phase' missing"):
        dc.score(t, dec, {k: v for k, v in lab.items() if k != "phase"})


def test_held_decisions_hold_each_check_until_the_next():
    out = dc.held(8, [2, 5], [True, False])
    assert out.tolist() == [False, False, True, True, True, False, False, False]
    assert dc.held(3, [], []).tolist() == [False] * 3


def test_checks_held_per_sample_give_evaluations_false_statics_on_a_real_flight(run_cached):
    """The pattern circuit's recording, seed 000's NMV at its recommended point and at a looser
    threshold (more false statics), judged by Evaluation every W_s and, held between checks as a
    streaming detector reports them, by the per-sample scorer with grace W_s."""
    rec = run_cached("pattern").recording
    labels = {
        "in_flight_window": rec.in_flight_window,
        "sensor_static": rec.sensor_static,
        "phase": rec.phase,
    }
    sigma2 = np.var(rec.acc_g[:6000], axis=0)  # the first minute at rest
    window = np.asarray(rec.in_flight_window, bool)
    w0, w1 = np.flatnonzero(window)[[0, -1]]
    total = 0
    for k in (4.0, 40.0):
        p = dataclasses.replace(DetectorParams(fs_hz=rec.odr_hz), k_sigma=k)
        e = ev.evaluate(rec.t_s, rec.acc_g, labels, p, sigma2)
        per = dc.score(
            rec.t_s,
            dc.held(rec.t_s.shape[0], e.checks.index, e.checks.final_static),
            labels,
            grace_s=p.window_s,
        )
        total += e.false_static_count
        # the count: exactly
        assert per.false_static_count == e.false_static_count, k
        for a, b in zip(per.false_static_events, e.false_static_events, strict=True):
            first = abs(a["t_s"] - rec.t_s[w0]) < 1e-9  # carried over from before the window
            last = b["t_s"] + b["duration_s"] > rec.t_s[w1]  # reaching the window's end
            if not (first or last):
                # inside the window: the same checks, held W samples each: equal to rounding
                assert a["t_s"] == b["t_s"] and a["phase"] == b["phase"]
                assert a["duration_s"] == pytest.approx(b["duration_s"], rel=1e-9)
            else:
                # at an end of the window, the samples count what the checks round to whole windows:
                # less than one window apart
                assert abs(a["duration_s"] - b["duration_s"]) < p.window_s
        # the same rest, counted per sample rather than per check (W samples each) outside the window:
        # apart by less than one window per put-down (the runs of truth and decisions outside it)
        assert per.missed_static_s == pytest.approx(e.missed_static_s, abs=5 * p.window_s)
        if e.response_s is not None:
            # a check held from before the bag came to rest answers at once per sample; Evaluation waits
            # for the first check closing at or after rest: within one window, never later
            assert e.response_s - p.window_s < per.response_s <= e.response_s + 1e-9
    assert total > 0  # the loose threshold made false statics to compare
