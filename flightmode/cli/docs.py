"""The command reference, generated from the app: ``python -m flightmode.cli.docs > docs/cli.md``.

Walks the Click command tree behind the Typer app and writes each command's usage, help and options
as Markdown, at a fixed terminal width (so the text does not depend on the terminal it runs in).
tests/cli/test_docs.py fails when docs/cli.md drifts from the app."""

from __future__ import annotations

import sys

WIDTH = 100  # the help text's width in the reference


def _help_text(cmd, ctx) -> str:
    formatter = ctx.make_formatter()
    cmd.format_help(ctx, formatter)
    return formatter.getvalue().rstrip()


def _context(cmd, name: str, parent=None):
    return cmd.context_class(
        cmd, info_name=name, parent=parent, terminal_width=WIDTH, max_content_width=WIDTH
    )


def _walk(cmd, ctx, path: list[str], out: list[str]) -> None:
    depth = min(len(path), 3)
    title = " ".join(["flightmode", *path[1:]])
    out.append(f"{'#' * (depth + 1)} `{title}`\n")
    out.append("```text\n" + _help_text(cmd, ctx) + "\n```\n")
    if hasattr(cmd, "list_commands"):  # a group (Typer's own Click classes)
        for name in cmd.list_commands(ctx):
            sub = cmd.get_command(ctx, name)
            if sub is None or sub.hidden:
                continue
            _walk(sub, _context(sub, name, ctx), [*path, name], out)


def reference() -> str:
    """docs/cli.md's text: every command's ``--help`` at :data:`WIDTH` columns, in the app's order."""
    import typer

    from flightmode.cli.main import app

    root = typer.main.get_command(app)
    ctx = _context(root, "flightmode")
    out = [
        "# The `flightmode` command line\n",
        "Generated from the app by `python -m flightmode.cli.docs > docs/cli.md`; "
        "`tests/cli/test_docs.py` fails when it drifts. Every command prints `--help` the same way.\n",
        "Conventions: `--out DIR` is always a folder (a command that writes one file writes it there under "
        "a fixed name); `--json` prints the numbers of the command's table as one JSON document on stdout; "
        "`--workers` is 1 (in this process) unless a command says otherwise; `--sensor` takes one "
        "accelerometer preset or a comma list; errors print one line and exit with status 2.\n",
    ]
    _walk(root, ctx, ["flightmode"], out)
    return "\n".join(out).rstrip() + "\n"


if __name__ == "__main__":  # pragma: no cover
    sys.stdout.write(reference())
