"""Property-based fuzzing of the scenario and family parsers (issue 54, item 5): documents of random
structure, the built-in scenario and family files with keys deleted, values of the wrong type, NaN,
infinities, huge and negative numbers, Unicode, and their texts edited character by character. Whatever
the input, the parser returns a scenario (or family) or raises a FlightmodeError subclass: nothing else.

A scenario it accepts writes itself back as TOML and reads back equal; a family it accepts makes its
first member. The number of examples: tests/fuzz.py (FLIGHTMODE_FUZZ_EXAMPLES; 200 in CI).
"""

from __future__ import annotations

import tomli_w
from hypothesis import event, given

from flightmode.errors import FlightmodeError
from flightmode.scenarios.family import SECTIONS as FAMILY_SECTIONS
from flightmode.scenarios.family import Family
from flightmode.scenarios.scenario import Scenario
from flightmode.scenarios.spec import MODEL_SECTION, SPEC
from tests.fuzz import fuzz_settings, mutated_docs, mutated_texts, random_docs, toml_texts

SCENARIOS = toml_texts("scenarios/library")
FAMILIES = toml_texts("scenarios/families")
SCENARIO_SECTIONS = (*SPEC, MODEL_SECTION)
SCENARIO_KEYS = tuple(sorted({k for keys in SPEC.values() for k in keys}))
FAMILY_KEYS = tuple(sorted({k for keys in FAMILY_SECTIONS.values() if keys is not None for k in keys}))


def _scenario(text: str) -> None:
    try:
        sc = Scenario.from_toml_text(text, "<fuzz>")
    except FlightmodeError as e:
        event(type(e).__name__)  # pytest --hypothesis-show-statistics: how many were refused, how many read
        return
    event("read")
    assert Scenario.from_toml_text(sc.to_toml(), "<again>") == sc


def _family(text: str) -> None:
    try:
        fam = Family.from_toml_text(text, "<fuzz>")
        fam.member(0)
    except FlightmodeError as e:
        event(type(e).__name__)
        return
    event("read")


@fuzz_settings()
@given(mutated_docs(SCENARIOS, SCENARIO_KEYS))
def test_scenario_parser_mutated_builtins(doc):
    _scenario(tomli_w.dumps(doc))


@fuzz_settings()
@given(random_docs(SCENARIO_SECTIONS, SCENARIO_KEYS))
def test_scenario_parser_random_documents(doc):
    _scenario(tomli_w.dumps(doc))


@fuzz_settings()
@given(mutated_texts(SCENARIOS))
def test_scenario_parser_edited_texts(text):
    _scenario(text)


@fuzz_settings()
@given(mutated_docs(FAMILIES, FAMILY_KEYS))
def test_family_parser_mutated_builtins(doc):
    _family(tomli_w.dumps(doc))


@fuzz_settings()
@given(random_docs(tuple(FAMILY_SECTIONS), FAMILY_KEYS))
def test_family_parser_random_documents(doc):
    _family(tomli_w.dumps(doc))


@fuzz_settings()
@given(mutated_texts(FAMILIES))
def test_family_parser_edited_texts(text):
    _family(text)
