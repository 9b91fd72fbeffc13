"""Firmware over a pipe (``--detector-cmd "PROGRAM ARGS"``): any program that reads samples on its
standard input and writes decisions on its standard output is a detector
(:mod:`flightmode.detector.interface`), so a tracker's firmware, built for the host, runs in
``detect``, ``sweep`` and ``certify`` as it will run on the part.

The protocol (docs/detector_pipe.md says the same with an example):

1. The program is started once per detector (the command split as a shell would, by
   :func:`shlex.split`, and run without a shell); its standard error is ours (its messages appear
   as they are written).
2. It first reads ONE header line, JSON, ended by ``\\n``::

       {"fs_hz": 100.0, "channels": ["acc_x_g", "acc_y_g", "acc_z_g"],
        "units": {"t_s": "s", "acc_x_g": "g", "acc_y_g": "g", "acc_z_g": "g"},
        "framing": "csv", "params": {"k": 4.0}}

   ``fs_hz`` the sample rate; ``channels`` the columns after the time, in order, units in the name
   and in ``units`` (``s``, ``g``, ``deg/s``, ``Pa``); ``framing`` as below; ``params`` the detector's
   parameters (``--param key=value``, a grid point), JSON values.
3. Then the samples, in one of two framings:

   - ``csv`` (the default): one line per sample, ``t_s,<channels...>\\n``, each number written as
     Python's ``repr`` of the float64 (the shortest text that reads back to the same bits: C's
     ``strtod`` restores it exactly); the program answers each sample with one line ``0\\n`` or
     ``1\\n`` (``\\r\\n`` and spaces around the digit are accepted);
   - ``f64``: each sample is ``1 + len(channels)`` IEEE-754 float64 values, little-endian, ``t_s``
     first, then the channels in order (8 (1 + n) bytes, no separator); the program answers each
     sample with ONE byte, ``0x00`` or ``0x01`` (the values, not the characters ``0``/``1``).

   ``1``: at rest, the radio may transmit; ``0``: not. One answer per sample, in order, no other
   output on stdout.
4. The samples come in chunks (the harness's pushes); after a chunk the harness waits for all of
   its answers before it sends more, so a program must **flush its output before it blocks reading
   input** (or after every answer). The end of the stream is the end of the input (EOF): the
   program then exits with status 0.

Failures are one-line :class:`~flightmode.errors.DetectorError`\\ s naming the sample: the program
not found (before sample 0), exited early (its exit status and the sample reached), garbage (the
offending answer quoted, truncated), too many answers, too few (it exited, or said nothing for
``timeout_s`` seconds while answers were due). ``close()`` closes the program's input, waits
``timeout_s`` for it to exit and kills it otherwise: no process is left behind.

Writing a chunk and reading its answers overlap (a writer thread for chunks larger than a pipe's
buffer), so a program that answers while it reads never deadlocks against us.

This module imports NumPy inside its functions.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import shlex
import subprocess
import threading
import time
import weakref
from collections.abc import Sequence
from typing import Any

from flightmode.detector.interface import ACC_CHANNELS, Loaded, check_channels
from flightmode.errors import DetectorError

FRAMINGS = ("csv", "f64")
# seconds without a byte from the program while answers are due, and for its exit at close
TIMEOUT_S = 30.0
# a chunk of at most this many samples fits the pipe's buffer (4 KiB by POSIX, 64 KiB on Linux) with
# up to 7 channels in either framing (csv: at most 25 characters a number): written directly
DIRECT_WRITE_SAMPLES = 16
# the writer encodes and sends this many samples at a time (the program starts on the first block)
ENCODE_BLOCK = 2048
# an answer quoted in an error is cut here
QUOTE_CHARS = 40


def units_of(channels: Sequence[str]) -> dict:
    """The header's ``units``: ``t_s`` in s, then each channel's unit from its name's suffix."""
    suffix = {"_g": "g", "_dps": "deg/s", "_pa": "Pa"}
    out = {"t_s": "s"}
    for c in channels:
        out[c] = next(u for s, u in suffix.items() if c.endswith(s))
    return out


