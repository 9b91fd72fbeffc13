"""``flightmode scenarios --model``: the registry of uncertain model parameters (what a scenario's
``[model]`` table may override, and what ``flightmode certify --uncertainty`` varies)."""

from __future__ import annotations

from rich.table import Table

from flightmode.cli.common import console, emit_json


def print_registry(as_json: bool) -> None:
    """The uncertain model parameters: name, value, range, unit, what each shapes and its source."""
    from flightmode.scenarios.model import registry_rows

    rows = registry_rows()
    if as_json:
        emit_json(rows)
        return
    t = Table(title="uncertain model parameters (a scenario's [model] table overrides them)")
    t.add_column("parameter", no_wrap=True)
    for col in ("value", "range", "unit", "what it shapes", "source"):
        t.add_column(col)
    for r in rows:
        t.add_row(
            r["name"], f"{r['value']:g}", f"{r['low']:g}-{r['high']:g}", r["unit"], r["shapes"], r["source"]
        )
    console().print(t)
