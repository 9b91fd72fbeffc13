"""The house's contract, read from the code's own imports (every ``import`` and ``from ... import``,
at module level or inside a function: a lazy import is still a dependency).

Three rules (DESIGN.md's "Rooms" and "Conventions"):

1. no import cycle between modules (an import under ``if TYPE_CHECKING:`` never runs and makes no
   cycle; it still may not point upward);
2. no upward import between rooms: :data:`LAYERS` lists the rooms from the top floor down, and a
   module may import only from its own room or a room below it (rooms on one floor are independent:
   neither imports the other); the face is used only by :data:`FACE_USERS`, and the e-obs toolkit
   reaches the rooms above the physics only through the public API (:data:`PUBLIC_API_ONLY`);
3. no ``_private`` name imported from another module.

:func:`violations` checks a tree laid out as the repository is (each top-level folder installed under
``flightmode.`` by pyproject's package-dir), so a test can plant a violation in a copy and see it fail.
"""

from __future__ import annotations

import ast
import functools
from dataclasses import dataclass
from pathlib import Path

# The repository's folders and the installed package each one is (pyproject.toml's package-dir).
FOLDERS = {
    "flightmode": "flightmode",
    "scenarios": "flightmode.scenarios",
    "sim": "flightmode.sim",
    "detector": "flightmode.detector",
    "nav": "flightmode.nav",
    "viz": "flightmode.viz",
    "eobs": "flightmode.eobs",
}

# From the top floor down; rooms on one floor never import each other. A module belongs to the
# longest room prefix that names it; the face (the package ``flightmode`` itself, whose pipeline
# names load lazily on first use) stands above every room, and the base modules directly under
# flightmode/ (errors, units, labels, streams, digest, the atomic writer, the Dask cluster...) below.
LAYERS: tuple[tuple[str, ...], ...] = (
    ("flightmode.cli",),
    ("flightmode.eobs",),
    ("flightmode.studies",),
    ("flightmode.datasets",),
    ("flightmode.runs",),
    ("flightmode.viz",),
    ("flightmode.scenarios",),
    ("flightmode.nav", "flightmode.detector"),
    ("flightmode.sim.sensor",),
    ("flightmode.sim.flight",),
)
FACE = "flightmode"
BASE = "flightmode (base modules)"
# The rooms that may use the face (its pipeline names load on first use, so it stands above every
# room): the command line, and the e-obs toolkit, which reaches flights through the public API only:
# the face and the datasets' face, never a module of the run, dataset, study or scenario rooms.
FACE_USERS = ("flightmode.cli", "flightmode.eobs")
PUBLIC_API_ONLY = {"flightmode.eobs": ("flightmode", "flightmode.datasets")}
BEHIND_THE_API = ("flightmode.runs", "flightmode.datasets", "flightmode.studies", "flightmode.scenarios")


@dataclass(frozen=True)
class Import:
    importer: str  # module name
    imported: str  # module name (the submodule where ``from pkg import sub`` names one)
    names: tuple[str, ...]  # the names taken by a ``from`` import (empty for ``import x``)
    line: int
    typing_only: bool = False  # under ``if TYPE_CHECKING:``: a type checker's, never run


def modules(root: Path) -> dict[str, Path]:
    """Every module of the tree under ``root``: installed name -> file."""
    out: dict[str, Path] = {}
    for folder, package in FOLDERS.items():
        for f in sorted((root / folder).rglob("*.py")):
            parts = list(f.relative_to(root / folder).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join([package, *parts])] = f
    return out


def _resolve(importer: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = importer.split(".") if is_package else importer.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def imports(root: Path) -> list[Import]:
    """Every import of a flightmode module by a flightmode module in the tree under ``root``."""
    mods = modules(root)
    names = frozenset(mods)
    out: list[Import] = []
    for name, path in mods.items():
        out.extend(_file_imports(name, path.name == "__init__.py", path.read_text(encoding="utf-8"), names))
    return out


@functools.lru_cache(maxsize=4096)
def _file_imports(name: str, is_package: bool, text: str, mods: frozenset[str]) -> tuple[Import, ...]:
    """One module's imports (:func:`imports`), once per (module, text, the tree's modules) in a process:
    a planted copy of the tree reads again only the files it changed."""
    tree = ast.parse(text)
    out: list[Import] = []
    typing_only = {
        id(n)
        for block in ast.walk(tree)
        if isinstance(block, ast.If) and ast.unparse(block.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING")
        for stmt in block.body
        for n in ast.walk(stmt)
    }
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "flightmode":
                    out.append(Import(name, alias.name, (), node.lineno, id(node) in typing_only))
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(name, is_package, node)
            if target.split(".")[0] != "flightmode":
                continue
            plain = []
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                if sub in mods:  # ``from pkg import module``: a dependency on that module
                    out.append(Import(name, sub, (), node.lineno, id(node) in typing_only))
                else:
                    plain.append(alias.name)
            if plain:
                out.append(Import(name, target, tuple(plain), node.lineno, id(node) in typing_only))
    out.extend(_private_attributes(name, tree, mods))
    return tuple(out)


def _private_attributes(name: str, tree: ast.Module, mods: frozenset[str]) -> list[Import]:
    """``alias._x`` where ``alias`` names another flightmode module (``from pkg import mod as alias``,
    ``import pkg.mod as alias``): a private name reached across modules without importing it."""
    bound: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname and alias.name in mods:
                    bound[alias.asname] = alias.name
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            for alias in node.names:
                sub = f"{node.module}.{alias.name}"
                if sub in mods:
                    bound[alias.asname or alias.name] = sub
    out = []
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Name)
            and node.value.id in bound
            and bound[node.value.id] != name
            and node.attr.startswith("_")
            and not node.attr.startswith("__")
        ):
            out.append(Import(name, bound[node.value.id], (node.attr,), node.lineno))
    return out


