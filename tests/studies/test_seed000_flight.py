"""Seed 000 Table 9's rate on a flight: the session's pattern run sensed again at 66.7 Hz and at its
own 100 Hz (:func:`flightmode.studies.seed000.table9_flight`)."""

from __future__ import annotations

import pytest

from flightmode.studies.seed000 import TABLE9_FLIGHT_FS_HZ, table9_flight


def test_the_flight_at_table9s_rate(pattern_run):
    run_dir, _ = pattern_run
    rows = table9_flight(run_dir, ks=(2.5, 4.0), tths=(4.0,))
    by = {(round(r["fs_hz"], 2), r["T_sigma"]): r for r in rows}
    assert set(by) == {(100.0, 2.5), (100.0, 4.0), (66.67, 2.5), (66.67, 4.0)}
    # 60-70 Hz (Table 9); W_s 1 s is 67 samples there
    assert 60.0 <= TABLE9_FLIGHT_FS_HZ <= 70.0 and by[(66.67, 2.5)]["window"] == 67
    for fs in (100.0, 66.67):
        lo, hi = by[(fs, 2.5)], by[(fs, 4.0)]
        assert lo["checks"] == hi["checks"] > 0
        # a higher threshold lets at least as many checks under it, on every axis (same MVs)
        for ax in "xyz":
            assert hi[f"P_FA_{ax}"] >= lo[f"P_FA_{ax}"]
        # eq. 14 with W_s = 1 s
        assert hi["P_FA"] == pytest.approx(hi["P_FA_t"] ** 4, rel=1e-12, abs=0)
    # the same flight in checks: one per second at either rate (within the window's rounding, 1 s vs 67/66.7 s)
    assert by[(66.67, 2.5)]["checks"] == pytest.approx(by[(100.0, 2.5)]["checks"], rel=0.01)