def _jsonable(v: Any) -> Any:
    if hasattr(v, "tolist"):  # NumPy scalars and arrays
        return v.tolist()
    raise TypeError(f"{type(v).__name__} is not a JSON value")


def header(fs_hz: float, channels: Sequence[str], framing: str, params: dict) -> bytes:
    """The header line (module docstring, step 2), newline included."""
    try:
        text = json.dumps(
            {
                "fs_hz": float(fs_hz),
                "channels": list(channels),
                "units": units_of(channels),
                "framing": framing,
                "params": params,
            },
            default=_jsonable,
            allow_nan=False,
        )
    except (TypeError, ValueError) as e:
        raise DetectorError(f"--detector-cmd: the parameters {params} are not JSON values ({e})") from None
    return text.encode() + b"\n"


def encode(t_s: Any, x: Any, framing: str) -> bytes:
    """A chunk's samples in the framing (module docstring, step 3)."""
    return b"".join(encode_blocks(t_s, x, framing))


def encode_blocks(t_s: Any, x: Any, framing: str, block: int = ENCODE_BLOCK):
    """:func:`encode` ``block`` samples at a time (the writer sends each as it is made)."""
    import numpy as np

    rows = np.column_stack([np.asarray(t_s, float), np.asarray(x, float)])
    line = ",".join(["%r"] * rows.shape[1]) + "\n"  # %r of a float is its repr: exact
    for i in range(0, rows.shape[0], block):
        r = rows[i : i + block]
        if framing == "f64":
            yield r.astype("<f8").tobytes()
        else:
            yield ((line * r.shape[0]) % tuple(r.ravel().tolist())).encode()


def load_cmd(
    cmd: str, framing: str = "csv", channels: Sequence[str] | None = None, timeout_s: float = TIMEOUT_S
) -> Loaded:
    """The program ``cmd`` as a detector: a :class:`~flightmode.detector.interface.Loaded` whose
    factory ``make(fs_hz, channels, **params)`` starts it (module docstring). ``channels``: what it
    reads (default the three accelerometer axes)."""
    if framing not in FRAMINGS:
        raise DetectorError(f"--detector-cmd framing {framing!r}: use {' or '.join(FRAMINGS)}")
    try:
        argv = shlex.split(str(cmd))
    except ValueError as e:
        raise DetectorError(f"--detector-cmd {cmd!r}: cannot split it as a shell would ({e})") from None
    if not argv:
        raise DetectorError("--detector-cmd: empty command; give the program and its arguments")
    ch = tuple(channels) if channels is not None else ACC_CHANNELS
    check_channels(ch, f"--detector-cmd {cmd!r}")
    if not timeout_s > 0:
        raise DetectorError(f"--detector-cmd: timeout {timeout_s} s must be > 0")

    def make(fs_hz: float, channels: Sequence[str], **params: Any) -> PipeDetector:
        return PipeDetector(str(cmd), argv, fs_hz, channels, framing, params, timeout_s)

    make.channels = ch  # type: ignore[attr-defined]
    return Loaded(str(cmd), make, f"program {cmd!r} ({framing})", ch, {})


def _reap(proc: subprocess.Popen) -> None:
    """Kill a program still running and collect its exit status (no zombie)."""
    if proc.poll() is None:
        with contextlib.suppress(OSError):
            proc.kill()
    with contextlib.suppress(Exception):
        proc.wait(timeout=5)
    for f in (proc.stdin, proc.stdout):
        with contextlib.suppress(Exception):
            if f is not None:
                f.close()


