"""Scenario families: a population of flights described by distributions (a TOML file), whose member
``i`` is a plain :class:`~flightmode.scenarios.scenario.Scenario`.

Member ``i`` is drawn from the streams ``Streams(family seed).child("member/<i>")``
(:mod:`flightmode.streams`: a ``SeedSequence`` spawn key made of the names), one stream per choice, so
member 417 is regenerated alone, in any process, and adding a choice to the file format never moves
another choice's numbers. A family file (``flightmode family FILE --show 5``):

    [family]
    name = "airline-mix"            # also the dataset's name
    description = "..."
    seed = 2026

    [aircraft]                      # type -> weight (any positive numbers)
    A320 = 4
    737 = 3

    [routes]                        # pairs flown as given, or random pairs among airports (or both)
    pairs = [["LSGG", "EGLL"], ["LFPG", "LEMD"]]
    airports = ["EGLL", "LFPG", "EDDF"]
    countries = ["CH", "AT"]        # a region: every large airport of these countries (ISO 3166 codes)
    max_km = 2500                   # optional: longest random pair

    [turbulence]
    patch_probability = 0.3         # one patch en route (between top of climb and descent) with this probability
    severity = { light = 6, moderate = 3, severe = 1 }
    patch_s = [120, 600]            # its duration, uniform

    [landing]
    quality = { normal = 85, firm = 12, hard = 3 }

    [carrier]
    kind = { handbag = 1 }          # handbag or parcel (a parcel travels in the hold)
    placement = { under_seat = 5, overhead_bin = 3 }   # a handbag's
    handled_in_cruise = { 0 = 6, 1 = 3, 2 = 1 }
    truck_s = [0, 0]                # a parcel's road legs, uniform (s)
    terminal_walk_s = [60, 600]     # a handbag's walks and wait, uniform (s); absent: the defaults
    gate_walk_s = [30, 300]
    gate_rest_s = [300, 2400]

    [model]                         # optional: uncertain model parameters for every member
    "turbulence.background_scale" = 0.5   # (`flightmode scenarios --model` lists them)

    [sensor]
    preset = { lis302dl-logged16 = 1 }
    vibration_level = [0.7, 1.4]    # optional: the floor vibration's multiplier, log-uniform
    baro = "bmp581"                 # optional: a barometer fitted to every member (absent: none)
    gyro = "bmi270"                 # optional: a gyroscope beside every accelerometer (absent: none)

A type is only given routes it can fly (range, runway length); every member is validated as strictly
as a scenario file. Everything but ``[family]``, ``[aircraft]`` and ``[routes]`` is optional.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from flightmode.errors import ScenarioError, did_you_mean

SECTIONS = {
    "family": {"name", "description", "seed"},
    "aircraft": None,  # free keys: types
    "routes": {"pairs", "airports", "countries", "max_km"},
    "turbulence": {"patch_probability", "severity", "patch_s"},
    "landing": {"quality"},
    "carrier": {
        "kind",
        "placement",
        "handled_in_cruise",
        "truck_s",
        "terminal_walk_s",
        "gate_walk_s",
        "gate_rest_s",
    },
    "sensor": {"preset", "vibration_level", "baro", "gyro"},
    "model": None,  # free keys: uncertain model parameters (flightmode.scenarios.model), every member's
}
EN_ROUTE_CLIMB_MPS = 10.0  # the estimate of the top of climb and descent for placing a patch (WRAP: 5-13 m/s)
EN_ROUTE_SPEED_MPS = 200.0  # mean ground speed airborne (390 kt)


@dataclass(frozen=True, slots=True)
class Weighted:
    """A discrete distribution: choices and their probabilities."""

    choices: tuple[str, ...]
    p: tuple[float, ...]

    def draw(self, rng) -> str:
        return self.choices[int(rng.choice(len(self.choices), p=self.p))]


def _weighted(source: str, path: str, table: Any, allowed) -> Weighted:
    if not isinstance(table, Mapping) or not table:
        raise ScenarioError(
            f"{source}: {path} must be a table of choice = weight, e.g. {{ A320 = 2, 737 = 1 }}"
        )
    names, w = [], []
    for k, v in table.items():
        k = str(k)
        if allowed is not None and k not in allowed:
            raise ScenarioError(
                f"{source}: {path}: unknown choice '{k}'{did_you_mean(k, allowed)}; "
                f"allowed: {', '.join(map(str, allowed))}"
            )
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
            raise ScenarioError(f"{source}: {path}.{k} = {v!r}: a weight must be a number >= 0")
        names.append(k)
        w.append(float(v))
    total = sum(w)
    if total <= 0:
        raise ScenarioError(
            f"{source}: {path}: the weights sum to {total:g}; give at least one positive weight"
        )
    return Weighted(tuple(names), tuple(x / total for x in w))


def _range(source: str, path: str, v: Any, lo: float, hi: float) -> tuple[float, float]:
    if (
        not isinstance(v, list)
        or len(v) != 2
        or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v)
        or not lo <= v[0] <= v[1] <= hi
    ):
        raise ScenarioError(
            f"{source}: {path} = {v!r}: give [low, high] with {lo:g} <= low <= high <= {hi:g}"
        )
    return float(v[0]), float(v[1])


@dataclass(frozen=True)
class Family:
    """A validated family (:func:`Family.from_toml`)."""

    name: str
    description: str
    seed: int
    aircraft: Weighted
    pairs: tuple[tuple[str, str], ...]
    airports: tuple[str, ...]
    max_km: float
    patch_probability: float
    severity: Weighted
    patch_s: tuple[float, float]
    landing: Weighted
    kind: Weighted
    placement: Weighted
    handled: Weighted
    truck_s: tuple[float, float]
    walks: tuple[tuple[str, tuple[float, float]], ...]  # (carrier key, uniform range) for a handbag
    sensor: Weighted
    vibration_level: tuple[float, float] | None
    baro: str | None
    gyro: str | None
    text: str  # the file's text (what the dataset stores)
    source: str = "<family>"
    # the [model] table: every member's overrides of uncertain model parameters (sorted name, value)
    model: tuple[tuple[str, float], ...] = ()

    # ------------------------------------------------------------------ reading
    @classmethod
    def from_toml_text(cls, text: str, source: str = "<family>") -> Family:
        import tomllib

        from flightmode.labels import SEVERITIES
        from flightmode.scenarios import airports as ap
        from flightmode.scenarios.model import check_model
        from flightmode.scenarios.spec import SPEC
        from flightmode.sim.flight.aircraft.registry import PROFILES
        from flightmode.sim.sensor.barometer import PRESETS as BARO_PRESETS
        from flightmode.sim.sensor.gyroscope import PRESETS as GYRO_PRESETS

        try:
            doc = tomllib.loads(text)
        except tomllib.TOMLDecodeError as e:
            raise ScenarioError(f"{source}: not valid TOML: {e}") from None
        for sec, table in doc.items():
            if not isinstance(table, dict):
                raise ScenarioError(
                    f"{source}: [{sec}] must be a table (a [{sec}] header), not {type(table).__name__}"
                )
            if sec not in SECTIONS:
                raise ScenarioError(
                    f"{source}: unknown section [{sec}]{did_you_mean(sec, SECTIONS)}; "
                    f"sections: {', '.join(SECTIONS)}"
                )
            keys = SECTIONS[sec]
            if keys is not None:
                for k in table:
                    if k not in keys:
                        raise ScenarioError(
                            f"{source}: unknown key [{sec}].{k}{did_you_mean(k, keys)}; "
                            f"keys: {', '.join(sorted(keys))}"
                        )
        for sec in ("family", "aircraft", "routes"):
            if sec not in doc:
                raise ScenarioError(f"{source}: missing section [{sec}]")
        fam = doc["family"]
        for k in ("name", "seed"):
            if k not in fam:
                raise ScenarioError(f"{source}: missing key [family].{k}")
        seed = fam["seed"]
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ScenarioError(f"{source}: [family].seed = {seed!r}: must be an integer >= 0")
        routes = doc["routes"]
        pairs = []
        given = routes.get("pairs", [])
        codes = routes.get("airports", [])
        for key, v in (("pairs", given), ("airports", codes)):
            if not isinstance(v, list):
                raise ScenarioError(f"{source}: [routes].{key} must be a list")
        from flightmode.scenarios.routes import MIN_ROUTE_M
        from flightmode.sim.flight.geodesy import gc_distance_m

        for pr in given:
            if not (isinstance(pr, list) and len(pr) == 2 and all(isinstance(c, str) for c in pr)):
                raise ScenarioError(
                    f'{source}: [routes].pairs: {pr!r} is not a pair of ICAO codes like ["LSGG", "EGLL"]'
                )
            a, b = ap.airport(pr[0]), ap.airport(pr[1])
            if gc_distance_m(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg) < MIN_ROUTE_M:
                raise ScenarioError(
                    f"{source}: [routes].pairs: {a.icao} to {b.icao} is shorter than "
                    f"{MIN_ROUTE_M / 1000:.0f} km; drop it"
                )
            pairs.append((a.icao, b.icao))
        for c in codes:
            if not isinstance(c, str):
                raise ScenarioError(f'{source}: [routes].airports: {c!r} is not an ICAO code like "LSGG"')
        airports_ = tuple(ap.airport(c).icao for c in codes)
        countries = routes.get("countries", [])
        if not isinstance(countries, list) or not all(isinstance(c, str) for c in countries):
            raise ScenarioError(
                f'{source}: [routes].countries must be a list of ISO 3166 codes like ["CH", "AT"]'
            )
        known = {a.country for a in ap.airports().values()}
        for c in countries:
            if c.upper() not in known:
                raise ScenarioError(
                    f"{source}: [routes].countries: unknown country code '{c}'{did_you_mean(c.upper(), known)}"
                )
        want = {c.upper() for c in countries}
        region = sorted(
            a.icao for a in ap.airports().values() if a.country in want and a.kind == "large_airport"
        )
        airports_ = tuple(dict.fromkeys(airports_ + tuple(region)))  # the list's order, then the region's
        if not pairs and len(airports_) < 2:
            raise ScenarioError(
                f"{source}: [routes] needs pairs, or at least two airports (or countries' large "
                "airports) to pair at random"
            )
        max_km = routes.get("max_km", math.inf)
        if isinstance(max_km, bool) or not isinstance(max_km, (int, float)) or max_km <= 0:
            raise ScenarioError(f"{source}: [routes].max_km = {max_km!r}: must be a positive number of km")
        turb, land, car, sen = (doc.get(k, {}) for k in ("turbulence", "landing", "carrier", "sensor"))
        pp = turb.get("patch_probability", 0.0)
        if isinstance(pp, bool) or not isinstance(pp, (int, float)) or not 0.0 <= pp <= 1.0:
            raise ScenarioError(f"{source}: [turbulence].patch_probability = {pp!r}: must be within 0..1")
        carrier_keys = SPEC["carrier"]
        placements = carrier_keys["placement"].choices
        assert placements is not None  # a choice key (spec.SPEC)
        out = cls(
            name=str(fam["name"]),
            description=str(fam.get("description", "")),
            seed=seed,
            aircraft=_weighted(source, "[aircraft]", doc["aircraft"], sorted(PROFILES)),
            pairs=tuple(pairs),
            airports=airports_,
            max_km=float(max_km),
            patch_probability=float(pp),
            severity=_weighted(
                source, "[turbulence].severity", turb.get("severity", {"light": 1}), SEVERITIES[1:]
            ),
            patch_s=_range(source, "[turbulence].patch_s", turb.get("patch_s", [120, 600]), 1, 7200),
            landing=_weighted(
                source,
                "[landing].quality",
                land.get("quality", {"normal": 1}),
                SPEC["landing"]["quality"].choices,
            ),
            kind=_weighted(
                source, "[carrier].kind", car.get("kind", {"handbag": 1}), carrier_keys["kind"].choices
            ),
            placement=_weighted(
                source,
                "[carrier].placement",
                car.get("placement", {"under_seat": 1}),
                [p for p in placements if p != "hold"],
            ),
            handled=_weighted(
                source,
                "[carrier].handled_in_cruise",
                car.get("handled_in_cruise", {"0": 1}),
                [str(n) for n in range(21)],
            ),
            truck_s=_range(source, "[carrier].truck_s", car.get("truck_s", [0, 0]), 0, 86400),
            walks=tuple(
                (k, _range(source, f"[carrier].{k}", car[k], 0, 86400))
                for k in ("terminal_walk_s", "gate_walk_s", "gate_rest_s")
                if k in car
            ),
            sensor=_weighted(
                source,
                "[sensor].preset",
                sen.get("preset", {"lis302dl-logged16": 1}),
                SPEC["sensor"]["preset"].choices,
            ),
            vibration_level=(
                _range(source, "[sensor].vibration_level", sen["vibration_level"], 0.05, 20)
                if "vibration_level" in sen
                else None
            ),
            baro=_preset(source, "baro", sen.get("baro"), BARO_PRESETS),
            gyro=_preset(source, "gyro", sen.get("gyro"), GYRO_PRESETS),
            text=text,
            source=source,
            model=tuple(check_model(doc.get("model"), source).items()),
        )
        for t in out.aircraft.choices:  # every type with a positive weight needs a route it can fly
            if out.aircraft.p[out.aircraft.choices.index(t)] > 0 and not out.routes_for(t):
                raise ScenarioError(
                    f"{source}: no route of [routes] suits the {t} (range "
                    f"{PROFILES[t].range_km:,.0f} km, runways of {PROFILES[t].min_runway_m:.0f} m); "
                    "add a pair it can fly or drop it from [aircraft]"
                )
        return out

    @classmethod
    def from_toml(cls, path: str | Path) -> Family:
        p = Path(path)
        try:
            text = p.read_text(encoding="utf-8")
        except OSError as e:
            raise ScenarioError(f"cannot read family file {p}: {e.strerror}") from None
        return cls.from_toml_text(text, str(p))

    @classmethod
    def builtin(cls, name: str) -> Family:
        names = builtin_families()
        if name not in names:
            raise ScenarioError(
                f"unknown family '{name}'{did_you_mean(name, names)}; built-in families: "
                f"{', '.join(names)} (or give the path of a family .toml file)"
            )
        text = (
            resources.files("flightmode.scenarios.families")
            .joinpath(f"{name}.toml")
            .read_text(encoding="utf-8")
        )
        return cls.from_toml_text(text, f"family '{name}'")

    @classmethod
    def resolve(cls, name_or_path: str | Path) -> Family:
        from flightmode.scenarios.scenario import resolve_name

        return resolve_name(cls, name_or_path, "family")

    def with_model(self, overrides: Mapping[str, float]) -> Family:
        """This family with its ``[model]`` table replaced by ``overrides`` (name -> value; ``{}``: none):
        the same members, drawn from the same streams, flown with those parameters. Its text is the
        file's with the table rewritten (a new digest: another dataset)."""
        import tomllib

        import tomli_w

        doc = tomllib.loads(self.text)
        if "model" in doc or not overrides:
            doc.pop("model", None)
            if overrides:
                doc["model"] = dict(overrides)
            text = tomli_w.dumps(doc)
        else:  # the file as written, the table added at its end (comments kept)
            table = tomli_w.dumps({"model": dict(overrides)})
            text = self.text.rstrip("\n") + "\n\n" + table
        return Family.from_toml_text(text, f"{self.source} (model overrides)")

    def digest(self) -> str:
        """SHA-256 of the family file's text: the family hash a dataset is tied to."""
        return hashlib.sha256(self.text.encode("utf-8")).hexdigest()

    # ------------------------------------------------------------------ routes
    def routes_for(self, aircraft: str) -> list[tuple[str, str]]:
        """The pairs (given, then every ordered pair of ``airports`` within ``max_km``) the type can fly."""
        return _routes_for(self, aircraft)

    # ------------------------------------------------------------------ members
    def member(self, i: int):
        """Member ``i`` (>= 0): a validated Scenario, the same in any process."""
        from flightmode.scenarios.routes import scenario_between
        from flightmode.streams import Streams

        if isinstance(i, bool) or not isinstance(i, int) or i < 0:
            raise ScenarioError(f"family member {i!r}: must be an integer >= 0")
        s = Streams(self.seed).child(f"member/{i}")
        aircraft = self.aircraft.draw(s.rng("aircraft"))
        routes = self.routes_for(aircraft)
        o, d = routes[int(s.rng("route").integers(len(routes)))]
        sc = scenario_between(o, d, aircraft, seed=s.integer_seed("seed"))
        changes: dict[str, Any] = {"name": f"{self.name}-{i:05d}"}
        r = s.rng("turbulence")
        if r.random() < self.patch_probability:
            changes["turbulence"] = [_patch(sc, r, self.patch_s, self.severity)]
        changes["landing"] = {"quality": self.landing.draw(s.rng("landing"))}
        r = s.rng("carrier")
        kind = self.kind.draw(r)
        if kind == "parcel":
            carrier = {
                "kind": "parcel",
                "placement": "hold",
                "truck_s": round(float(r.uniform(*self.truck_s)), 1),
            }
        else:
            carrier = {
                "kind": "handbag",
                "placement": self.placement.draw(r),
                "handled_in_cruise": int(self.handled.draw(r)),
            }
            carrier |= {k: round(float(r.uniform(*lim)), 1) for k, lim in self.walks}
        changes["carrier"] = carrier
        r = s.rng("sensor")
        changes["sensor"] = {"preset": self.sensor.draw(r)}
        if self.vibration_level is not None:  # drawn after the preset: adding it moves no preset
            lo, hi = self.vibration_level
            changes["sensor"]["vibration_level"] = round(
                float(math.exp(r.uniform(math.log(lo), math.log(hi)))), 4
            )
        if self.baro is not None:  # fixed, no draw: fitting one moves no other member's numbers
            changes["sensor"]["baro"] = self.baro
        if self.gyro is not None:
            changes["sensor"]["gyro"] = self.gyro
        if self.model:  # no draw: the overrides move no member's numbers
            changes["model"] = dict(self.model)
        return sc.replace(**changes)

    def members(self, n: int, start: int = 0) -> Iterator:
        for i in range(start, start + n):
            yield self.member(i)


