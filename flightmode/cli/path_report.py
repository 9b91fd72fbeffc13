"""Path-estimator figures for the command line (``flightmode path``), printing only: the rows of
:func:`flightmode.runs.path.path_table` as a Rich table."""

from __future__ import annotations

from rich.console import Console
from rich.table import Table


def _m(x: float) -> str:
    return f"{x:,.2f}" if x < 10 else f"{x:,.0f}"


def print_rows(console: Console, rows: list[dict], title: str) -> None:
    t = Table(title=title)
    for c in ("acceleration", "method", "max error (m)", "RMS (m)", "final (m)"):
        t.add_column(c, justify="right" if "(m)" in c else "left")
    for r in rows:
        t.add_row(r["source"], r["method"], _m(r["max_m"]), _m(r["rms_m"]), _m(r["final_m"]))
    console.print(t)
