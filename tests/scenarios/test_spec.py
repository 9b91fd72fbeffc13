"""Scenario files: every built-in validates; each class of bad input gets a one-line error naming
the file, key path, value, what is allowed and (for misspellings) the nearest valid name."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from flightmode.errors import ScenarioError
from flightmode.scenarios.scenario import DEFAULT_SCENARIO, Scenario, builtin_names, builtin_path

REQUIRED_BUILTINS = {"gva-lhr-a320", "hel-zrh-f100", "ist-osl-737", "lhr-jfk-787", "pattern"}


def test_builtin_library_is_complete_and_every_scenario_round_trips_exactly():
    names = set(builtin_names())
    assert REQUIRED_BUILTINS <= names
    assert DEFAULT_SCENARIO == "gva-lhr-a320"
    from flightmode.cli import main as cli

    assert cli.DEFAULT_SCENARIO == DEFAULT_SCENARIO  # the CLI's copy (it imports nothing at start)
    for name in names:
        sc = Scenario.builtin(name)
        assert sc.name == name == builtin_path(name).stem
        text = sc.to_toml()
        back = Scenario.from_toml_text(text)
        # every field equal (floats bit for bit: TOML writes repr), the same text, the same hash
        assert back == sc and back.to_toml() == text and back.digest() == sc.digest()
        # and the TOML written is the file's own content: every key the file sets has the same value
        doc = tomllib.loads(builtin_path(name).read_text())
        written = tomllib.loads(text)
        for sec, table in doc.items():
            if isinstance(table, dict):
                for k, v in table.items():
                    assert written[sec][k] == v, (name, sec, k)


def test_replace_is_validated_like_a_file_and_changes_only_what_it_names():
    sc = Scenario.builtin("pattern")
    s2 = sc.replace(seed=3, cruise={"altitude_m": 1000.0}, **{"carrier.placement": "overhead_bin"})
    assert (s2.seed, s2.plan.cruise_alt_m, s2.carrier.placement) == (3, 1000.0, "overhead_bin")
    assert s2.plan.cruise_mach == sc.plan.cruise_mach and s2.plan.origin == sc.plan.origin
    assert s2 != sc and s2.digest() != sc.digest()
    assert Scenario.from_toml_text(s2.to_toml()) == s2
    with pytest.raises(ScenarioError, match=r"\[cruise\]\.altitude_ft.*did you mean \"altitude_m\""):
        sc.replace(**{"cruise.altitude_ft": 1000.0})
    with pytest.raises(ScenarioError, match=r"replace\(crusie=...\).*did you mean \"cruise\""):
        sc.replace(crusie={"mach": 0.5})
    with pytest.raises(ScenarioError, match=r"\[scenario\]\.seed = -1: must be >= 0"):
        sc.replace(seed=-1)
    # above the type's maximum operating altitude (the A320's 39,100 ft, 11,918 m): named, with the limit
    with pytest.raises(
        ScenarioError,
        match=r"\[cruise\]\.altitude_m = 12000.0: above the A320's maximum operating altitude, 11918 m",
    ):
        Scenario.builtin("gva-lhr-a320").replace(cruise={"altitude_m": 12000.0})


def _doc(name="pattern"):
    return tomllib.loads(builtin_path(name).read_text())


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "bad.toml"
    p.write_text(text)
    return p


def test_toml_syntax_error_names_file_and_position(tmp_path):
    p = _write(tmp_path, builtin_path("pattern").read_text().replace('name = "pattern"', 'name = "pattern'))
    with pytest.raises(ScenarioError) as ei:
        Scenario.from_toml(p)
    msg = str(ei.value)
    assert str(p) in msg and "TOML syntax error" in msg and "line" in msg
    assert "\n" not in msg


def test_unknown_key_suggests_the_nearest():
    doc = _doc()
    doc["cruise"]["altitude_ft"] = doc["cruise"].pop("altitude_m")
    with pytest.raises(ScenarioError) as ei:
        Scenario.from_doc(doc, "x.toml")
    msg = str(ei.value)
    assert "x.toml: [cruise].altitude_ft" in msg and 'did you mean "altitude_m"' in msg


def test_unknown_section_suggests_the_nearest():
    doc = _doc()
    doc["turbulance"] = [{"start_s": 1, "duration_s": 2, "severity": "light"}]
    with pytest.raises(ScenarioError, match=r'\[turbulance\].*did you mean "turbulence"'):
        Scenario.from_doc(doc, "x.toml")


def test_wrong_type():
    doc = _doc()
    doc["cruise"]["mach"] = "fast"
    with pytest.raises(ScenarioError, match=r"\[cruise\]\.mach = 'fast': must be a float"):
        Scenario.from_doc(doc, "x.toml")


def test_negative_duration():
    doc = _doc()
    doc["scenario"]["gate_wait_s"] = -5
    with pytest.raises(ScenarioError, match=r"\[scenario\]\.gate_wait_s = -5.0: must be >= 0"):
        Scenario.from_doc(doc, "x.toml")


def test_negative_hold_in_a_list():
    doc = _doc()
    doc["taxi_out"]["holds_s"] = [30, -1]
    with pytest.raises(ScenarioError, match=r"\[taxi_out\]\.holds_s\[1\] = -1"):
        Scenario.from_doc(doc, "x.toml")


def test_unknown_aircraft_suggests_the_nearest():
    doc = _doc()
    doc["scenario"]["aircraft"] = "A321"
    with pytest.raises(ScenarioError) as ei:
        Scenario.from_doc(doc, "x.toml")
    msg = str(ei.value)
    assert "[scenario].aircraft = 'A321'" in msg and 'did you mean "A320"' in msg and "737" in msg


def test_missing_required_key():
    doc = Scenario.builtin("pattern").to_doc()  # every key written, the runways' figures included
    del doc["origin"]["heading_deg"]
    with pytest.raises(ScenarioError, match=r"\[origin\]\.heading_deg is missing"):
        Scenario.from_doc(doc, "x.toml")


def test_a_runway_named_by_airport_and_ident_takes_ourairports_figures():
    doc = _doc()
    assert set(doc["origin"]) == {"icao", "runway"}  # the built-ins name their runways only
    sc = Scenario.from_doc(doc, "x.toml")
    # LSGG 22 in OurAirports: 3,900 m (12,795 ft), heading 225.5 deg true; written back in full
    assert sc.plan.origin.length_m == pytest.approx(3900.0, abs=1.0)
    assert sc.plan.origin.heading_deg == 225.5
    assert Scenario.from_toml_text(sc.to_toml()) == sc
    doc["origin"]["runway"] = "23"  # renamed 22 in 2020 (magnetic variation): OurAirports has 04/22
    with pytest.raises(
        ScenarioError,
        match=r"x.toml: \[origin\]: airport LSGG has no paved, open runway '23' "
        r"\(did you mean \"22\"\?\); its runways: 04, 22",
    ):
        Scenario.from_doc(doc, "x.toml")


def test_airports_too_close_for_the_cruise_asked():
    doc = _doc("gva-lhr-a320")
    doc["destination"] = dict(_doc("hel-zrh-f100")["destination"])  # Geneva -> Zurich, 225 km
    doc["route"]["waypoints"] = []
    with pytest.raises(ScenarioError) as ei:
        Scenario.from_doc(doc, "x.toml")
    msg = str(ei.value)
    assert "airports too close" in msg and "lower the cruise to at most" in msg
    # and the suggested altitude is accepted
    max_alt = float(msg.split("at most ")[1].split(" m")[0])
    doc["cruise"]["altitude_m"] = max_alt - 10.0
    Scenario.from_doc(doc, "x.toml")


def test_unknown_builtin_name_suggests_the_nearest():
    with pytest.raises(ScenarioError, match=r"unknown scenario 'gva-lhr-a32'.*did you mean \"gva-lhr-a320\""):
        Scenario.resolve("gva-lhr-a32")


@pytest.mark.parametrize(
    "edit, expected",
    [
        (lambda t: t.replace("[cruise]", "[cruise]\nspeed_kt = 300"), "[cruise].speed_kt"),
        (lambda t: t.replace('aircraft = "737"', 'aircraft = "B737"'), 'did you mean "737"'),
    ],
)
def test_cli_fly_bad_file_exits_nonzero_with_one_line_and_no_traceback(tmp_path, edit, expected):
    p = _write(tmp_path, edit(builtin_path("pattern").read_text()))
    r = subprocess.run(
        [sys.executable, "-m", "flightmode.cli.main", "fly", str(p), "--out", str(tmp_path / "out")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert r.returncode == 2
    err = " ".join(r.stderr.split())
    assert err.startswith("error:") and expected in err
    assert "Traceback" not in r.stderr + r.stdout
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_spec_lists_every_section():
    from flightmode.scenarios.spec import SPEC, spec_text

    text = spec_text()
    for sec in SPEC:
        assert sec in text


def test_sensor_rate_the_part_does_not_have():
    doc = _doc()
    doc["sensor"] = {"preset": "lis302dl", "odr_hz": 200}
    with pytest.raises(
        ScenarioError, match=r"\[sensor\]\.odr_hz = 200.0: the lis302dl part has only 100, 400 Hz"
    ):
        Scenario.from_doc(doc, "x.toml")
    doc["sensor"] = {"preset": "lis302dll"}
    with pytest.raises(ScenarioError, match=r'did you mean "lis302dl"'):
        Scenario.from_doc(doc, "x.toml")