class PipeDetector:
    """A running program speaking the protocol (module docstring)."""

    def __init__(
        self,
        cmd: str,
        argv: list[str],
        fs_hz: float,
        channels: Sequence[str],
        framing: str,
        params: dict,
        timeout_s: float = TIMEOUT_S,
    ):
        check_channels(channels, f"--detector-cmd {cmd!r}")
        self.cmd, self.framing, self.timeout_s = cmd, framing, float(timeout_s)
        self.n_ch = len(channels)
        head = header(fs_hz, channels, framing, params)
        try:
            self.proc = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE, bufsize=0)
        except FileNotFoundError:
            raise DetectorError(
                f"--detector-cmd {cmd!r}: program {argv[0]!r} not found (before sample 0); "
                "give its path or put it on PATH"
            ) from None
        except PermissionError:
            raise DetectorError(
                f"--detector-cmd {cmd!r}: {argv[0]!r} is not executable (before sample 0); chmod +x it"
            ) from None
        except OSError as e:
            raise DetectorError(f"--detector-cmd {cmd!r}: cannot start it (before sample 0): {e}") from None
        self._finalizer = weakref.finalize(self, _reap, self.proc)
        self.sent = 0  # samples written so far (the global index of the next one)
        self.answered = 0
        self.failed = False
        self._pending = bytearray()  # bytes read beyond the answers taken (only in error)
        self._write(head)

    # ------------------------------------------------------------------ writing
    def _write(self, data: bytes) -> bool:
        """Write all of ``data`` to the program's input; False at a closed pipe, left to the reader to
        report (the program exited: its status says why)."""
        assert self.proc.stdin is not None
        view = memoryview(data)
        try:
            fd = self.proc.stdin.fileno()
            while view:
                view = view[os.write(fd, view) :]
        except (OSError, ValueError):  # BrokenPipeError: it exited or closed its input; closed by us
            return False
        return True

    def _write_all(self, blocks) -> None:
        """The writer thread: each block as it is encoded; stops at a closed pipe."""
        for b in blocks:
            if self.failed or not self._write(b):
                return

    # ------------------------------------------------------------------ the detector
    def push(self, t_s: Any, x: Any):
        import numpy as np

        if self.failed:
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: the program failed earlier; make a new detector"
            )
        t = np.asarray(t_s, float)
        a = np.asarray(x, float)
        n = t.shape[0]
        if a.shape != (n, self.n_ch):
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: chunk from sample {self.sent} has x of shape {a.shape}, "
                f"expected ({n}, {self.n_ch})"
            )
        if n == 0:
            return np.zeros(0, bool)
        start = self.sent
        self.sent += n
        writer = None
        if n <= DIRECT_WRITE_SAMPLES:
            self._write(encode(t, a, self.framing))  # it has read all before: this fits the pipe
        else:
            blocks = encode_blocks(t, a, self.framing)
            writer = threading.Thread(target=self._write_all, args=(blocks,), daemon=True)
            writer.start()
        try:
            raw = self._read_answers(n, start)
            out = self._parse(raw, n, start)
        except DetectorError:
            self._fail()
            raise
        finally:
            if writer is not None:
                writer.join(timeout=self.timeout_s)
        self.answered += n
        return out

    def _read_answers(self, n: int, start: int) -> bytes:
        """Read until the chunk's ``n`` answers are in; an error for EOF (exit), silence or extras."""
        assert self.proc.stdout is not None
        fd = self.proc.stdout.fileno()
        buf = bytearray()
        got = 0  # complete answers in buf
        while got < n:
            ready, _, _ = select.select([fd], [], [], self.timeout_s)
            if not ready:
                raise DetectorError(
                    f"--detector-cmd {self.cmd!r}: gave {got} answers for the {n} samples {start}-{start + n - 1} "
                    f"and then nothing for {self.timeout_s:g} s: no answer for sample {start + got} (too few "
                    "answers, or answers kept in its output buffer: flush stdout before reading more input)"
                )
            data = os.read(fd, 1 << 16)
            if not data:
                raise DetectorError(self._exit_message(start + got, start + n))
            buf += data
            got = buf.count(b"\n") if self.framing == "csv" else len(buf)
        if got > n:
            extra = start + n
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: more answers than samples: an answer for sample {extra} "
                f"arrived with the answers to samples {start}-{start + n - 1} (one answer per sample)"
            )
        if self.framing == "csv" and not buf.endswith(b"\n"):
            tail = bytes(buf[buf.rfind(b"\n") + 1 :])
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: output after the answer to sample {start + n - 1} "
                f"({_quote(tail)}): one answer per sample"
            )
        return bytes(buf)

    def _parse(self, raw: bytes, n: int, start: int):
        import numpy as np

        b = np.frombuffer(raw, np.uint8)
        if self.framing == "f64":
            bad = np.flatnonzero(b > 1)
            if bad.size:
                i = int(bad[0])
                raise DetectorError(
                    f"--detector-cmd {self.cmd!r}: answer for sample {start + i} is byte 0x{b[i]:02x}: "
                    "with framing f64 each answer is one byte 0x00 or 0x01"
                )
            return b.astype(bool)
        if b.shape[0] == 2 * n and np.all(b[1::2] == 10) and np.all((b[0::2] == 48) | (b[0::2] == 49)):
            return b[0::2] == 49  # every answer "0\n" or "1\n": the fast path
        lines = raw.split(b"\n")[:n]
        out = np.zeros(n, bool)
        for i, line in enumerate(lines):
            s = line.strip()
            if s not in (b"0", b"1"):
                raise DetectorError(
                    f"--detector-cmd {self.cmd!r}: answer for sample {start + i} is {_quote(line)}: "
                    "each answer is a line 0 or 1"
                )
            out[i] = s == b"1"
        return out

    def _exit_message(self, at: int, sent: int) -> str:
        """The program closed its output with answers due: its exit status and where it stopped."""
        try:
            rc = self.proc.wait(timeout=self.timeout_s)
        except subprocess.TimeoutExpired:
            return (
                f"--detector-cmd {self.cmd!r}: closed its output at sample {at} ({at} answers for the "
                f"{sent} samples sent) but did not exit"
            )
        how = f"was killed by signal {-rc}" if rc < 0 else f"exited with status {rc}"
        if rc == 0:
            return (
                f"--detector-cmd {self.cmd!r}: {how} at sample {at}: {at} answers for the {sent} samples "
                "sent (too few answers: one per sample, and exit only at the end of the input)"
            )
        return (
            f"--detector-cmd {self.cmd!r}: {how} at sample {at} ({at} answers for the {sent} samples "
            "sent; its messages are above)"
        )

    def _fail(self) -> None:
        self.failed = True
        self._finalizer()  # kill and reap now

    def close(self) -> None:
        """End the input, collect the program's exit (killing it after ``timeout_s``): a DetectorError
        when it then writes more answers or exits with a non-zero status (unless push failed before)."""
        if not self._finalizer.alive:
            return
        proc = self.proc
        with contextlib.suppress(OSError):
            assert proc.stdin is not None
            proc.stdin.close()
        extra = b""
        assert proc.stdout is not None
        fd = proc.stdout.fileno()
        deadline = time.monotonic() + self.timeout_s
        while True:  # drain what it still writes until EOF (its exit), or the deadline
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([fd], [], [], left)[0]:
                break
            data = os.read(fd, 1 << 16)
            if not data:
                break
            extra += data
        try:
            rc = proc.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            rc = None
        self._finalizer()
        if self.failed:
            return
        if extra:
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: more answers than samples: {_quote(extra)} after the answer "
                f"to the last sample ({self.sent - 1})"
            )
        if rc is None:
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: did not exit within {self.timeout_s:g} s of the end of its "
                f"input (after sample {self.sent - 1}); killed"
            )
        if rc != 0:
            how = f"was killed by signal {-rc}" if rc < 0 else f"exited with status {rc}"
            raise DetectorError(
                f"--detector-cmd {self.cmd!r}: {how} at the end of its input, after answering all "
                f"{self.sent} samples (its messages are above)"
            )


def _quote(b: bytes) -> str:
    """Bytes as a short quoted text for a message."""
    s = b.decode("utf-8", "backslashreplace")
    return repr(s if len(s) <= QUOTE_CHARS else s[:QUOTE_CHARS] + "...")


__all__ = [
    "FRAMINGS",
    "TIMEOUT_S",
    "PipeDetector",
    "encode",
    "encode_blocks",
    "header",
    "load_cmd",
    "units_of",
]
