"""The one JSBSim adapter: with the rest of :mod:`flightmode.sim.flight.jsbsim`, the only ``import jsbsim``
in flightmode.

JSBSim speaks imperial units; this module converts them to SI exactly once, in the
:data:`CHANNELS` table, and the rest of flightmode only sees SI arrays.

Safety: the model is loaded from a sanitised private copy of its main XML
(:mod:`~flightmode.sim.flight.jsbsim.model_copy`), ``disable_input()``/``disable_output()`` called as well.
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim.model_copy import private_model_copy
from flightmode.units import FT_M, G0_MPS2, KT_MPS, LBF_N


class PropertyNode(Protocol):
    """What flightmode uses of a JSBSim property node (jsbsim's FGPropertyNode; jsbsim ships no stubs)."""

    def get_double_value(self) -> float: ...

    def set_double_value(self, value: float) -> None: ...


@dataclass(frozen=True, slots=True)
class Channel:
    """One JSBSim property recorded for the FlightTrack, with its SI name and scale. A ``slow``
    channel is read at the pilot's ticks only (4-40 Hz) and interpolated linearly to every step: the
    actuator positions (rate-limited, piecewise linear in time), the engines (first-order spool
    lags of seconds) and the air data (airspeeds, Mach, angle of attack), which only the truth
    columns show. Reading 32 properties every step cost a third of a flight's time."""

    name: str
    prop: str
    scale: float = 1.0
    slow: bool = False


# Height above ground is derived, not read: ``position/h-agl-ft`` costs three times any other
# property (JSBSim asks its ground callback on every read, 174 ns against 60 ns). Over JSBSim's
# flat terrain, altitude minus terrain elevation is the height along the ellipsoid normal; JSBSim's
# own differs from it by 1 - cos(geodetic - geocentric latitude), at most 6 ppm of the height (mm
# on the ground, 6 cm at FL350; tests/sim/test_adapter.py). Rows given to the pilot carry it after
# the read channels, at ``index["agl_m"]``.
DERIVED_CHANNELS = (Channel("agl_m", "(alt_m - terrain elevation)"),)

# The angular acceleration is derived, not read, too. JSBSim integrates the body rates with
# rectangular Euler (``simulation/integrator/rate/rotational`` = 1, its default; JSBSim reference
# manual, FGPropagate), so the acceleration it applied in a step is exactly the step's change of rate
# over dt: ``accelerations/pdot-rad_sec2`` read before a step equals (p after - p before) / dt to
# 5e-8 rad/s^2 (the change of the Earth's rate seen in body axes; tests/sim/test_adapter.py). The
# flight loop then reads 16 properties per step instead of 19.
ROTATIONAL_RATE_INTEGRATOR_RECT_EULER = 1


def _channels(n_engines: int) -> tuple[Channel, ...]:
    base = [
        Channel("lat_deg", "position/lat-geod-deg"),
        Channel("lon_deg", "position/long-gc-deg"),
        Channel("alt_m", "position/h-sl-ft", FT_M),
        Channel("phi_rad", "attitude/phi-rad"),
        Channel("theta_rad", "attitude/theta-rad"),
        Channel("psi_rad", "attitude/psi-rad"),
        Channel("p_radps", "velocities/p-rad_sec"),
        Channel("q_radps", "velocities/q-rad_sec"),
        Channel("r_radps", "velocities/r-rad_sec"),
        Channel("v_north_mps", "velocities/v-north-fps", FT_M),
        Channel("v_east_mps", "velocities/v-east-fps", FT_M),
        Channel("v_down_mps", "velocities/v-down-fps", FT_M),
        # Specific force at the CG, body axes: JSBSim's load factors N = F_nongravity / W, so
        # f = N * g0 (Nz is positive up in JSBSim's convention, hence the sign below).
        Channel("fx_mps2", "accelerations/Nx", G0_MPS2),
        Channel("fy_mps2", "accelerations/Ny", G0_MPS2),
        Channel("fz_mps2", "accelerations/Nz", -G0_MPS2),
        Channel("wow", "gear/wow"),
        Channel("ias_mps", "velocities/vc-kts", KT_MPS, slow=True),
        Channel("tas_mps", "velocities/vtrue-kts", KT_MPS, slow=True),
        Channel("mach", "velocities/mach", slow=True),
        Channel("alpha_rad", "aero/alpha-rad", slow=True),
        Channel("flap_norm", "fcs/flap-pos-norm", slow=True),
        Channel("gear_norm", "gear/gear-pos-norm", slow=True),
        Channel("speedbrake_norm", "fcs/speedbrake-pos-norm", slow=True),
    ]
    for i in range(n_engines):
        base += [
            Channel(f"n1_pct_{i}", f"propulsion/engine[{i}]/n1", slow=True),
            Channel(f"n2_pct_{i}", f"propulsion/engine[{i}]/n2", slow=True),
            Channel(f"thrust_n_{i}", f"propulsion/engine[{i}]/thrust-lbs", LBF_N, slow=True),
        ]
    return tuple(base)  # the every-step channels first, then the slow ones


COPY_PREFIX = "flightmode-model-"  # + the process id + "-" + mkdtemp's letters
STALE_COPY_S = 600.0  # a copy lives for the load (under a second): older ones are a killed process's
_SWEPT: set[Path] = set()  # the folders this process has swept (JSBSimAircraft)


def remove_stale_copies(root: Path) -> list[Path]:
    """Remove the private model copies in ``root`` that a killed process left (SIGKILL between the copy
    and its removal after loading: a dataset worker killed as a flight starts): those whose process no
    longer runs and that are older than ``STALE_COPY_S`` (a process of another machine sharing the
    folder, whose id means nothing here, has long finished loading by then). Returns what it removed."""
    import time

    removed: list[Path] = []
    now = time.time()
    try:
        entries = list(os.scandir(root))
    except OSError:
        return removed
    for e in entries:
        if not e.name.startswith(COPY_PREFIX):
            continue
        pid = e.name[len(COPY_PREFIX) :].split("-", 1)[0]
        try:
            if not pid.isdigit() or now - e.stat().st_mtime < STALE_COPY_S or _running(int(pid)):
                continue
        except OSError:
            continue
        shutil.rmtree(e.path, ignore_errors=True)
        removed.append(Path(e.path))
    return removed


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


class JSBSimAircraft:
    """A JSBSim FDM with flightmode's safety settings, SI channels and fast property access.

    Parameters
    ----------
    model : JSBSim aircraft directory name (e.g. ``"A320"``).
    dt_s : FDM time step (s).
    n_engines : number of engines whose N1/N2/thrust are read every step.
    workdir : where the temporary private model copy is made (a fresh subdirectory, deleted
        after loading); the system temporary directory when ``None``.
    edits : functions of the model's XML root applied to the private copy
        (:func:`~flightmode.sim.flight.jsbsim.model_copy.private_model_copy`).
    """

    def __init__(self, model: str, dt_s: float, n_engines: int, workdir: Path | None = None, edits=()):
        import jsbsim

        self.model = model
        self.dt_s = dt_s
        self.channels = _channels(n_engines)
        self.index = {c.name: i for i, c in enumerate(self.channels + DERIVED_CHANNELS)}
        self.n_every_step = sum(1 for c in self.channels if not c.slow)  # the first channels
        root = Path(workdir if workdir is not None else tempfile.gettempdir())
        if root not in _SWEPT:  # once per process and folder: a killed process's copies predate this one
            _SWEPT.add(root)
            remove_stale_copies(root)
        tmp = Path(
            tempfile.mkdtemp(prefix=f"{COPY_PREFIX}{os.getpid()}-", dir=root)
        ).resolve()  # JSBSim needs absolute paths
        try:
            aircraft_path = private_model_copy(model, tmp, edits)
            jsbsim.FGJSBBase().debug_lvl = 0  # no start-up banner on stdout
            fdm = jsbsim.FGFDMExec(None)
            fdm.set_debug_level(0)
            fdm.disable_output()
            fdm.set_aircraft_path(str(aircraft_path))
            if not fdm.load_model(model, True):
                raise AircraftError(f"JSBSim could not load aircraft model '{model}'")
            fdm.disable_input()
            fdm.disable_output()
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        fdm.set_dt(dt_s)
        self.fdm = fdm
        self._pm = fdm.get_property_manager()
        self._read_nodes = [self.node(c.prop) for c in self.channels]
        self._scales = np.array([c.scale for c in self.channels])
        self._nodes: dict[str, PropertyNode] = {}

    def node(self, prop: str):
        """The property node of ``prop`` (JSBSim's name; an :class:`AircraftError` if the model has none)."""
        node = self._pm.get_node(prop, False)
        if node is None:
            raise AircraftError(f"aircraft model '{self.model}' has no property '{prop}'")
        return node

    def has(self, prop: str) -> bool:
        """Whether the model has the property ``prop`` (JSBSim's name)."""
        return self._pm.hasNode(prop)

    # ----------------------------------------------------------------------------------------
    def set(self, prop: str, value: float) -> None:
        """Write a JSBSim property (imperial, as JSBSim names it); cached node lookup."""
        node = self._nodes.get(prop)
        if node is None:
            node = self._nodes[prop] = self.node(prop)
        node.set_double_value(float(value))

    def get(self, prop: str) -> float:
        node = self._nodes.get(prop)
        if node is None:
            node = self._nodes[prop] = self.node(prop)
        return node.get_double_value()

    @property
    def scales(self) -> np.ndarray:
        """Per-channel factors from JSBSim's units to SI (multiply a raw row by them)."""
        return self._scales

    def raw_getter(self):
        """(getter, nodes): ``map(getter, nodes)`` yields every channel's raw value."""
        return type(self._read_nodes[0]).get_double_value, self._read_nodes

    def init_on_ground(self, lat_deg: float, lon_deg: float, elevation_m: float, heading_deg: float) -> None:
        """Place the aircraft at rest on flat ground (ground start: terrain elevation set, a little above it, run_ic, gear
        down, brakes on, JSBSim's ground trim)."""
        fdm = self.fdm
        fdm["ic/lat-geod-deg"] = lat_deg
        fdm["ic/long-gc-deg"] = lon_deg
        fdm["ic/terrain-elevation-ft"] = elevation_m / FT_M
        fdm["ic/h-agl-ft"] = 20.0  # start a little high: AGL 0 buries the gear (the A320 then goes NaN)
        fdm["ic/psi-true-deg"] = heading_deg
        for p in ("ic/u-fps", "ic/v-fps", "ic/w-fps", "ic/p-rad_sec", "ic/q-rad_sec", "ic/r-rad_sec"):
            fdm[p] = 0.0
        if not fdm.run_ic():
            raise AircraftError(f"JSBSim rejected the initial conditions of '{self.model}'")
        fdm["gear/gear-cmd-norm"] = 1.0
        fdm["fcs/left-brake-cmd-norm"] = 1.0
        fdm["fcs/right-brake-cmd-norm"] = 1.0
        fdm["simulation/do_simple_trim"] = 2  # ground trim
        if not math.isfinite(fdm["position/h-agl-ft"]):
            raise AircraftError(f"ground trim of '{self.model}' produced NaN")

    def step(self) -> None:
        self.fdm.run()