def room_of(module: str) -> str:
    """The room a module belongs to: a name of :data:`LAYERS`, :data:`FACE` or :data:`BASE`."""
    best = ""
    for floor in LAYERS:
        for room in floor:
            if (module == room or module.startswith(room + ".")) and len(room) > len(best):
                best = room
    if best:
        return best
    return FACE if module == FACE else BASE


def floor_of(room: str) -> int:
    """0 for the face, 1 for the top room, ..., len(LAYERS) + 1 for the base modules."""
    if room == FACE:
        return 0
    if room == BASE:
        return len(LAYERS) + 1
    return 1 + next(i for i, floor in enumerate(LAYERS) if room in floor)


def cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:  # recursion depth is bounded by the module count (a few hundred)
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return sorted(found)


def violations(root: Path) -> list[str]:
    """Every breach of the three rules in the tree under ``root``, one line each (empty: the contract
    holds)."""
    mods = modules(root)
    found: list[str] = []
    edges: dict[str, set[str]] = {m: set() for m in mods}
    for imp in imports(root):
        where = f"{mods[imp.importer].relative_to(root)}:{imp.line}"
        if imp.imported not in mods:
            continue  # a name flightmode does not define here (a module of another tree, a typo) is Python's to report
        if imp.imported != imp.importer and not imp.typing_only:  # a type-only import never runs
            edges[imp.importer].add(imp.imported)
        a, b = room_of(imp.importer), room_of(imp.imported)
        if a in PUBLIC_API_ONLY and b in BEHIND_THE_API + (FACE,) and imp.imported not in PUBLIC_API_ONLY[a]:
            found.append(
                f"past the public API: {where} ({a}) imports {imp.imported}; use the face or flightmode.datasets"
            )
        if b == FACE and a in FACE_USERS:
            pass
        elif a != b and a != FACE:
            fa, fb = floor_of(a), floor_of(b)
            if fb < fa:
                found.append(f"upward import: {where} ({a}) imports {imp.imported} ({b}, a floor above)")
            elif fb == fa:
                found.append(f"sideways import: {where} ({a}) imports {imp.imported} ({b}, the same floor)")
        for n in imp.names:
            if n.startswith("_") and not n.startswith("__"):
                found.append(f"private name: {where} imports {n} from {imp.imported}")
    for comp in cycles(edges):
        found.append("import cycle: " + " -> ".join(comp))
    return found


def room_graph(root: Path) -> tuple[dict[str, int], dict[tuple[str, str], int]]:
    """Lines of code per room, and the imports between rooms (importer room, imported room) -> count."""
    mods = modules(root)
    lines: dict[str, int] = {}
    for m, f in mods.items():
        r = room_of(m)
        lines[r] = lines.get(r, 0) + len(f.read_text(encoding="utf-8").splitlines())
    arrows: dict[tuple[str, str], int] = {}
    for imp in imports(root):
        if imp.imported in mods:
            a, b = room_of(imp.importer), room_of(imp.imported)
            if a != b:
                arrows[(a, b)] = arrows.get((a, b), 0) + 1
    return lines, arrows


if __name__ == "__main__":  # python -m tests.architecture: the house, floor by floor, and its breaches
    root = Path(__file__).resolve().parents[1]
    lines, arrows = room_graph(root)
    floors = [(FACE,), *LAYERS, (BASE,)]
    for floor in floors:
        for room in floor:
            down = sorted(b for (a, b) in arrows if a == room)
            print(
                f"{floor_of(room):2d}  {room:28s} {lines.get(room, 0):6d} lines  -> {', '.join(down) or '-'}"
            )
    found = violations(root)
    print(
        "\n".join(found)
        if found
        else "contract holds: no cycle, no upward or sideways import, no private name"
    )
