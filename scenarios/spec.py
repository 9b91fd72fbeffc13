"""The scenario file format (TOML): every section and key, and their validation.

Every key is declared in :data:`SPEC` with its type, bounds, default and meaning; ``flightmode
scenarios --spec`` prints it. Validation is strict: unknown sections or keys, wrong types, values out
of range, an aircraft with no profile, and airports too close for the cruise asked all raise a
:class:`~flightmode.errors.ScenarioError` whose one-line message names the file, the key path, the
value, what is allowed and, for a misspelt name, the nearest valid one. The typed object built from
a valid document is :class:`flightmode.scenarios.scenario.Scenario`. An optional ``[model]`` table
overrides uncertain model parameters (name = number; :mod:`flightmode.scenarios.model` checks it
against the registry; ``flightmode scenarios --model`` lists them).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from flightmode.errors import ScenarioError, did_you_mean
from flightmode.sim.flight.aircraft.registry import PROFILES
from flightmode.sim.flight.cabin import HOLD_OPTIONS, ISA_DEV_RANGE_K, QNH_RANGE_HPA
from flightmode.sim.flight.draws import LANDING_QUALITIES
from flightmode.sim.flight.geodesy import great_circle_distance_m
from flightmode.sim.flight.plan import SEVERITIES, FlightPlan
from flightmode.sim.sensor.accelerometer import PRESETS as SENSOR_PRESETS
from flightmode.sim.sensor.barometer import PRESETS as BARO_PRESETS
from flightmode.sim.sensor.carrier import CABIN_ROWS, PACKINGS, PLACEMENTS, CarrierSpec
from flightmode.sim.sensor.carrier import KINDS as CARRIER_KINDS
from flightmode.sim.sensor.gyroscope import PRESETS as GYRO_PRESETS
from flightmode.units import FT_M, NM_M

_CARRIER = CarrierSpec()  # the [carrier] defaults are CarrierSpec's own (one place)


@dataclass(frozen=True, slots=True)
class Key:
    type: type | tuple[type, ...]
    doc: str
    default: Any = None  # None: required
    lo: float | None = None
    hi: float | None = None
    choices: tuple[str, ...] | None = None
    optional: bool = False  # may be absent with no default


def _runway_keys(role: str) -> dict[str, Key]:
    return {
        "icao": Key(str, f"ICAO code of the {role} airport"),
        "runway": Key(str, "runway designator, e.g. '23' or '27L'"),
        "threshold_lat_deg": Key(float, "latitude of the runway threshold (WGS-84)", lo=-90, hi=90),
        "threshold_lon_deg": Key(float, "longitude of the runway threshold (WGS-84)", lo=-180, hi=180),
        "elevation_m": Key(float, "threshold elevation above mean sea level", lo=-500, hi=5000),
        "heading_deg": Key(float, "runway true heading", lo=0, hi=360),
        "length_m": Key(float, "runway length", lo=1200, hi=6000),
        "width_m": Key(float, "runway width", 45.0, lo=20, hi=100),
    }


def _taxi_keys() -> dict[str, Key]:
    return {
        "length_m": Key(float, "taxi distance between stand area and runway", lo=300, hi=15000),
        "holds_s": Key(list, "stops along the taxiway (s each), evenly spaced", []),
        "lineup_hold_s": Key(
            float, "line-up-and-wait time on the runway (taxi out only)", 30.0, lo=0, hi=3600
        ),
        "taxiway_offset_m": Key(
            float, "distance of the parallel taxiway from the centreline", 180.0, lo=100, hi=1000
        ),
        "apron_depth_m": Key(float, "distance from the taxiway to the stand", 80.0, lo=40, hi=500),
    }


SPEC: dict[str, dict[str, Key]] = {
    "scenario": {
        "name": Key(str, "scenario name (also the run folder prefix)"),
        "description": Key(str, "one line shown by `flightmode scenarios`"),
        "aircraft": Key(
            str, "JSBSim aircraft model with a flightmode profile", choices=tuple(sorted(PROFILES))
        ),
        "seed": Key(
            int,
            "the run's random seed: every random stream (turbulence, the bag, the sensor unit and "
            "its noise) is derived from it by name",
            1,
            lo=0,
            hi=2**63 - 1,
        ),
        "gate_wait_s": Key(
            float, "time parked at the gate, engines off, before engine start", 120.0, lo=0, hi=86400
        ),
        "fdm_hz": Key(int, "JSBSim integration rate, Hz: the FlightTrack's sample rate", 120, lo=60, hi=480),
    },
    "origin": _runway_keys("departure"),
    "destination": _runway_keys("arrival"),
    "taxi_out": _taxi_keys(),
    "taxi_in": _taxi_keys(),
    "takeoff": {
        "thrust_norm": Key(
            float,
            "takeoff throttle (1 = maximum); absent: drawn per flight so that the takeoff "
            "acceleration follows the type's real traffic (OpenAP WRAP)",
            optional=True,
            lo=0.7,
            hi=1.0,
        ),
        "flaps_norm": Key(
            float, "takeoff flap command; absent: the type's default", optional=True, lo=0, hi=1
        ),
    },
    "cruise": {
        "altitude_m": Key(float, "cruise altitude above mean sea level", lo=300, hi=13500),
        "mach": Key(float, "cruise Mach number", lo=0.3, hi=0.9),
    },
    "route": {
        "waypoints": Key(list, "[[lat_deg, lon_deg], ...] flown before the approach fix", []),
    },
    "turbulence": {
        "start_s": Key(float, "start, seconds after liftoff", lo=0, hi=86400),
        "duration_s": Key(float, "duration", lo=1, hi=86400),
        "severity": Key(str, "category (ICAO Annex 3 peak-EDR bands)", choices=SEVERITIES[1:]),
        "edr": Key(
            float,
            "eddy dissipation rate, m^2/3 s^-1; absent: drawn inside the severity's band",
            optional=True,
            lo=0.01,
            hi=1.0,
        ),
    },
    "atmosphere": {
        "surface_wind_mps": Key(
            float,
            "wind at 20 ft above ground (sets low-level gustiness); absent: drawn",
            optional=True,
            lo=0,
            hi=30,
        ),
        "background_edr": Key(
            float,
            "background turbulence above 2000 ft, EDR m^2/3 s^-1; absent: drawn",
            optional=True,
            lo=0.001,
            hi=0.1,
        ),
        "convective_velocity_mps": Key(
            float,
            "the mixed layer's convective velocity scale w* (daytime thermals; 0: none); absent: drawn",
            optional=True,
            lo=0,
            hi=3,
        ),
        "departure_qnh_hpa": Key(
            float,
            "the departure airport's QNH (sea-level pressure setting); absent: drawn",
            optional=True,
            lo=QNH_RANGE_HPA[0],
            hi=QNH_RANGE_HPA[1],
        ),
        "arrival_qnh_hpa": Key(
            float,
            "the arrival airport's QNH; absent: drawn",
            optional=True,
            lo=QNH_RANGE_HPA[0],
            hi=QNH_RANGE_HPA[1],
        ),
        "isa_dev_k": Key(
            float,
            "temperature deviation from the ISA at both airports, K; absent: drawn per airport",
            optional=True,
            lo=ISA_DEV_RANGE_K[0],
            hi=ISA_DEV_RANGE_K[1],
        ),
    },
    "cabin": {
        "hold": Key(
            str,
            "the cargo hold: pressurised (the cabin's pressure, as on every profiled type) or "
            "unpressurised (ambient: some cargo aircraft's holds)",
            "pressurised",
            choices=HOLD_OPTIONS,
        ),
    },
    "descent": {
        "angle_deg": Key(
            float,
            "descent path angle from cruise to the glideslope; absent: the aircraft type's "
            "(2.8, the Fokker 100 2.5)",
            optional=True,
            lo=1.5,
            hi=4.0,
        ),
    },
    "approach": {
        "glideslope_deg": Key(float, "ILS glideslope angle", 3.0, lo=2.5, hi=4.0),
        "fix_nm": Key(
            float, "approach fix on the extended centreline, nm before the threshold", 16.0, lo=6, hi=40
        ),
        "landing_flaps_norm": Key(
            float, "landing flap command; absent: the type's default", optional=True, lo=0, hi=1
        ),
    },
    "landing": {
        "autobrake_decel_mps2": Key(float, "autobrake deceleration target", 1.5, lo=0.5, hi=3.5),
        "quality": Key(
            str, "touchdown sink speed distribution (normal, firm, hard)", "normal", choices=LANDING_QUALITIES
        ),
        "sink_mps": Key(
            float,
            f"touchdown sink speed the flare aims at (1 ft/s = {FT_M:g} m/s); absent: drawn by quality",
            optional=True,
            lo=0.15,
            hi=2.9,
        ),
        "go_arounds": Key(
            int,
            "go-arounds ordered at the flare height (air traffic control, an occupied runway) "
            "before the landing, each followed by a circuit and another approach",
            0,
            lo=0,
            hi=2,
        ),
    },
    "shutdown": {
        "post_shutdown_s": Key(float, "time recorded after engines off", 30.0, lo=0, hi=86400),
    },
    "carrier": {
        "kind": Key(str, "what carries the sensor", _CARRIER.kind, choices=CARRIER_KINDS),
        "placement": Key(str, "where it travels on board", _CARRIER.placement, choices=tuple(PLACEMENTS)),
        "terminal_walk_s": Key(
            float, "first walk through the terminal", _CARRIER.terminal_walk_s, lo=0, hi=86400
        ),
        "terminal_rest_s": Key(
            float, "resting in the terminal (truly static)", _CARRIER.terminal_rest_s, lo=0, hi=86400
        ),
        "gate_walk_s": Key(float, "walk to the gate", _CARRIER.gate_walk_s, lo=0, hi=86400),
        "gate_rest_s": Key(float, "resting at the gate (truly static)", _CARRIER.gate_rest_s, lo=0, hi=86400),
        "boarding_s": Key(
            float, "boarding walk (or loading, for a parcel)", _CARRIER.boarding_s, lo=0, hi=3600
        ),
        "stow_before_engine_start_s": Key(
            float,
            "bag stowed this long before engine start",
            _CARRIER.stow_before_engine_start_s,
            lo=0,
            hi=3600,
        ),
        "handled_in_cruise": Key(
            int, "times the bag is taken out and put back in cruise", _CARRIER.handled_in_cruise, lo=0, hi=20
        ),
        "handling_s": Key(float, "duration of one handling", _CARRIER.handling_s, lo=1, hi=600),
        "deplane_after_engines_off_s": Key(
            float, "wait on board after engines off", _CARRIER.deplane_after_engines_off_s, lo=0, hi=3600
        ),
        "deplaning_s": Key(float, "deplaning walk (or unloading)", _CARRIER.deplaning_s, lo=0, hi=3600),
        "arrival_rest_s": Key(
            float, "resting at the destination (truly static)", _CARRIER.arrival_rest_s, lo=0, hi=86400
        ),
        "truck_s": Key(float, "road transport before and after (parcel)", _CARRIER.truck_s, lo=0, hi=86400),
        "gait_vertical_g": Key(
            float, "walking: vertical step-frequency amplitude", _CARRIER.gait_vertical_g, lo=0, hi=2
        ),
        "gait_lateral_g": Key(
            float, "walking: lateral amplitude (half the step frequency)", _CARRIER.gait_lateral_g, lo=0, hi=2
        ),
        "gait_fore_aft_g": Key(float, "walking: fore-aft amplitude", _CARRIER.gait_fore_aft_g, lo=0, hi=2),
        "putdown_peak_g": Key(
            float, "peak of the shock when the bag is set down", _CARRIER.putdown_peak_g, lo=0.05, hi=50
        ),
        "putdown_ms": Key(float, "duration of that shock", _CARRIER.putdown_ms, lo=2, hi=1000),
        "pickup_height_m": Key(
            float, "height the bag is lifted when picked up", _CARRIER.pickup_height_m, lo=0, hi=3
        ),
        "pickup_s": Key(float, "duration of the lift", _CARRIER.pickup_s, lo=0.1, hi=10),
        "packing": Key(
            str,
            "what surrounds the sensor (soft handbag, rigid hard-shell case, boxed parcel); "
            "absent: the kind's (handbag soft, parcel boxed)",
            optional=True,
            choices=tuple(PACKINGS),
        ),
        "cabin_row": Key(
            str,
            "cabin row whose floor vibration the bag feels (ignored in the hold); absent: drawn per flight",
            optional=True,
            choices=CABIN_ROWS,
        ),
        "stowed_yaw_deg": Key(
            float,
            "a handbag set down on board lies level; its sensor x axis this far from "
            "the fuselage axis (0: along it); absent: drawn per put-down",
            optional=True,
            lo=0,
            hi=360,
        ),
        "cruise_placement": Key(
            str,
            "a handbag moved there after reaching cruise and back before the descent "
            "(baggage is stowed for taxi, takeoff and landing: 14 CFR 121.589); absent: "
            "it stays put",
            optional=True,
            choices=tuple(PLACEMENTS),
        ),
    },
    "sensor": {
        "preset": Key(str, "accelerometer preset", "lis302dl-logged16", choices=tuple(SENSOR_PRESETS)),
        "odr_hz": Key(float, "output data rate; absent: the preset's", optional=True, lo=0.5, hi=1000),
        "vibration_level": Key(
            float,
            "multiplier of the floor vibration drawn for the flight (a population's "
            "spread of levels); absent: 1",
            optional=True,
            lo=0.05,
            hi=20,
        ),
        "baro": Key(
            str,
            "barometer preset fitted beside the accelerometer (samples gain baro_pa); absent: none",
            optional=True,
            choices=tuple(BARO_PRESETS),
        ),
        "baro_odr_hz": Key(
            float, "the barometer's output data rate; absent: the preset's", optional=True, lo=0.1, hi=500
        ),
        "gyro": Key(
            str,
            "gyroscope preset sampled with the accelerometer (samples gain gyro_*_dps); absent: none",
            optional=True,
            choices=tuple(GYRO_PRESETS),
        ),
    },
}
ARRAY_SECTIONS = {"turbulence"}  # [[turbulence]] tables
# the [model] table: overrides of uncertain model parameters, name -> number (free keys, checked against
# flightmode.scenarios.model.registry(); `flightmode scenarios --model` lists them)
MODEL_SECTION = "model"
OPTIONAL_SECTIONS = {
    "takeoff",
    "route",
    "turbulence",
    "atmosphere",
    "cabin",
    "descent",
    "approach",
    "landing",
    "shutdown",
    "carrier",
    "sensor",
}


def _fail(source: str, path: str, value: Any, allowed: str, hint: str = "") -> ScenarioError:
    return ScenarioError(f"{source}: {path} = {value!r}: {allowed}{hint}")


def _check_value(source: str, path: str, key: Key, value: Any) -> Any:
    want = key.type
    if want is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if want is int and isinstance(value, float) and value.is_integer():
        value = int(value)
    well_typed = isinstance(value, want) and not isinstance(value, bool)  # a flag: value stays Any
    if not well_typed:
        name = want.__name__ if isinstance(want, type) else "/".join(t.__name__ for t in want)
        article = "an" if name[0] in "aeiou" else "a"
        raise _fail(source, path, value, f"must be {article} {name} ({key.doc})")
    if isinstance(value, float) and not math.isfinite(value):
        raise _fail(source, path, value, "must be finite")
    if key.choices is not None and value not in key.choices:
        raise _fail(
            source, path, value, f"must be one of {', '.join(key.choices)}", did_you_mean(value, key.choices)
        )
    if key.lo is not None and value < key.lo:
        raise _fail(source, path, value, f"must be >= {key.lo:g} ({key.doc})")
    if key.hi is not None and value > key.hi:
        raise _fail(source, path, value, f"must be <= {key.hi:g} ({key.doc})")
    return value


def _section(source: str, name: str, table: Any) -> dict[str, Any]:
    keys = SPEC[name]
    if not isinstance(table, dict):
        raise _fail(source, f"[{name}]", table, "must be a table of keys")
    for k in table:
        if k not in keys:
            raise _fail(
                source,
                f"[{name}].{k}",
                table[k],
                f"unknown key; allowed: {', '.join(keys)}",
                did_you_mean(k, keys),
            )
    out = {}
    for k, key in keys.items():
        path = f"[{name}].{k}"
        if k in table:
            out[k] = _check_value(source, path, key, table[k])
        elif key.default is not None:
            out[k] = key.default
        elif key.optional:
            out[k] = None
        else:
            raise ScenarioError(f"{source}: {path} is missing: required ({key.doc})")
    return out


def validate_doc(doc: dict[str, Any], source: str = "<scenario>") -> dict[str, Any]:
    """Check a parsed TOML document key by key against :data:`SPEC`; return it normalised: every
    section present, every key filled (defaults; ``None`` for an absent optional key), numbers as the
    declared type, ``turbulence`` a list of such sections. Cross-key checks (the route length, the
    sensor's rates) are :func:`check_scenario`'s."""
    if not isinstance(doc, dict):
        raise ScenarioError(f"{source}: a scenario must be a table of sections, got {type(doc).__name__}")
    for sec in doc:
        if sec not in SPEC and sec != MODEL_SECTION:
            raise _fail(
                source,
                f"[{sec}]",
                "...",
                f"unknown section; allowed: {', '.join([*SPEC, MODEL_SECTION])}",
                did_you_mean(sec, [*SPEC, MODEL_SECTION]),
            )
    for sec in SPEC:
        if sec not in doc and sec not in OPTIONAL_SECTIONS:
            raise ScenarioError(f"{source}: section [{sec}] is missing: required")
    doc = dict(doc)
    for side in (
        "origin",
        "destination",
    ):  # a runway named by its airport and ident alone: OurAirports' figures
        t = doc.get(side)
        if isinstance(t, dict) and "icao" in t and "runway" in t and "threshold_lat_deg" not in t:
            from flightmode.scenarios.airports import runway_keys

            try:
                doc[side] = runway_keys(str(t["icao"]), str(t["runway"]), landing=side == "destination") | t
            except ScenarioError as e:
                raise ScenarioError(f"{source}: [{side}]: {e}") from None
    v: dict[str, Any] = {
        sec: _section(source, sec, doc.get(sec, {})) for sec in SPEC if sec not in ARRAY_SECTIONS
    }

    turb_tables = doc.get("turbulence", [])
    if not isinstance(turb_tables, list):
        raise _fail(source, "[turbulence]", "...", "must be an array of tables: write [[turbulence]]")
    v["turbulence"] = [_section(source, "turbulence", t) for t in turb_tables]

    for side in ("taxi_out", "taxi_in"):
        holds = []
        for j, h in enumerate(v[side]["holds_s"]):
            holds.append(
                _check_value(
                    source, f"[{side}].holds_s[{j}]", Key(float, "a hold time in seconds", lo=0, hi=86400), h
                )
            )
        v[side]["holds_s"] = holds
    waypoints = []
    for j, wp in enumerate(v["route"]["waypoints"]):
        if not (isinstance(wp, list) and len(wp) == 2):
            raise _fail(source, f"[route].waypoints[{j}]", wp, "must be [lat_deg, lon_deg]")
        lat = _check_value(source, f"[route].waypoints[{j}][0]", Key(float, "latitude", lo=-90, hi=90), wp[0])
        lon = _check_value(
            source, f"[route].waypoints[{j}][1]", Key(float, "longitude", lo=-180, hi=180), wp[1]
        )
        waypoints.append([lat, lon])
    v["route"]["waypoints"] = waypoints
    from flightmode.scenarios.model import check_model

    v[MODEL_SECTION] = check_model(doc.get(MODEL_SECTION), source)  # name -> value, validated
    return v


def check_scenario(
    source: str,
    plan: FlightPlan,
    sensor_preset: str,
    sensor_odr_hz: float | None,
    baro: str | None = None,
    baro_odr_hz: float | None = None,
) -> None:
    """The checks across keys: the route is long enough for the cruise asked, the sensor parts have the
    output data rates asked."""
    _check_distance(source, plan)
    allowed = SENSOR_PRESETS[sensor_preset].allowed_odr_hz
    if sensor_odr_hz is not None and sensor_odr_hz not in allowed:
        raise _fail(
            source,
            "[sensor].odr_hz",
            sensor_odr_hz,
            f"the {sensor_preset} part has only {', '.join(f'{f:g}' for f in allowed)} Hz",
        )
    if baro_odr_hz is not None:
        if baro is None:
            raise _fail(
                source, "[sensor].baro_odr_hz", baro_odr_hz, "needs [sensor].baro (the barometer preset)"
            )
        allowed = BARO_PRESETS[baro].allowed_odr_hz
        if baro_odr_hz not in allowed:
            raise _fail(
                source,
                "[sensor].baro_odr_hz",
                baro_odr_hz,
                f"the {baro} part has only {', '.join(f'{f:g}' for f in allowed)} Hz",
            )


CLIMB_GRADIENT = 0.06  # a typical airliner climb gradient (6 %, about 1800 ft/min at 300 kt)


def route_length_m(plan: FlightPlan) -> float:
    """Origin threshold -> waypoints -> approach fix -> destination threshold, along great circles."""
    from flightmode.sim.flight.geodesy import destination_point

    d = plan.destination
    fix = destination_point(
        d.lat_deg, d.lon_deg, (d.heading_deg + 180.0) % 360.0, plan.approach_fix_nm * NM_M
    )
    pts = [(plan.origin.lat_deg, plan.origin.lon_deg), *plan.waypoints, fix]
    total = sum(float(great_circle_distance_m(*a, *b)) for a, b in zip(pts, pts[1:]))
    return total + plan.approach_fix_nm * NM_M


def _check_distance(source: str, plan: FlightPlan) -> None:
    """The route must be long enough to climb to the cruise altitude and descend from it."""
    climb = (plan.cruise_alt_m - plan.origin.elevation_m) / CLIMB_GRADIENT
    gs = math.tan(math.radians(plan.glideslope_deg))
    h_gs = 10.0 * NM_M * gs
    descent = 10.0 * NM_M + max(0.0, plan.cruise_alt_m - plan.destination.elevation_m - h_gs) / math.tan(
        math.radians(plan.descent_angle_deg)
    )
    need = climb + descent
    have = route_length_m(plan)
    if plan.cruise_alt_m <= max(plan.origin.elevation_m, plan.destination.elevation_m) + 300.0:
        raise _fail(
            source, "[cruise].altitude_m", plan.cruise_alt_m, "must be at least 300 m above both airports"
        )
    ceiling_m = PROFILES[plan.aircraft].ceiling_ft * FT_M if plan.aircraft in PROFILES else math.inf
    if plan.cruise_alt_m > ceiling_m + 0.5:
        raise _fail(
            source,
            "[cruise].altitude_m",
            plan.cruise_alt_m,
            f"above the {plan.aircraft}'s maximum operating altitude, {ceiling_m:.0f} m "
            f"({PROFILES[plan.aircraft].ceiling_ft:,.0f} ft); lower the cruise",
        )
    if have < need:
        max_alt = plan.origin.elevation_m + (have - 10.0 * NM_M) / (
            1.0 / CLIMB_GRADIENT + 1.0 / math.tan(math.radians(plan.descent_angle_deg))
        )
        raise _fail(
            source,
            "[cruise].altitude_m",
            plan.cruise_alt_m,
            f"airports too close for this cruise: the route is {have / 1000:.0f} km but climbing to it and "
            f"descending from it needs {need / 1000:.0f} km; lower the cruise to at most {max_alt:.0f} m "
            "or add [route].waypoints",
        )


def read_toml(path: Path) -> dict[str, Any]:
    """Read a scenario file's TOML document (not yet validated)."""
    path = Path(path)
    source = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError(f"{source}: no such scenario file") from None
    except (IsADirectoryError, UnicodeDecodeError) as e:
        raise ScenarioError(f"{source}: not a readable TOML text file ({e.__class__.__name__})") from None
    return parse_toml(text, source)


def parse_toml(text: str, source: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(f"{source}: TOML syntax error: {e}") from None


def spec_text() -> str:
    """Human-readable specification of every section and key."""
    lines = []
    for sec, keys in SPEC.items():
        head = f"[[{sec}]]" if sec in ARRAY_SECTIONS else f"[{sec}]"
        lines.append(head + ("  (optional)" if sec in OPTIONAL_SECTIONS else ""))
        for k, key in keys.items():
            t = key.type.__name__ if isinstance(key.type, type) else str(key.type)
            rng = ""
            if key.lo is not None or key.hi is not None:
                rng = f" [{key.lo if key.lo is not None else ''}..{key.hi if key.hi is not None else ''}]"
            if key.choices:
                rng = f" one of {', '.join(key.choices)}"
            dflt = (
                " (required)" if key.default is None and not key.optional else f" (default {key.default!r})"
            )
            lines.append(f"  {k}: {t}{rng}{dflt} - {key.doc}")
    lines.append(f"[{MODEL_SECTION}]  (optional)")
    lines.append(
        '  "<parameter>": float - an uncertain model parameter overridden within its declared range '
        "(`flightmode scenarios --model` lists them)"
    )
    return "\n".join(lines)
