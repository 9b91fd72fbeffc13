"""Benchmark: firmware over a pipe (flightmode.detector.pipe) with examples/nmv_fixed.c.

    python benchmarks/bench_pipe.py [HOURS]

On the same 100 Hz stream of three accelerometer axes (default 1 h = 360,000 samples; a bag at
rest with LIS302DL-like noise and a shaken stretch), each timed best of three:

- the C program through the pipe, csv and f64 framings, the stream as one chunk and in 1,000-sample
  chunks: samples per second through the pipe (header, encoding, the program, the answers parsed);
- the parts of the csv figure: encoding the text alone, and the program alone reading the same
  text from a file (no pipe, no Python);
- nmv-fixed in Python (NumPy, one chunk) on the same stream, for scale;
- the ratio f64 / csv.

Decisions of every run are checked equal to nmv-fixed's. Needs a C compiler (cc or gcc).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from _bench import best, best_timed, report

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "nmv_fixed.c"


def main(hours: float = 1.0) -> dict:
    from flightmode.detector import fixed_point as fp
    from flightmode.detector import interface, pipe

    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        raise SystemExit("bench_pipe: no C compiler (cc or gcc)")
    fs = 100.0
    n = int(hours * 3600 * fs)
    rng = np.random.default_rng(0)
    t = np.arange(n) / fs
    x = np.array([0.02, -0.03, 1.0]) + rng.normal(0.0, 2.23e-3, (n, 3))
    x[n // 3 : n // 2] += rng.normal(0.0, 0.05, (n // 2 - n // 3, 3))
    ch = list(interface.ACC_CHANNELS)
    ref = fp.make(fs, ch).push(t, x)
    res: dict = {"samples": n}
    with tempfile.TemporaryDirectory() as d:
        exe = Path(d) / "nmv_fixed"
        subprocess.run([cc, "-std=c99", "-O2", "-o", str(exe), str(EXAMPLE), "-lm"], check=True)
        rates = {}
        for framing in pipe.FRAMINGS:
            loaded = pipe.load_cmd(str(exe), framing)
            for chunk in (None, 1000):

                def run(loaded=loaded, chunk=chunk):
                    det = interface.build(loaded, fs, ch, {})
                    return interface.decisions(loaded.name, det, t, x, chunk=chunk)

                out, secs = best_timed(run)
                assert np.array_equal(out, ref), f"{framing} chunk {chunk}: decisions differ from nmv-fixed's"
                rates[framing, chunk] = n / secs
                res[
                    f"pipe {framing}, {'one chunk' if chunk is None else f'chunks of {chunk}'} (samples/s)"
                ] = n / secs
        text, enc_s = best_timed(lambda: pipe.encode(t, x, "csv"))
        res["csv encoding alone (samples/s)"] = n / enc_s
        src = Path(d) / "in.csv"
        src.write_bytes(pipe.header(fs, ch, "csv", {}) + text)

        def alone():
            with open(src, "rb") as f:
                subprocess.run([str(exe)], stdin=f, stdout=subprocess.DEVNULL, check=True)

        res["C program alone on the csv file (samples/s)"] = n / best(alone)
    res["nmv-fixed in Python, one chunk (samples/s)"] = n / best(lambda: fp.make(fs, ch).push(t, x))
    res["f64 / csv, one chunk"] = rates["f64", None] / rates["csv", None]
    res["f64 / csv, chunks of 1000"] = rates["f64", 1000] / rates["csv", 1000]
    report(res)
    return res


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 1.0)
