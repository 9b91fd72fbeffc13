"""The Scenario: one typed, frozen, validated description of a run (what flies, how the bag travels,
which sensor records it, and the run's seed).

Built from a TOML file (:meth:`Scenario.from_toml`), a built-in name (:meth:`Scenario.builtin`), or
any scenario with overrides (:meth:`Scenario.replace`, validated as strictly as a file). It writes
itself back as TOML (:meth:`Scenario.to_toml`) and reads back equal: ``Scenario.from_toml_text(
s.to_toml()) == s`` for every scenario. :meth:`Scenario.digest` (SHA-256 of that TOML) identifies it.

    >>> s = Scenario.builtin("pattern")
    >>> s.aircraft, s.seed
    ('737', 1)
    >>> s2 = s.replace(seed=3, cruise={"altitude_m": 1000.0})
    >>> Scenario.from_toml_text(s2.to_toml()) == s2
    True
"""

from __future__ import annotations

import dataclasses
import hashlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from flightmode.errors import ScenarioError, did_you_mean

DEFAULT_SCENARIO = "gva-lhr-a320"


@dataclass(frozen=True, slots=True)
class SensorChoice:
    """The ``[sensor]`` section: an accelerometer preset, its output data rate (None: the preset's), and
    the floor vibration's multiplier (None: 1)."""

    preset: str = "lis302dl-logged16"
    odr_hz: float | None = None
    vibration_level: float | None = None  # the floor vibration's multiplier (None: 1, as drawn)
    baro: str | None = None  # a barometer preset fitted beside the accelerometer (None: none)
    baro_odr_hz: float | None = None  # its output data rate (None: the preset's)
    gyro: str | None = None  # a gyroscope preset sampled with the accelerometer (None: none)


def resolve_name(cls: Any, name_or_path: str | Path, what: str) -> Any:
    """``cls.from_toml(path)`` for a ``.toml`` path or any file, else ``cls.builtin(name)``: the
    resolution of :class:`Scenario` and :class:`~flightmode.scenarios.family.Family` (``what``: which,
    for the error). A folder of a built-in's name (a dataset made with ``--out airline-mix``, run again
    from beside it) does not hide the built-in; a folder that is none is a ScenarioError naming it."""
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.is_file():
        return cls.from_toml(p)
    try:
        return cls.builtin(str(name_or_path))
    except ScenarioError as e:
        if p.is_dir():
            raise ScenarioError(f"{p} is a folder, not a {what} .toml file: {e}") from None
        raise


