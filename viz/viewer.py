"""Opening a recording: a new native Rerun viewer, or the web viewer served on 127.0.0.1 only.

Rerun's own viewer binary (shipped in the rerun-sdk wheel, package ``rerun_cli``) binds 0.0.0.0 unless told
otherwise (rerun 0.41's default), so every command here passes ``--bind 127.0.0.1``. The native viewer gets
``--new`` so that it never streams into a viewer that is already open.

Rerun's viewer sends anonymous usage analytics unless they are disabled with
``rerun analytics disable`` (a per-user setting that flightmode does not change for you);
``flightmode view`` prints that hint.
"""

from __future__ import annotations

import socket
import sys
from pathlib import Path

from flightmode.errors import FlightmodeError, InputDataError

LOOPBACK = "127.0.0.1"


def resolve_rrd(path: Path) -> Path:
    p = Path(path)
    rrd = p / "recording.rrd" if p.is_dir() else p
    if not rrd.is_file():
        raise FlightmodeError(
            f"{path}: no recording.rrd (run `flightmode fly` without --no-rrd, or give an .rrd file)"
        )
    if rrd.suffix != ".rrd":
        raise FlightmodeError(f"{rrd}: not an .rrd file")
    check_rrd_framing(rrd)
    return rrd


# Rerun's file framing (rerun 0.41, re_log_encoding): a stream header that opens with the FourCC "RRF2",
# and a stream footer that ends the file with "RRF2" "FOOT" and a 4-byte version. A file cut short
# (a copy or a write that stopped) has no footer; the viewer would open it without a word.
RRD_MAGIC = b"RRF2"
RRD_FOOTER_MAGIC = b"RRF2FOOT"


def check_rrd_framing(rrd: Path) -> None:
    """A one-line error unless ``rrd`` opens with Rerun's header and ends with its footer (the
    framing only: a flipped byte inside a chunk is not seen, the format carries no checksum)."""
    size = rrd.stat().st_size
    with open(rrd, "rb") as f:
        head = f.read(len(RRD_MAGIC))
        f.seek(max(0, size - len(RRD_FOOTER_MAGIC) - 4))
        tail = f.read(len(RRD_FOOTER_MAGIC))
    if head != RRD_MAGIC:
        raise InputDataError(f"{rrd}: not a Rerun recording (it does not start with {RRD_MAGIC!r})")
    if tail != RRD_FOOTER_MAGIC:
        raise InputDataError(
            f"{rrd}: a damaged Rerun recording (no footer at its end: cut short?); write it again with "
            "`flightmode fly`"
        )


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((LOOPBACK, 0))
        return int(s.getsockname()[1])


def rerun_exe() -> str:
    """The viewer binary shipped in the rerun-sdk wheel, run directly (``python -m rerun_cli`` would
    add a wrapper process that outlives nothing but can be left behind when killed)."""
    import os

    import rerun_cli

    exe = os.path.join(
        os.path.dirname(rerun_cli.__file__), "rerun" + (".exe" if sys.platform.startswith("win") else "")
    )
    if sys.platform == "darwin":
        app = os.path.join(os.path.dirname(rerun_cli.__file__), "Rerun.app", "Contents", "MacOS", "Rerun")
        exe = app if os.path.exists(app) else exe
    if not os.path.exists(exe):
        raise FlightmodeError(f"the Rerun viewer binary is missing ({exe}): reinstall rerun-sdk==0.41.0")
    return exe


def native_command(rrd: Path) -> list[str]:
    return [rerun_exe(), "--new", "--bind", LOOPBACK, str(rrd)]


def web_command(rrd: Path, web_port: int, grpc_port: int) -> tuple[list[str], str]:
    cmd = [
        rerun_exe(),
        "--web-viewer",
        "--bind",
        LOOPBACK,
        "--web-viewer-port",
        str(web_port),
        "--port",
        str(grpc_port),
        str(rrd),
    ]
    url = f"http://{LOOPBACK}:{web_port}/?url=rerun%2Bhttp%3A%2F%2F{LOOPBACK}%3A{grpc_port}%2Fproxy"
    return cmd, url
