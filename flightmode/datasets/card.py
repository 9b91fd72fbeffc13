"""The dataset card (``DIR/README.md``) of a dataset made by :mod:`flightmode.datasets.make`: the
family, the schema with units, the label definitions, the versions, the counts, how to load it in
four tools (each example is run by the test suite), and the licence."""

from __future__ import annotations

from pathlib import Path

LABELS = {
    "in_flight_window": "True from pushback to engines off: the tracker must not transmit (the detector's target)",
    "airborne": "True from liftoff to touchdown",
    "sensor_static": "True while the sensor itself is at rest (on a table, in a parked aircraft with engines off)",
    "phase": "the flight phase (gate ... parked) or, off the aircraft, the bag's own (terminal_walk, truck, ...)",
    "bag_state": "carried, resting, stowed, in_hold or handled",
    "turbulence_severity": "the turbulence category the aircraft is in: none, light, moderate, severe (ICAO Annex 3 EDR bands)",
    "clipped": "True where an axis hit the sensor's range",
    "pressure_pa": "the true pressure at the bag, Pa (the cabin's, the hold's, or ambient off board)",
    "baro_pa": "the barometer's latest reading at this row, Pa (its own rate: see baro_new)",
    "baro_new": "True on the rows where a new barometer reading arrived (its stream: baro_pa where baro_new)",
}

LOADERS = {
    "pyarrow": """import pyarrow.dataset as pads
import flightmode.datasets
ds = flightmode.datasets.open("{dir}")            # a pyarrow.dataset.Dataset (hive: aircraft column)
table = ds.to_table(filter=pads.field("in_flight_window"))""",
    "polars": """import polars as pl
df = pl.scan_parquet("{dir}/samples/**/*.parquet", hive_partitioning=True).collect()""",
    "duckdb": """import duckdb
rows = duckdb.sql("SELECT aircraft, count(*) FROM read_parquet('{dir}/samples/*/*.parquet', hive_partitioning=true) GROUP BY aircraft").fetchall()""",
    "datasets": """from datasets import load_dataset
hf = load_dataset("parquet", data_files="{dir}/samples/*/*.parquet", split="train")""",
}


def _schema_lines(out: Path, rows: dict) -> list[str]:
    import pyarrow.parquet as pq

    from flightmode.units import G0_MPS2

    ok = [r for r in rows.values() if r["status"] == "ok"]
    if not ok:
        return ["(no flight succeeded: no samples to describe)"]
    lines = ["| column | type | meaning |", "|---|---|---|"]
    schema = pq.read_schema(out / ok[0]["samples_file"])
    for f in schema:
        unit = f.name.rsplit("_", 1)[-1] if "_" in f.name else ""
        meaning = LABELS.get(
            f.name,
            {
                "g": f"acceleration along the sensor axis, g ({G0_MPS2:g} m/s^2)",
                "s": "time since the track's start, s",
            }.get(unit, "sensor output / identifier"),
        )
        if f.name.startswith("raw_"):
            meaning = "the sensor's raw output, counts (LSB) along that axis"
        if f.name == "flight_id":
            meaning = "the flight (a row of flights.parquet)"
        lines.append(f"| `{f.name}` | {f.type} | {meaning} |")
    lines.append("| `aircraft` | string (folder) | the aircraft type: the hive partition `aircraft=<type>` |")
    return lines


def write_card(out: Path, fam, rows: dict, options) -> Path:
    from flightmode.atomic import write_text as atomic_text
    from flightmode.detector.recommended_point import POINT
    from flightmode.runs.run_io import package_versions

    ok = [r for r in rows.values() if r["status"] == "ok"]
    failed = [r for r in rows.values() if r["status"] != "ok"]
    hours = sum(r.get("gate_to_gate_s") or 0.0 for r in ok) / 3600.0
    by_type: dict[str, int] = {}
    for r in ok:
        by_type[r["aircraft"]] = by_type.get(r["aircraft"], 0) + 1
    lines = [
        f"# {fam.name}: a flightmode dataset",
        "",
        fam.description,
        "",
        f"Simulated, labelled accelerometer streams of a bag or parcel travelling gate to gate in an airliner "
        f"(JSBSim flights, flightmode's sensor models), made by `flightmode dataset`. Family SHA-256 "
        f"`{fam.digest()}` (the file is `family.toml`); member *i* is regenerated alone by "
        f"`Family.from_toml('family.toml').member(i)`.",
        "",
        "## Counts",
        "",
        f"- flights: {len(ok)} ok, {len(failed)} failed (see `flights.parquet`, columns `status` and `error`)",
        f"- flight-hours (gate to gate): {hours:.2f}",
        f"- by type: {', '.join(f'{k} {v}' for k, v in sorted(by_type.items()))}",
        f"- samples: {sum(r['samples'] for r in ok):,} ({sum(r['samples_in_flight_window'] for r in ok):,} in the "
        "in-flight window)",
        f"- truth: {options.truth}",
        "",
        "## Files",
        "",
        "- `flights.parquet`: the manifest, one row per flight: id, seed, the scenario (`scenario_toml`, "
        "`scenario_sha256`), status and error, seconds per phase (`phase_<name>_s`), sample counts per label, "
        "where and how the bag lay in flight (`inflight_placement`, `cabin_row`, `packing`, "
        "`stowed_yaw_deg`, `stowed_tilt_deg`, `sensor_x_from_fuselage_deg`: 0 with the sensor's x axis "
        "fore-aft; `stowage_json`: every stowed stretch of the in-flight window and the mounts), "
        f"the recommended detector's summary (seed 000's {POINT.short_text}), file names and SHA-256.",
        "- `samples/aircraft=<type>/part-<flight_id>.parquet`: the accelerometer stream and its labels.",
        "- `truth/aircraft=<type>/part-<flight_id>.parquet`: the aircraft's state (positions, velocities, attitude, "
        "specific force ...; SI units in the column names), every FDM step (`full`) or every 12th (`10hz`: "
        "instantaneous values, not averages).",
        "",
        "## Samples schema",
        "",
        *_schema_lines(out, rows),
        "",
        "## Labels",
        "",
        *[f"- `{k}`: {v}" for k, v in LABELS.items()],
        "",
        "## Loading",
        "",
    ]
    for name, code in LOADERS.items():
        lines += [f"{name}:", "", "```python", code.format(dir=out.resolve()), "```", ""]
    lines += [
        "## Versions",
        "",
        *[f"- {k} {v}" for k, v in sorted(package_versions().items())],
        "",
        "## Licence",
        "",
        "The data are simulated and free to use under CC-BY-4.0. Airport and runway data: OurAirports "
        "(public domain).",
        "",
    ]
    path = out / "README.md"
    atomic_text("\n".join(lines), path)
    return path