@dataclass(frozen=True, slots=True)
class Scenario:
    """A validated scenario. ``plan`` is what the flight side flies, ``carrier`` the bag's life around
    it, ``sensor`` what records it; ``seed`` seeds every random stream of the run by name
    (:class:`flightmode.streams.Streams`). Build one with the class methods, never field by field."""

    description: str
    seed: int
    plan: Any  # flightmode.sim.flight.plan.FlightPlan
    carrier: Any  # flightmode.sim.sensor.carrier.CarrierSpec
    sensor: SensorChoice
    source: str = field(default="<scenario>", compare=False)  # where it came from, for messages
    # the [model] table: overrides of uncertain model parameters (flightmode.uncertain), sorted
    # (name, value) pairs; () runs every parameter at its nominal value
    model: tuple[tuple[str, float], ...] = ()

    # ------------------------------------------------------------------ reading
    @classmethod
    def from_doc(cls, doc: Mapping[str, Any], source: str = "<scenario>") -> Scenario:
        """From a parsed TOML document (a dict of sections), validated against the spec."""
        from flightmode.scenarios.spec import check_scenario, validate_doc
        from flightmode.sim.flight.plan import FlightPlan, Runway, TaxiPlan, TurbulenceSegment
        from flightmode.sim.sensor.carrier import CarrierSpec

        v = validate_doc(dict(doc), source)

        def runway(sec: str) -> Runway:
            r = v[sec]
            return Runway(
                r["icao"],
                r["runway"],
                r["threshold_lat_deg"],
                r["threshold_lon_deg"],
                r["elevation_m"],
                r["heading_deg"],
                r["length_m"],
                r["width_m"],
            )

        def taxi(sec: str) -> TaxiPlan:
            t = v[sec]
            return TaxiPlan(
                t["length_m"],
                tuple(t["holds_s"]),
                t["lineup_hold_s"],
                t["taxiway_offset_m"],
                t["apron_depth_m"],
            )

        s = v["scenario"]
        plan = FlightPlan(
            name=s["name"],
            aircraft=s["aircraft"],
            origin=runway("origin"),
            destination=runway("destination"),
            taxi_out=taxi("taxi_out"),
            taxi_in=taxi("taxi_in"),
            cruise_alt_m=v["cruise"]["altitude_m"],
            cruise_mach=v["cruise"]["mach"],
            gate_wait_s=s["gate_wait_s"],
            takeoff_thrust_norm=v["takeoff"]["thrust_norm"],
            takeoff_flaps_norm=v["takeoff"]["flaps_norm"],
            landing_flaps_norm=v["approach"]["landing_flaps_norm"],
            waypoints=tuple((lat, lon) for lat, lon in v["route"]["waypoints"]),
            turbulence=tuple(
                TurbulenceSegment(t["start_s"], t["duration_s"], t["severity"], t["edr"])
                for t in v["turbulence"]
            ),
            descent_angle_deg=_descent_angle_deg(v["descent"]["angle_deg"], s["aircraft"]),
            glideslope_deg=v["approach"]["glideslope_deg"],
            approach_fix_nm=v["approach"]["fix_nm"],
            autobrake_decel_mps2=v["landing"]["autobrake_decel_mps2"],
            post_shutdown_s=v["shutdown"]["post_shutdown_s"],
            fdm_hz=s["fdm_hz"],
            landing_quality=v["landing"]["quality"],
            touchdown_sink_mps=v["landing"]["sink_mps"],
            go_arounds=v["landing"]["go_arounds"],
            surface_wind_mps=v["atmosphere"]["surface_wind_mps"],
            background_edr=v["atmosphere"]["background_edr"],
            convective_velocity_mps=v["atmosphere"]["convective_velocity_mps"],
            departure_qnh_hpa=v["atmosphere"]["departure_qnh_hpa"],
            arrival_qnh_hpa=v["atmosphere"]["arrival_qnh_hpa"],
            isa_dev_k=v["atmosphere"]["isa_dev_k"],
            hold=v["cabin"]["hold"],
        )
        sen = v["sensor"]
        sensor = SensorChoice(
            sen["preset"], sen["odr_hz"], sen["vibration_level"], sen["baro"], sen["baro_odr_hz"], sen["gyro"]
        )
        check_scenario(source, plan, sensor.preset, sensor.odr_hz, sensor.baro, sensor.baro_odr_hz)
        model = tuple(sorted(v["model"].items()))
        return cls(s["description"], s["seed"], plan, CarrierSpec(**v["carrier"]), sensor, source, model)

    @classmethod
    def from_toml_text(cls, text: str, source: str = "<scenario>") -> Scenario:
        from flightmode.scenarios.spec import parse_toml

        return cls.from_doc(parse_toml(text, source), source)

    @classmethod
    def from_toml(cls, path: str | Path) -> Scenario:
        """Read and validate a scenario file."""
        from flightmode.scenarios.spec import read_toml

        return cls.from_doc(read_toml(Path(path)), str(path))

    @classmethod
    def builtin(cls, name: str) -> Scenario:
        """A built-in scenario by name (``flightmode scenarios`` lists them)."""
        return cls.from_toml(builtin_path(name))

    @classmethod
    def resolve(cls, name_or_path: str | Path) -> Scenario:
        """A built-in name, or the path of a ``.toml`` file."""
        return resolve_name(cls, name_or_path, "scenario")

    # ------------------------------------------------------------------ properties
    @property
    def name(self) -> str:
        return self.plan.name

    @property
    def aircraft(self) -> str:
        return self.plan.aircraft

    @property
    def overrides(self) -> dict[str, float]:
        """The ``[model]`` overrides as a dict (name -> value; empty: every parameter nominal), what the
        flight and sensing functions read through :func:`flightmode.uncertain.value_of`."""
        return dict(self.model)

    @property
    def run_id(self) -> str:
        """The run folder's name: ``<name>-s<seed>``."""
        return f"{self.name}-s{self.seed}"

    # ------------------------------------------------------------------ writing
    def to_doc(self) -> dict[str, Any]:
        """The TOML document (a dict of sections) that reads back as this scenario: every key written,
        optional keys that are unset left out."""
        p, c = self.plan, self.carrier
        doc: dict[str, Any] = {
            "scenario": {
                "name": p.name,
                "description": self.description,
                "aircraft": p.aircraft,
                "seed": self.seed,
                "gate_wait_s": p.gate_wait_s,
                "fdm_hz": p.fdm_hz,
            },
            "origin": _runway_doc(p.origin),
            "destination": _runway_doc(p.destination),
            "taxi_out": _taxi_doc(p.taxi_out),
            "taxi_in": _taxi_doc(p.taxi_in),
            "takeoff": _drop_none({"thrust_norm": p.takeoff_thrust_norm, "flaps_norm": p.takeoff_flaps_norm}),
            "cruise": {"altitude_m": p.cruise_alt_m, "mach": p.cruise_mach},
            "route": {"waypoints": [[lat, lon] for lat, lon in p.waypoints]},
            "descent": {"angle_deg": p.descent_angle_deg},
            "approach": _drop_none(
                {
                    "glideslope_deg": p.glideslope_deg,
                    "fix_nm": p.approach_fix_nm,
                    "landing_flaps_norm": p.landing_flaps_norm,
                }
            ),
            "landing": _drop_none(
                {
                    "autobrake_decel_mps2": p.autobrake_decel_mps2,
                    "quality": p.landing_quality,
                    "sink_mps": p.touchdown_sink_mps,
                    "go_arounds": p.go_arounds or None,
                }
            ),
            "atmosphere": _drop_none(
                {
                    "surface_wind_mps": p.surface_wind_mps,
                    "background_edr": p.background_edr,
                    "convective_velocity_mps": p.convective_velocity_mps,
                    "departure_qnh_hpa": p.departure_qnh_hpa,
                    "arrival_qnh_hpa": p.arrival_qnh_hpa,
                    "isa_dev_k": p.isa_dev_k,
                }
            ),
            "cabin": {"hold": p.hold},
            "shutdown": {"post_shutdown_s": p.post_shutdown_s},
            "carrier": _drop_none(dataclasses.asdict(c)),
            "sensor": _drop_none(
                {
                    "preset": self.sensor.preset,
                    "odr_hz": self.sensor.odr_hz,
                    "vibration_level": self.sensor.vibration_level,
                    "baro": self.sensor.baro,
                    "baro_odr_hz": self.sensor.baro_odr_hz,
                    "gyro": self.sensor.gyro,
                }
            ),
        }
        if self.model:
            doc["model"] = dict(self.model)
        if p.turbulence:
            doc["turbulence"] = [
                _drop_none(
                    {"start_s": t.start_s, "duration_s": t.duration_s, "severity": t.severity, "edr": t.edr}
                )
                for t in p.turbulence
            ]
        return doc

    def to_toml(self) -> str:
        """The scenario as TOML text (reads back equal, :meth:`from_toml_text`)."""
        import tomli_w

        return tomli_w.dumps(self.to_doc())

    def digest(self) -> str:
        """SHA-256 of :meth:`to_toml`: equal digests, equal scenarios (the scenario hash)."""
        return hashlib.sha256(self.to_toml().encode("utf-8")).hexdigest()

    # ------------------------------------------------------------------ overrides
    def replace(self, **changes: Any) -> Scenario:
        """A new scenario with ``changes``, validated as strictly as a file. Keys:

        - a ``[scenario]`` key: ``seed=3``, ``aircraft="A320"``, ``name=...``, ``gate_wait_s=...``;
        - a section with a dict of its keys to change: ``cruise={"altitude_m": 9000.0}``, or a typed
          value for it (``carrier=CarrierSpec(...)``, ``origin=Runway(...)``, ``sensor=SensorChoice(...)``);
        - ``turbulence=[...]``: the whole list (dicts or ``TurbulenceSegment``);
        - a dotted ``"section.key"`` (pass as ``**{"cruise.altitude_m": 9000.0}``);
        - ``model={...}``: the whole ``[model]`` table (uncertain parameter name -> value; ``{}``: none).
        """
        from flightmode.scenarios.spec import SPEC

        doc = self.to_doc()
        for key, value in changes.items():
            if "." in key:
                sec, _, k = key.partition(".")
                if sec not in SPEC or sec == "turbulence":
                    raise ScenarioError(
                        f"replace({key}=...): unknown section '{sec}'{did_you_mean(sec, SPEC)}"
                    )
                if value is None:
                    doc.setdefault(sec, {}).pop(k, None)
                else:
                    doc.setdefault(sec, {})[k] = value
            elif key in SPEC["scenario"]:
                doc["scenario"][key] = value
            elif key == "turbulence":
                doc["turbulence"] = [_as_doc(t) for t in value]
            elif key == "model":
                if not isinstance(value, Mapping):
                    raise ScenarioError(
                        f"replace(model={value!r}): give a dict of uncertain parameter name -> value"
                    )
                doc["model"] = dict(value)
            elif key in SPEC:
                if isinstance(value, Mapping):  # a key given None is unset (an optional key's "absent")
                    merged = {**doc.get(key, {}), **value}
                    doc[key] = {k: v for k, v in merged.items() if v is not None}
                else:
                    doc[key] = _as_doc(value)
            else:
                allowed = [*SPEC["scenario"], *SPEC, "model"]
                raise ScenarioError(
                    f"replace({key}=...): not a scenario key or section{did_you_mean(key, allowed)}; "
                    f"allowed: {', '.join(allowed)}, or 'section.key'"
                )
        src = self.source if self.source.endswith(" (replaced)") else f"{self.source} (replaced)"
        return Scenario.from_doc(doc, src)


