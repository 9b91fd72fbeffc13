"""The README stays short, and every relative link in the README and docs/ leads somewhere.

- README.md has at most 200 lines (issue 49: the rest lives in docs/);
- every relative link or image (``[text](target)``, ``![alt](target)``) in README.md and docs/*.md
  names a file or folder of the repository, and a ``#fragment`` names a heading of the file it points
  to (GitHub's anchors: lower case, punctuation dropped, spaces to hyphens). Links inside code blocks
  and code spans are not links; web addresses are not checked (no network in the tests).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README_MAX_LINES = 200
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"`+[^`]*`+")


def markdown_files() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def prose_lines(path: Path) -> list[tuple[int, str]]:
    """(line number, text) of the lines outside fenced code blocks, code spans removed."""
    out, fenced = [], False
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            out.append((n, CODE_SPAN.sub("", line)))
    return out


def anchor(heading: str) -> str:
    """GitHub's anchor of a heading's text."""
    text = re.sub(r"[`*_]|\[([^\]]*)\]\([^)]*\)", lambda m: m.group(1) or "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path: Path) -> set[str]:
    found: set[str] = set()
    for _, line in prose_lines(path):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            a = anchor(m.group(1))
            k = 1
            base = a
            while a in found:  # GitHub numbers repeated headings: name, name-1, name-2, ...
                a, k = f"{base}-{k}", k + 1
            found.add(a)
    return found


def relative_links(path: Path) -> list[tuple[int, str]]:
    links = []
    for n, line in prose_lines(path):
        for m in LINK.finditer(line):
            target = m.group(1)
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):  # http:, https:, mailto:, ...
                continue
            links.append((n, target))
    return links


def broken_links(path: Path) -> list[str]:
    broken = []
    for n, target in relative_links(path):
        file_part, _, fragment = target.partition("#")
        dest = (path.parent / file_part).resolve() if file_part else path
        where = f"{path.relative_to(ROOT)}:{n}: {target}"
        if not dest.exists():
            broken.append(f"{where}: no such file")
        elif ROOT not in dest.parents and dest != ROOT:
            broken.append(f"{where}: outside the repository")
        elif fragment and dest.suffix == ".md" and fragment not in anchors(dest):
            broken.append(f"{where}: no heading with anchor #{fragment}")
    return broken


def test_readme_is_at_most_200_lines():
    n = len((ROOT / "README.md").read_text(encoding="utf-8").splitlines())
    assert n <= README_MAX_LINES, (
        f"README.md has {n} lines; move detail into docs/ (at most {README_MAX_LINES})"
    )


@pytest.mark.parametrize("path", markdown_files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_resolve(path):
    assert not broken_links(path), "\n".join(broken_links(path))


def test_the_link_check_sees_links():
    """The checker finds the README's links into docs/ and would report a missing one."""
    links = [t for _, t in relative_links(ROOT / "README.md")]
    assert "docs/modelling.md" in links and "docs/default-recording.png" in links
    assert anchor("The paper's tables on the default flight") == "the-papers-tables-on-the-default-flight"
    assert anchor("The (in)activity detectors study (seed 001)") == "the-inactivity-detectors-study-seed-001"
