"""The stock JSBSim models shipped in the installed wheel, and the private copy of one that the adapter
(:class:`~flightmode.sim.flight.jsbsim.adapter.JSBSimAircraft`) loads.

Safety (checked on jsbsim 1.3.3's stock models): the stock 737 opens a telnet server and a UDP socket from its
``<input>`` sections and some models write CSV files from ``<output>``. The model is therefore
loaded from a *private copy* of its main XML in a temporary directory, with every top-level
``<input>`` and ``<output>`` element removed, ``disable_input()``/``disable_output()`` called
as well, and the temporary copy deleted as soon as JSBSim has parsed it. The copy also gives
every model the same tug: a body-axis ``external_reactions`` force named ``pushback`` at the
nose gear (the 787-8 and fokker100 already define one; the fokker100's own FlightGear-driven
``pushback`` system is removed so that one tug controller, :class:`~flightmode.sim.flight.pilot.ground.Pushback`,
drives all).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

from flightmode.errors import AircraftError, did_you_mean
from flightmode.sim.flight.jsbsim.model_xml import external_reactions, xml_sub
from flightmode.sim.flight.jsbsim.roughness_model import add_gear_roughness


def available_models() -> list[str]:
    """JSBSim aircraft directories shipped in the installed wheel."""
    import jsbsim

    root = Path(jsbsim.get_default_root_dir()) / "aircraft"
    return sorted(p.name for p in root.iterdir() if (p / f"{p.name}.xml").is_file())


def stock_model_xml(model: str) -> Path:
    """The main XML file of the stock JSBSim ``model`` shipped in the installed wheel (an
    :class:`AircraftError` naming the installed models if there is none)."""
    import jsbsim

    path = Path(jsbsim.get_default_root_dir()) / "aircraft" / model / f"{model}.xml"
    if not path.is_file():
        raise AircraftError(
            f"unknown JSBSim aircraft model '{model}'{did_you_mean(model, available_models())}; "
            f"installed models: {', '.join(available_models())}"
        )
    return path


def private_model_copy(model: str, workdir: Path, edits=()) -> Path:
    """Write the sanitised copy of ``model``'s main XML below ``workdir``; return the aircraft path.
    ``edits``: functions applied to the XML root before it is written (e.g. the gear's damping,
    :mod:`flightmode.sim.flight.jsbsim.gear`)."""
    src = stock_model_xml(model)
    src_dir = src.parent
    dst_dir = workdir / "aircraft" / model
    dst_dir.mkdir(parents=True)
    for entry in src_dir.iterdir():
        if entry.name != f"{model}.xml":
            os.symlink(entry, dst_dir / entry.name)
    tree = ET.parse(src)
    root = tree.getroot()
    for tag in ("input", "output"):
        for el in root.findall(tag):
            root.remove(el)
    for el in root.findall("system"):
        if el.get("file") == "pushback":
            root.remove(el)
    if root.find("external_reactions") is None:
        nose_x_in = _nose_gear_x_in(root)
        # external_reactions must come after ground_reactions in the document (made there by
        # model_xml.external_reactions)
        ext = external_reactions(root)
        force = xml_sub(ext, "force", name="pushback", frame="BODY")
        loc = xml_sub(force, "location", unit="IN")
        for axis, val in (("x", nose_x_in), ("y", 0.0), ("z", -60.0)):
            xml_sub(loc, axis, f"{val:.3f}")
        direc = xml_sub(force, "direction")
        for axis, val in (("x", 1.0), ("y", 0.0), ("z", 0.0)):
            xml_sub(direc, axis, f"{val:.1f}")
    for edit in edits:
        edit(root)
    add_gear_roughness(
        root
    )  # runway roughness through the gear, from the gear as edited (roughness_model.py)
    tree.write(dst_dir / f"{model}.xml", encoding="utf-8", xml_declaration=True)
    return workdir / "aircraft"


def _nose_gear_x_in(root: ET.Element) -> float:
    """Structural x of the most forward BOGEY contact (the nose gear), inches."""
    xs = []
    gr = root.find("ground_reactions")
    if gr is not None:
        for contact in gr.findall("contact"):
            if contact.get("type") == "BOGEY":
                x = contact.find("location/x")
                if x is not None and x.text:
                    xs.append(float(x.text))
    if not xs:
        raise AircraftError("model has no BOGEY gear contact to attach the pushback tug to")
    return min(xs)