def _preset(source: str, key: str, name: Any, presets: Mapping[str, Any]) -> str | None:
    """A fixed ``[sensor]`` preset name (``baro``, ``gyro``) checked against its presets; None if absent."""
    if name is None:
        return None
    if not isinstance(name, str) or name not in presets:
        raise ScenarioError(
            f"{source}: [sensor].{key} = {name!r}: a preset, one of {', '.join(presets)}"
            f"{did_you_mean(str(name), presets)}"
        )
    return name


def _patch(sc, r, patch_s: tuple[float, float], severity: Weighted) -> dict:
    """One turbulence patch en route: it starts after the estimated top of climb and ends before the
    estimated top of descent (climb at :data:`EN_ROUTE_CLIMB_MPS`, descent at the plan's angle and
    :data:`EN_ROUTE_SPEED_MPS`); on a hop too short for a cruise, in the middle third of the flight."""
    from flightmode.scenarios.spec import route_length_m

    p = sc.plan
    airborne = route_length_m(p) / EN_ROUTE_SPEED_MPS
    toc = (p.cruise_alt_m - p.origin.elevation_m) / EN_ROUTE_CLIMB_MPS
    tod = (
        airborne
        - (p.cruise_alt_m - p.destination.elevation_m)
        / math.tan(math.radians(p.descent_angle_deg))
        / EN_ROUTE_SPEED_MPS
    )
    duration = float(r.uniform(*patch_s))
    lo, hi = toc, tod - duration
    if hi <= lo:  # no cruise long enough: the middle third, the patch shortened to fit
        lo, hi = airborne / 3.0, airborne / 3.0
        duration = min(duration, airborne / 3.0)
    return {
        "start_s": round(float(r.uniform(lo, hi)) if hi > lo else lo, 1),
        "duration_s": round(duration, 1),
        "severity": severity.draw(r),
    }