def _descent_angle_deg(angle_deg: float | None, aircraft: str) -> float:
    """The scenario's descent path angle, or its aircraft type's when the file gives none."""
    if angle_deg is not None:
        return float(angle_deg)
    from flightmode.sim.flight.aircraft.registry import get_profile

    return get_profile(aircraft).descent_angle_deg


def _drop_none(d: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in d.items() if v is not None}


def _runway_doc(r) -> dict[str, Any]:
    return {
        "icao": r.icao,
        "runway": r.name,
        "threshold_lat_deg": r.lat_deg,
        "threshold_lon_deg": r.lon_deg,
        "elevation_m": r.elevation_m,
        "heading_deg": r.heading_deg,
        "length_m": r.length_m,
        "width_m": r.width_m,
    }


def _taxi_doc(t) -> dict[str, Any]:
    return {
        "length_m": t.length_m,
        "holds_s": list(t.holds_s),
        "lineup_hold_s": t.lineup_hold_s,
        "taxiway_offset_m": t.taxiway_offset_m,
        "apron_depth_m": t.apron_depth_m,
    }


def _as_doc(value: Any) -> dict[str, Any]:
    """A typed section value as its TOML table."""
    from flightmode.sim.flight.plan import Runway, TaxiPlan, TurbulenceSegment

    if isinstance(value, Mapping):
        return dict(value)
    if isinstance(value, Runway):
        return _runway_doc(value)
    if isinstance(value, TaxiPlan):
        return _taxi_doc(value)
    if isinstance(value, TurbulenceSegment):
        return _drop_none(
            {
                "start_s": value.start_s,
                "duration_s": value.duration_s,
                "severity": value.severity,
                "edr": value.edr,
            }
        )
    if isinstance(value, SensorChoice):
        return _drop_none(dataclasses.asdict(value))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return _drop_none(dataclasses.asdict(value))
    raise ScenarioError(
        f"replace: cannot use a {type(value).__name__} as a scenario section; give a dict of its keys"
    )


# ---------------------------------------------------------------------- the built-in library
def builtin_names() -> list[str]:
    """Names of the built-in scenarios (TOML files shipped in ``flightmode.scenarios.library``)."""
    lib = resources.files("flightmode.scenarios.library")
    return sorted(p.name[:-5] for p in lib.iterdir() if p.name.endswith(".toml"))


def builtin_path(name: str) -> Path:
    names = builtin_names()
    if name not in names:
        raise ScenarioError(
            f"unknown scenario '{name}'{did_you_mean(name, names)}; built-in scenarios: {', '.join(names)} "
            "(or give the path of a .toml file)"
        )
    return Path(str(resources.files("flightmode.scenarios.library").joinpath(f"{name}.toml")))
