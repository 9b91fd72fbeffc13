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
    # seed 000's recommended point: (nominal bound, per bar (bound at low, at high), corner bound);
    # None when the grid lacks it
    seed000: tuple[float, tuple[tuple[float | None, float | None], ...], float | None] | None = None


def bar_order(data: TornadoData) -> list[int]:
    """The bars' order, widest swing first (the top of the tornado)."""
    return sorted(range(len(data.bars)), key=lambda i: -abs(data.bars[i][5] - data.bars[i][4]))


def _panel(ax, data: TornadoData, order: list[int], x0: float, ends: list, corner: float | None, title: str):
    """One tornado: the bars of ``ends`` [(bound at low, at high)] around ``x0``; the longer of a
    parameter's two bars is drawn first (the shorter stays visible on it), the end with the lower
    bound labelled on the left, the other on the right."""
    from matplotlib.patches import Patch

    colours = ("tab:blue", "tab:orange")  # the low end, the high end
    n = len(order)
    for row, i in enumerate(reversed(order)):
        _name, lo, hi, _unit, _b_lo, _b_hi = data.bars[i]
        pairs = [(b, colours[k], end) for k, (b, end) in enumerate(((ends[i][0], lo), (ends[i][1], hi)))]
        pairs = [q for q in pairs if q[0] is not None and math.isfinite(q[0])]
        for b, colour, _ in sorted(pairs, key=lambda q: -abs(q[0] - x0)):
            ax.barh(row, b - x0, left=x0, color=colour, alpha=0.85, height=0.6)
        for rank, (b, _, end) in enumerate(sorted(pairs, key=lambda q: q[0])):
            right = rank == len(pairs) - 1 and (len(pairs) == 1 or b >= x0)
            ax.annotate(
                f"{end:g}",
                (b, row),
                xytext=(4 if right else -4, 0),
                textcoords="offset points",
                ha="left" if right else "right",
                va="center",
                fontsize=8,
            )
    ax.set_yticks(range(n), [data.bars[i][0] for i in reversed(order)], fontsize=8)
    handles = [
        ax.axvline(x0, color="k", lw=1, label=f"nominal {x0:.3g} /h"),
        ax.axvline(data.target, color="tab:red", ls="--", lw=1, label=f"target {data.target:g} /h"),
    ]
    if corner is not None:
        handles.append(
            ax.axvline(corner, color="tab:purple", ls=":", lw=1.5, label=f"worst corner {corner:.3g} /h")
        )
    handles += [
        Patch(color=colours[0], label="parameter at its low end"),
        Patch(color=colours[1], label="at its high end"),
    ]
    vals = [x0, data.target] + [b for e in ends for b in e if b is not None] + ([corner] if corner else [])
    finite = [v for v in vals if math.isfinite(v)]
    if finite:
        lo_x, hi_x = min(finite), max(finite)
        pad = 0.12 * (hi_x - lo_x) if hi_x > lo_x else 0.1 * max(abs(hi_x), 1e-12)
        ax.set_xlim(lo_x - pad, hi_x + pad)
    ax.set_xlabel(f"false statics per in-window flight-hour, {data.confidence:.0%} bound", fontsize=8)
    ax.set_title(title, fontsize=9)
    ax.legend(handles=handles, fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))


def fig_tornado(data: TornadoData, path: Path) -> None:
    """The chart (module docstring) as a PNG at ``path``: the recommended point's tornado, and seed
    000's recommended point's beside it when the grid holds it."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flightmode.atomic import write_with

    order = bar_order(data)
    panels = 1 if data.seed000 is None else 2
    fig, axes = plt.subplots(
        panels, 1, figsize=(10.0, (1.5 + 0.5 * max(len(order), 1)) * panels), squeeze=False
    )
    try:
        ends = [(b[4], b[5]) for b in data.bars]
        _panel(
            axes[0][0], data, order, data.nominal_bound, ends, data.corner_bound, f"recommended: {data.point}"
        )
        if data.seed000 is not None:
            x0, paper_ends, corner = data.seed000
            _panel(axes[1][0], data, order, x0, list(paper_ends), corner, "seed 000's recommended point")
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
        "end that raised it (the worst plausible corner); beside it, seed 000's recommended point's. "
        "`flightmode scenarios --model` lists the parameters and their sources.</p>",
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
            ("seed000_bound_per_h", "seed 000's point: bound /h", "{:.3g}"),
        )
        head = "".join(f"<th>{e(t)}</th>" for _, t, _ in cols)
        body = "".join(
            "<tr>"
            + "".join(f"<td>{e('-' if r.get(k) is None else f.format(r[k]))}</td>" for k, _, f in cols)
            + "</tr>"
            for r in data.rows
        )
        parts.append(f"<table><tr>{head}</tr>{body}</table>")
    return parts


__all__ = ["TornadoData", "bar_order", "fig_tornado", "tornado_html"]