@lru_cache(maxsize=64)
def _routes_for(fam: Family, aircraft: str) -> list[tuple[str, str]]:
    from flightmode.scenarios import airports as ap
    from flightmode.scenarios.routes import MIN_ROUTE_M
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.geodesy import gc_distance_m

    prof = get_profile(aircraft)
    cands = list(fam.pairs) + [(a, b) for a in fam.airports for b in fam.airports if a != b]
    out, seen = [], set()
    for a, b in cands:
        if (a, b) in seen:
            continue
        seen.add((a, b))
        A, B = ap.airport(a), ap.airport(b)
        dist = gc_distance_m(A.lat_deg, A.lon_deg, B.lat_deg, B.lon_deg)
        given = (a, b) in fam.pairs
        if dist < MIN_ROUTE_M or dist > prof.range_km * 1000.0 or (not given and dist > fam.max_km * 1000.0):
            continue
        if not ap.usable_ends(A, prof.min_runway_m) or not ap.usable_ends(B, prof.min_runway_m):
            continue
        out.append((a, b))
    return out


def builtin_families() -> list[str]:
    lib = resources.files("flightmode.scenarios.families")
    return sorted(p.name[:-5] for p in lib.iterdir() if p.name.endswith(".toml"))


__all__ = ["Family", "Weighted", "builtin_families"]
