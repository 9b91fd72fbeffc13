"""What the property-based fuzz tests share (issue 54, item 5): their Hypothesis settings and the
generators of damaged TOML documents and texts.

The number of examples is FLIGHTMODE_FUZZ_EXAMPLES (default :data:`DEFAULT_EXAMPLES`, the fast tier's;
CI's ``.ci/run`` sets 200; docs/failures.md gives the 10,000-example command). Every run is reproducible: ``derandomize`` draws the examples from a
seed fixed by the test's name, and nothing is written to a Hypothesis database (none in the repository).
"""

from __future__ import annotations

import copy
import math
import os
import tomllib
from pathlib import Path

from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st

DEFAULT_EXAMPLES = 50
ROOT = Path(__file__).resolve().parent.parent


def fuzz_settings() -> settings:
    """The fuzz tests' settings: FLIGHTMODE_FUZZ_EXAMPLES examples, derandomized, no database, no
    deadline (a slow example is not a failure; the count is)."""
    n = int(os.environ.get("FLIGHTMODE_FUZZ_EXAMPLES", DEFAULT_EXAMPLES))
    return settings(
        max_examples=n,
        derandomize=True,
        database=None,
        deadline=None,
        print_blob=False,
        phases=[Phase.explicit, Phase.reuse, Phase.generate, Phase.target, Phase.shrink],  # no explain: no
        # patch files written under .hypothesis/ when an example fails
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
    )


def toml_texts(folder: str) -> dict[str, str]:
    """The built-in TOML files of ``folder`` (scenarios/library, scenarios/families) by name."""
    return {p.stem: p.read_text(encoding="utf-8") for p in sorted((ROOT / folder).glob("*.toml"))}


# ------------------------------------------------------------------------------------------ values

# the numbers that break ranges and arithmetic: NaN, the infinities, the extremes of a double and of
# TOML's 64-bit integer, zero of both signs, the smallest subnormal
EDGE_NUMBERS = (math.nan, math.inf, -math.inf, 1e308, -1e308, 0.0, -0.0, 5e-324, -1, 0, 2**63 - 1, -(2**63))

scalars = st.one_of(
    st.sampled_from(EDGE_NUMBERS),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(2**63), max_value=2**63 - 1),
    st.booleans(),
    st.text(max_size=12),  # any Unicode (no lone surrogates: TOML is UTF-8)
    st.datetimes(),
    st.dates(),
    st.times(),
)
values = st.recursive(
    scalars,
    lambda inner: st.one_of(
        st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=8), inner, max_size=3)
    ),
    max_leaves=8,
)


# ------------------------------------------------------------------------------------------ documents


def _nodes(tree, path=()):
    """Every (container, key) of a parsed TOML document: dict keys and list indices, at any depth."""
    items = tree.items() if isinstance(tree, dict) else enumerate(tree)
    for k, v in list(items):
        yield tree, k
        if isinstance(v, (dict, list)):
            yield from _nodes(v, path + (k,))


def _typo(draw, s: str) -> str:
    if not s:
        return draw(st.text(min_size=1, max_size=3))
    i = draw(st.integers(0, len(s) - 1))
    return draw(st.sampled_from([s[:i] + s[i + 1 :], s[:i] + s[i] + s[i:], s.upper(), s + "x"]))


@st.composite
def mutated_docs(draw, texts: dict[str, str], known_keys: tuple[str, ...] = ()):
    """A built-in file's document with 1-4 mutations: a key or section deleted, a value replaced by
    any value (NaN, inf, huge, negative, Unicode, a list, a table), a number scaled by -1, 0, 1e6 or
    1e-6, a string misspelt, a key added (a real key in the wrong place, or an unknown one), a value
    wrapped in a list."""
    doc = copy.deepcopy(tomllib.loads(texts[draw(st.sampled_from(sorted(texts)))]))
    for _ in range(draw(st.integers(1, 4))):
        nodes = list(_nodes(doc))
        if not nodes:
            doc[draw(st.text(min_size=1, max_size=8))] = draw(values)
            continue
        parent, k = draw(st.sampled_from(nodes))
        v = parent[k]
        op = draw(st.sampled_from(["delete", "replace", "scale", "typo", "add", "wrap"]))
        if op == "delete":
            del parent[k]
        elif op == "replace":
            parent[k] = draw(values)
        elif op == "scale" and isinstance(v, (int, float)) and not isinstance(v, bool):
            f = draw(st.sampled_from([-1, 0, 10**6, 1e-6, math.inf]))
            parent[k] = v * f if isinstance(f, int) else float(v) * f
        elif op == "typo" and isinstance(v, str):
            parent[k] = _typo(draw, v)
        elif op == "add" and isinstance(v, dict):
            name = draw(st.one_of(st.sampled_from(known_keys or ("x",)), st.text(min_size=1, max_size=8)))
            v[name] = draw(values)
        elif op == "wrap":
            parent[k] = [v]
        elif op == "typo" and isinstance(parent, dict):  # a misspelt key
            parent[_typo(draw, str(k))] = parent.pop(k)
        else:
            parent[k] = draw(values)
    return doc


def random_docs(section_names: tuple[str, ...], key_names: tuple[str, ...]):
    """Documents of random structure: sections (real names or any text) of keys (real names or any
    text) holding any value, or a value where a section belongs."""
    name = lambda real: st.one_of(st.sampled_from(real), st.text(min_size=1, max_size=10))  # noqa: E731
    return st.dictionaries(
        name(section_names),
        st.one_of(st.dictionaries(name(key_names), values, max_size=5), values),
        max_size=4,
    )


@st.composite
def mutated_texts(draw, texts: dict[str, str]):
    """A built-in file's text edited as characters: a slice deleted, any text inserted, a line
    doubled or dropped, the text cut short."""
    text = texts[draw(st.sampled_from(sorted(texts)))]
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(text)))
        j = draw(st.integers(i, min(len(text), i + 40)))
        lines = text.split("\n")
        n = draw(st.integers(0, max(0, len(lines) - 1)))
        op = draw(st.sampled_from(["delete", "insert", "double", "drop", "cut"]))
        if op == "delete":
            text = text[:i] + text[j:]
        elif op == "insert":
            text = text[:i] + draw(st.text(max_size=12)) + text[i:]
        elif op == "double":
            text = "\n".join(lines[: n + 1] + lines[n:])
        elif op == "drop":
            text = "\n".join(lines[:n] + lines[n + 1 :])
        else:
            text = text[:i]
    return text
