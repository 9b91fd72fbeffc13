"""What every command module shares: the consoles, the one error handler, the command group that
prints the commands in panels, and the small parsers and JSON output of the options."""

from __future__ import annotations

import json
import math
import sys
from typing import Any

import typer
from rich.console import Console
from rich.text import Text
from typer.core import TyperGroup

from flightmode.errors import FlightmodeError

# Help is Click's plain text (rich_markup_mode=None): Typer's Rich help imports rich.markdown and
# markdown_it (0.15-0.2 s of a 0.5 s `flightmode --help` budget); the commands' own output uses Rich.
HELP_MARKUP = None

# the panels of `flightmode --help`, in the order a user works
PANELS = ("Make flights", "Look at them", "Detect and stress-test", "Sensors and tags")


class Consoles:
    """Fresh consoles for each invocation: they read the terminal's width (COLUMNS) when made."""

    out = Console()
    err = Console(stderr=True)

    @classmethod
    def renew(cls) -> None:
        cls.out = Console()
        cls.err = Console(stderr=True)


def console() -> Console:
    return Consoles.out


def err_console() -> Console:
    return Consoles.err


def die(e: Exception) -> None:
    """The one error handler: a FlightmodeError is one line on stderr and exit status 2."""
    # user text (scenario paths, [section].key names) must not be read as Rich markup
    Consoles.err.print(Text.assemble(("error:", "bold red"), " ", str(e)), highlight=False, soft_wrap=True)
    raise typer.Exit(code=2)


class Group(TyperGroup):
    """Typer's group with the one error handler around every command, and the commands listed in the
    panels of :data:`PANELS` (Typer's own panels need its Rich help, which --help does not load)."""

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except FlightmodeError as e:
            die(e)

    def format_commands(self, ctx: Any, formatter: Any) -> None:
        rows: dict[str, list[tuple[str, str]]] = {}
        for name in self.list_commands(ctx):
            cmd = self.get_command(ctx, name)
            if cmd is None or cmd.hidden:
                continue
            panel = getattr(cmd, "rich_help_panel", None) or "Other"
            rows.setdefault(panel, []).append((name, first_line(cmd.help or "")))
        if not rows:
            return
        width = max(len(name) for panel in rows.values() for name, _ in panel)
        with formatter.section("Commands"):
            for panel in [p for p in PANELS if p in rows] + [p for p in rows if p not in PANELS]:
                formatter.write_text(f"{panel}:")
                with formatter.indentation():
                    formatter.write_dl([(name.ljust(width), text) for name, text in rows[panel]])


def first_line(text: str) -> str:
    """A command's one-line description: the first sentence of its help."""
    para = " ".join(text.strip().split("\n\n")[0].split())
    return para.split(". ")[0].rstrip(".")


def sub_app(help: str) -> typer.Typer:
    """A command group under ``flightmode`` (``activity``, ``eobs``)."""
    return typer.Typer(help=help, no_args_is_help=True, rich_markup_mode=HELP_MARKUP, cls=Group)


def comma_list(text: str | None, option: str) -> tuple[str, ...] | None:
    """``a,b,c`` as a tuple of names (None stays None); an empty list is a BadParameter."""
    if text is None:
        return None
    names = tuple(x.strip() for x in text.split(",") if x.strip())
    if not names:
        raise typer.BadParameter(f"{option}: give one name or a comma list", param_hint=option)
    return names


def finite(o):
    """JSON has no NaN or infinity: those become null, recursively."""
    if isinstance(o, float) and not math.isfinite(o):
        return None
    if isinstance(o, dict):
        return {str(k): finite(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [finite(v) for v in o]
    if hasattr(o, "tolist"):  # NumPy scalars and arrays
        return finite(o.tolist())
    return o


def emit_json(obj) -> None:
    """One JSON document on stdout (what ``--json`` prints)."""
    sys.stdout.write(json.dumps(finite(obj), indent=1, allow_nan=False) + "\n")


JSON_HELP = "Print the results as one JSON document on stdout (the numbers of the table) instead."
WORKERS_HELP = "Dask worker processes (1: in this process, no cluster)."


class CountingBar:
    """A progress bar counting ``label`` (runs, flights) up to a total known now or later: the one
    bar of the commands that map over flights or runs. ``quiet`` hides it (``--json``);
    ``stderr``/``transient``: drawn on standard error and erased when done."""

    def __init__(
        self,
        label: str,
        total: int | None = None,
        *,
        quiet: bool = False,
        stderr: bool = False,
        transient: bool = False,
    ):
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(
            TextColumn(label),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            console=err_console() if stderr else console(),
            disable=quiet,
            transient=transient,
        )
        self.task = self.bar.add_task(label, total=total)

    def __enter__(self) -> CountingBar:
        self.bar.__enter__()
        return self

    def __exit__(self, *exc) -> None:
        self.bar.__exit__(*exc)

    def total(self, n: int) -> None:
        self.bar.update(self.task, total=n)

    def advance(self, *_: object) -> None:
        """One more done (any arguments, e.g. the index a callback passes, are ignored)."""
        self.bar.advance(self.task)
