"""The tornado chart of a certification's model uncertainty (``flightmode certify --uncertainty``):
per uncertain parameter, a horizontal bar from the false-static bound with the parameter at the low
end of its range to the bound at the high end, around the nominal model's bound (a vertical line),
with the target (a dashed line) and the worst plausible corner. Drawn from plain data
(:class:`TornadoData`, made by :func:`flightmode.studies.uncertainty.tornado_data`); the PNG is
written atomically (:func:`flightmode.atomic.write_with`) and the report section is HTML text.
"""

from __future__ import annotations

import base64
import html
import math
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True, slots=True)
class TornadoData:
    """What the tornado chart and its table show."""

    point: str  # the nominal recommended point's name (the bounds are its)
    nominal_bound: float  # its false-static bound per flight-hour at the nominal model
    target: float  # the target rate per flight-hour
    confidence: float
    # per parameter: (name, low, high, unit, bound at low, bound at high)
    bars: tuple[tuple[str, float, float, str, float, float], ...]
    corner_bound: float | None  # the worst plausible corner's bound (None: no corner flown)
    sentence: str
    rows: tuple[dict, ...] = ()  # the variants' table (flightmode.studies.uncertainty._table_row)


def bar_order(data: TornadoData) -> list[int]:
    """The bars' order, widest swing first (the top of the tornado)."""
    return sorted(range(len(data.bars)), key=lambda i: -abs(data.bars[i][5] - data.bars[i][4]))


def fig_tornado(data: TornadoData, path: Path) -> None:
    """The chart (module docstring) as a PNG at ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flightmode.atomic import write_with

    order = bar_order(data)
    n = len(order)
    fig, ax = plt.subplots(figsize=(9.0, 1.2 + 0.55 * max(n, 1)))
    try:
        x0 = data.nominal_bound
        for row, i in enumerate(reversed(order)):
            name, lo, hi, unit, b_lo, b_hi = data.bars[i]
            for b, colour, end in ((b_lo, "tab:blue", lo), (b_hi, "tab:orange", hi)):
                ax.barh(row, b - x0, left=x0, color=colour, alpha=0.8, height=0.6)
                ax.annotate(
                    f"{end:g}",
                    (b, row),
                    xytext=(4 if b >= x0 else -4, 0),
                    textcoords="offset points",
                    ha="left" if b >= x0 else "right",
                    va="center",
                    fontsize=8,
                )
        ax.set_yticks(range(n), [data.bars[i][0] for i in reversed(order)], fontsize=8)
        ax.axvline(x0, color="k", lw=1, label=f"nominal {x0:.3g} /h")
        ax.axvline(data.target, color="tab:red", ls="--", lw=1, label=f"target {data.target:g} /h")
        if data.corner_bound is not None:
            ax.axvline(
                data.corner_bound,
                color="tab:purple",
                ls=":",
                lw=1.5,
                label=f"worst corner {data.corner_bound:.3g} /h",
            )
        ax.barh([], [], color="tab:blue", label="parameter at its low end")
        ax.barh([], [], color="tab:orange", label="parameter at its high end")
        vals = [x0, data.target] + [b for bar in data.bars for b in bar[4:]]
        if data.corner_bound is not None:
            vals.append(data.corner_bound)
        finite = [v for v in vals if math.isfinite(v)]
        if finite:
            lo, hi = min(finite), max(finite)
            pad = 0.08 * (hi - lo) if hi > lo else 0.1 * max(abs(hi), 1e-12)
            ax.set_xlim(lo - pad, hi + pad)
        ax.set_xlabel(f"false statics per in-window flight-hour, {data.confidence:.0%} bound")
        ax.set_title(f"the bound of {data.point} as each parameter moves", fontsize=9)
        ax.legend(fontsize=7, loc="lower right")
        fig.tight_layout()
        write_with(Path(path), lambda tmp: fig.savefig(tmp, dpi=110, format="png"), mkdir=True)
    finally:
        plt.close(fig)


def tornado_html(data: TornadoData, png: bytes) -> list[str]:
    """The report's section: the sentence, the chart and the variants' table."""
    e = html.escape
    parts = [
        "<h2>The verdict with its uncertainty</h2>",
        f"<div class='verdict'>{e(data.sentence)}</div>",
        f"<p>The bound of the recommended point ({e(data.point)}) with each uncertain model parameter "
        "at each end of its declared range (the same members and seeds), and with every parameter at the "
        "end that raised it (the worst plausible corner). `flightmode scenarios --model` lists the parameters and "
        "their sources.</p>",
        f"<img alt='tornado' src='data:image/png;base64,{base64.b64encode(png).decode()}'>",
    ]
    if data.rows:
        cols = (
            ("variant", "variant", "{}"),
            ("flights", "flights", "{:d}"),
            ("in_window_h", "in-window h", "{:,.2f}"),
            ("false_statics", "false statics", "{:d}"),
            ("bound_per_h", "bound /h (the point)", "{:.3g}"),
            ("response_p95_s", "response p95 s", "{:.1f}"),
            ("recommended", "its own recommended point", "{}"),
            ("recommended_bound_per_h", "its bound /h", "{:.3g}"),
            ("recommended_response_p95_s", "its response p95 s", "{:.1f}"),
        )
        head = "".join(f"<th>{e(t)}</th>" for _, t, _ in cols)
        body = "".join(
            "<tr>" + "".join(f"<td>{e(f.format(r[k]))}</td>" for k, _, f in cols) + "</tr>" for r in data.rows
        )
        parts.append(f"<table><tr>{head}</tr>{body}</table>")
    return parts


__all__ = ["TornadoData", "bar_order", "fig_tornado", "tornado_html"]
