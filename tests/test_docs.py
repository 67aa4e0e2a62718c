"""The documentation site's sources: every page is in the navigation of ``mkdocs.yml`` and every navigation entry is
a page; the changelog page is CHANGELOG.md itself; the reference has a page per subpackage; and no page, README or
docstring carries a tracker reference (an issue or item number, a dated note) — history belongs in CHANGELOG.md.

(``make docs`` builds the site with ``mkdocs build --strict``; CI runs it after the tests. These checks need no
MkDocs.)
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
MKDOCS = ROOT / "mkdocs.yml"

#: A tracker reference: an issue, item or stop number, a "#12"-style number (not a colour such as "#555"), a
#: dated note, or the words "work item".
TRACKER = [
    re.compile(r"\b[Ii]ssues? ?#?\d+"),
    re.compile(r"\b[Ii]tems? #?\d+\b"),
    re.compile(r"\b[Ss]top #?\d+\b(?![.,]\d)"),
    re.compile(r"(?<![\w&#/\"'])#\d{2,4}\b"),
    re.compile(r"\b20\d\d-[01]\d(?:-[0-3]\d)?\b"),
    re.compile(r"\b[Ww]ork[- ]items?\b"),
]


def nav_pages() -> list[str]:
    """The pages named in ``mkdocs.yml``'s navigation (``- Title: path.md``), in order."""
    text = MKDOCS.read_text(encoding="utf-8")
    nav = text[text.index("\nnav:"):]
    return re.findall(r"^\s+- [^:\n]+: (\S+\.md)\s*$", nav, flags=re.M)


def test_every_page_is_in_the_navigation_and_every_entry_is_a_page():
    pages = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md"))
    nav = nav_pages()
    assert len(nav) == len(set(nav)), "a page is twice in the navigation"
    assert sorted(nav) == pages, (sorted(set(pages) - set(nav)), sorted(set(nav) - set(pages)))
    assert nav[0] == "index.md"


def test_the_site_has_the_diataxis_sections_and_the_tutorials():
    nav = nav_pages()
    for page in ("tutorials/first-throw-map.md", "tutorials/feeder.md", "tutorials/positioning.md",
                 "tutorials/assembly.md", "explanation/errata.md", "explanation/validation.md",
                 "explanation/models.md", "explanation/conventions.md", "reference/development.md", "changelog.md"):
        assert page in nav, page
    text = MKDOCS.read_text(encoding="utf-8")
    for section in ("Tutorials", "How-to guides", "Explanation", "Reference"):
        assert re.search(rf"^  - {section}:\s*$", text, flags=re.M), section


def test_the_reference_has_a_page_per_subpackage():
    packages = sorted(p.parent.name for p in (ROOT / "src" / "throwmap").glob("*/__init__.py"))
    for name in packages:
        page = DOCS / "reference" / "api" / f"{name}.md"
        assert page.is_file(), f"no reference page for throwmap.{name}"
        assert f"::: throwmap.{name}" in page.read_text(encoding="utf-8")
    assert "::: throwmap\n" in (DOCS / "reference" / "api" / "index.md").read_text(encoding="utf-8")


def test_the_changelog_page_is_the_changelog():
    """docs/changelog.md includes CHANGELOG.md (pymdownx.snippets), so the two cannot disagree."""
    page = (DOCS / "changelog.md").read_text(encoding="utf-8")
    assert re.search(r'^--8<-- "CHANGELOG\.md"$', page, flags=re.M)
    assert "pymdownx.snippets" in MKDOCS.read_text(encoding="utf-8")
    assert (ROOT / "CHANGELOG.md").is_file()


def tracker_hits(text: str) -> list[str]:
    return [m.group(0) for pat in TRACKER for m in pat.finditer(text)]


def test_the_tracker_pattern_catches_what_it_should():
    for bad in ("see issue 12", "Issue #7", "item 3 of the list", "stop 4", "(#27)", "note of 2026-01-31",
                "a work item"):
        assert tracker_hits(bad), bad
    for good in ('color="#555"', "#2e86ab", "band #2", "seed 20240611", "stop (X = 0.38 m)", "issues none",
                 "the end stop at 0.38 m"):
        assert not tracker_hits(good), good


FILES = [ROOT / "README.md", ROOT / "CHANGELOG.md", *sorted(DOCS.rglob("*.md")),
         *sorted((ROOT / "src" / "throwmap").rglob("*.py"))]  # the changelog is a page of the site


def test_no_tracker_references_in_the_readme_the_docs_or_the_sources():
    hits = [f"{path.relative_to(ROOT)}:{n}: {h!r}" for path in FILES
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) for h in tracker_hits(line)]
    assert len(FILES) > 100 and not hits, hits
