"""The ``flightmode`` command line (Typer + Rich): one app, one error handler, the commands in the
order a user works. A thin shell over the library: each command parses its options, makes one
library call and prints; anything it does, ``import flightmode`` can do.

    Make flights            scenarios, family, fly, dataset
    Look at them            view, path, cabin, validate
    Detect and stress-test  detect, sweep, certify, activity synth
    Sensors and tags        sense, eobs detect / calibrate / tradeoff

Errors that flightmode raises on purpose (bad scenario, unknown aircraft, failed flight, a file that
is not a run) print one line on stderr and exit with status 2, with no traceback
(:class:`flightmode.cli.common.Group`). Only Typer and Rich are imported to start; each command
imports what it needs. The reference of every command: docs/cli.md (``python -m flightmode.cli.docs``).
"""

from __future__ import annotations

import sys

import typer

from flightmode.cli import activity, certify, common, detect, eobs, flights, fly, look, seeds, study, validate
from flightmode.cli.fly import DEFAULT_SCENARIO

__all__ = ["DEFAULT_SCENARIO", "app"]

HELP = "Physics-simulated accelerometer data for a package in an airliner, and its flight-mode detector."

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    rich_markup_mode=common.HELP_MARKUP,
    help=HELP,
    cls=common.Group,
)


@app.callback()
def _start() -> None:
    """Physics-simulated accelerometer data for a package in an airliner, and its flight-mode detector."""
    common.Consoles.renew()


MAKE, LOOK, DETECT, SENSORS = common.PANELS

# (name, function, panel, example); the order within a panel is the order a user meets them
COMMANDS = (
    ("scenarios", fly.scenarios_cmd, MAKE, "flightmode scenarios"),
    ("family", flights.family_cmd, MAKE, "flightmode family european-trio --show 3"),
    ("fly", fly.fly_cmd, MAKE, "flightmode fly pattern --out runs/"),
    ("dataset", flights.dataset_cmd, MAKE, "flightmode dataset european-trio --n 20 --out flights/"),
    ("view", look.view_cmd, LOOK, "flightmode view runs/pattern-s1/"),
    ("path", look.path_cmd, LOOK, "flightmode path runs/pattern-s1/ --sensor run,ideal"),
    ("cabin", look.cabin_cmd, LOOK, "flightmode cabin runs/pattern-s1/ --out figures/"),
    ("validate", validate.validate_cmd, LOOK, "flightmode validate runs/pattern-s1/"),
    ("detect", detect.detect_cmd, DETECT, "flightmode detect flights/ --flight 3 --method emv --weight 5"),
    ("sweep", study.sweep_cmd, DETECT, "flightmode sweep flights/ --k 3:6:0.5 --workers 2"),
    ("certify", certify.certify_cmd, DETECT, "flightmode certify flights/ --target-fa-per-h 1e-4"),
    ("seeds", seeds.seeds_cmd, DETECT, "flightmode seeds 000"),
    ("sense", fly.sense_cmd, SENSORS, "flightmode sense runs/pattern-s1/ --sensor lis302dl,lis302dl-8g"),
)
for _name, _fn, _panel, _example in COMMANDS:
    app.command(_name, rich_help_panel=_panel, epilog=f"Example: {_example}")(_fn)
app.add_typer(activity.activity_app, name="activity", rich_help_panel=DETECT)
app.add_typer(eobs.eobs_app, name="eobs", rich_help_panel=SENSORS)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(app())
