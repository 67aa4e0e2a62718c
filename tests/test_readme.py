"""The README and every documentation page (``docs/**/*.md``) work as pasted: every ```python block runs (page by
page, chapter by chapter, each chapter in one session, as a reader pasting them into one interpreter would), every
part file shown in a ```toml block loads, every command shown in a ```bash block exists with the options it uses
(``throwmap <cmd> --help``), and every link points at a file that is there.

Shell examples meant to fail (bad input) are in ```console blocks and are not run.
"""

from __future__ import annotations

import functools
import re
import shlex
from pathlib import Path

import pytest
from typer.testing import CliRunner

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
PAGES = [README, *sorted(DOCS.rglob("*.md"))]
PART_FILE_PAGE = DOCS / "how-to" / "part-files.md"


def rel(page: Path) -> str:
    return page.relative_to(ROOT).as_posix()


def blocks(lang: str, text: str | None = None) -> list[str]:
    """The contents of every fenced block of language ``lang`` in the README (or ``text``)."""
    text = README.read_text(encoding="utf-8") if text is None else text
    return re.findall(rf"^```{lang}\n(.*?)^```", text, flags=re.S | re.M)


@functools.lru_cache(maxsize=None)
def page_blocks(lang: str, page: str) -> tuple[str, ...]:
    """The ``lang`` blocks of one page (``page`` relative to the repository root)."""
    return tuple(blocks(lang, (ROOT / page).read_text(encoding="utf-8")))


def all_blocks(lang: str) -> list[tuple[str, str]]:
    """``(page, block)`` for every ``lang`` block of every page."""
    return [(rel(p), b) for p in PAGES for b in page_blocks(lang, rel(p))]


def shell_commands(block: str) -> list[list[str]]:
    """Each ``throwmap …`` / ``make …`` / ``python …`` line of a shell block as words, comments and
    ``[optional]`` brackets removed (``[--plot funnels.png]`` → ``--plot funnels.png``)."""
    out = []
    for line in re.sub(r"\\\n\s*", " ", block).splitlines():  # a command continued on the next line, joined
        line = line.split(" #")[0].strip()
        if line.startswith("$ "):
            line = line[2:]
        if not line or line.startswith("#"):
            continue
        line = line.replace("[", " ").replace("]", " ").replace("…", "x")
        for part in line.split("&&"):
            words = shlex.split(part)
            while words and re.fullmatch(r"[A-Z_]+=\S*", words[0]):  # VAR=value prefixes
                words = words[1:]
            if words:
                out.append(words)
    return out


def test_the_pages_have_the_blocks_this_test_reads():
    assert blocks("python") and blocks("bash")  # the README's first result, in Python and on the command line
    assert len(all_blocks("python")) >= 20 and len(all_blocks("bash")) >= 20 and all_blocks("toml")
    assert PART_FILE_PAGE in PAGES and len(PAGES) >= 20


def chapters(code_blocks: list[str] | tuple[str, ...]) -> list[tuple[int, int]]:
    """One page's Python as chapters ``(first, end)`` of block indices: a chapter starts at the page's first block
    and at every block that imports ``throwmap as tm`` itself, and runs to the next one."""
    starts = [i for i, b in enumerate(code_blocks) if i == 0 or re.match(r"import (\w+, )*throwmap as tm\b", b)]
    return list(zip(starts, starts[1:] + [len(code_blocks)]))


CHAPTERS = [(rel(p), a, b) for p in PAGES for a, b in chapters(page_blocks("python", rel(p)))]


def printed(text: str) -> dict[int, str]:
    """What a page says its Python blocks print: a ``text`` block that follows a ``python`` block with no other block
    between them is the output of that block (index among the page's Python blocks)."""
    out, k, last = {}, -1, ""
    for lang, body in re.findall(r"^```(\w*)\n(.*?)^```", text, flags=re.S | re.M):
        if lang == "python":
            k += 1
        elif lang == "text" and k >= 0 and k not in out and last == "python":
            out[k] = body
        last = lang
    return out


@pytest.mark.slow
@pytest.mark.parametrize("page, first, end", CHAPTERS, ids=[f"{p}:blocks {a}-{b - 1}" for p, a, b in CHAPTERS])
def test_python_blocks_run_as_pasted(page, first, end, tmp_path, monkeypatch):
    """A chapter's blocks in order in one fresh namespace, in an empty folder (files they write go there), as a
    reader pasting them into a new interpreter would."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import sys
    import types

    monkeypatch.chdir(tmp_path)
    module = types.ModuleType("__readme__")  # like __main__ of an interpreter: dataclasses look it up
    monkeypatch.setitem(sys.modules, module.__name__, module)
    namespace = module.__dict__
    import contextlib
    import io

    code_blocks = page_blocks("python", page)
    expected = printed((ROOT / page).read_text(encoding="utf-8"))
    for i in range(first, end):
        code = code_blocks[i]
        stdout = io.StringIO()
        try:
            with contextlib.redirect_stdout(stdout):
                exec(compile(code, f"{page} python block {i}", "exec"), namespace)
        except Exception as err:  # pragma: no cover - the message is the point
            pytest.fail(f"{page} python block {i} fails: {type(err).__name__}: {err}\n{code}")
        finally:
            plt.close("all")
        if i in expected:  # the page shows what the block prints: it must print that
            assert stdout.getvalue().rstrip() == expected[i].rstrip(), f"{page} python block {i} prints otherwise"


def test_the_chapters_cover_every_block_once():
    for p in PAGES:
        n = len(page_blocks("python", rel(p)))
        mine = [(a, b) for q, a, b in CHAPTERS if q == rel(p)]
        if n == 0:
            assert not mine
            continue
        assert mine[0][0] == 0 and mine[-1][1] == n
        assert all(a < b == c for (a, b), (c, _) in zip(mine, mine[1:] + [(n, n)]))
    assert chapters(["x = 1", "import throwmap as tm", "y = 2", "import math, throwmap as tm"]) == [(0, 1), (1, 3), (3, 4)]


def test_toml_part_files_load(tmp_path):
    from throwmap.io.config import load_config

    files = [(page, b) for page, b in all_blocks("toml") if "[part]" in b]
    assert files
    for i, (page, text) in enumerate(files):
        path = tmp_path / f"part{i}.toml"
        path.write_text(text, encoding="utf-8")
        loaded = load_config(path)
        assert loaded.part.n_sides >= 3, page


@functools.lru_cache(maxsize=None)
def _help(command: str) -> str:
    from throwmap.cli.app import app

    res = CliRunner().invoke(app, [*command.split(), "--help"], terminal_width=200,
                             env={"COLUMNS": "200", "NO_COLOR": "1"})
    assert res.exit_code == 0, f"`throwmap {command} --help` fails: {res.output}"
    return res.output


@functools.lru_cache(maxsize=None)
def _subcommands(command: str) -> frozenset[str]:
    """The subcommands of a command group (empty for a plain command)."""
    import typer.main

    from throwmap.cli.app import app

    group = typer.main.get_command(app).commands[command]
    return frozenset(getattr(group, "commands", {}) or {})


def _has_option(help_text: str, opt: str) -> bool:
    return re.search(rf"(?<![\w-]){re.escape(opt)}(?![\w-])", help_text) is not None


def _takes_value(help_text: str, opt: str) -> bool:
    """Whether ``opt`` takes a value, from the help's type column: the first word after the option's spellings is a
    type (``<int>``, ``INTEGER``) for an option that takes one; a flag has none (or ``<bool>``, ``BOOLEAN``)."""
    m = re.search(rf"(?<![\w-]){re.escape(opt)}(?![\w-])(?:[,/]?\s*-{{1,2}}[\w-]+)*\s+(\S+)", help_text)
    return m is not None and bool(re.fullmatch(r"<\w+>|[A-Z]{3,}", m.group(1))) and m.group(1) not in ("<bool>",
                                                                                                   "BOOLEAN")


def test_shell_commands_exist_with_their_options():
    commands = [(page, c) for page, b in all_blocks("bash") for c in shell_commands(b)]
    assert commands
    seen = set()
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    for page, words in commands:
        where = f"{page}: {' '.join(words)}"
        if words[0] == "make":
            assert re.search(rf"^{re.escape(words[1])}:", makefile, flags=re.M), f"no make target {words[1]!r} ({page})"
            continue
        if words[0] in ("git", "cd"):  # plain shell around a command
            continue
        if words[0] in ("python", "python3") and words[1].endswith(".py"):
            assert (ROOT / words[1]).is_file(), f"no script {words[1]} ({page})"
            continue
        assert words[0] == "throwmap", f"unexpected command in a bash block: {where}"
        cmd = words[1]
        rest = words[2:]
        if rest and rest[0] in _subcommands(cmd):  # a group: check the subcommand's own options
            cmd, rest = f"{cmd} {rest[0]}", rest[1:]
        text = _help(cmd)
        for k, w in enumerate(rest):
            if w.startswith("-") and not re.fullmatch(r"-?\d+(\.\d+)?", w):
                assert _has_option(text, w.split("=")[0]), f"`throwmap {cmd}` has no option {w} ({page})"
                if _takes_value(text, w) and "=" not in w:
                    nxt = rest[k + 1] if k + 1 < len(rest) else ""
                    assert nxt and not (nxt.startswith("-") and not re.fullmatch(r"-?\d+(\.\d+)?", nxt)), \
                        f"`throwmap {cmd} … {w}` is shown without its value ({page})"
        seen.add(cmd.split()[0])
    assert {"throw", "iterate", "compare", "validate", "animate", "demo", "limitset", "basins", "funnels", "map",
            "feeder"} <= seen


def test_a_text_block_after_a_python_block_is_its_output():
    page = "```python\nprint(1)\n```\nprints\n```text\n1\n```\n```bash\nls\n```\n```text\nx\n```\n```python\nf()\n```\n"
    assert printed(page) == {0: "1\n"}


def test_the_checker_catches_a_missing_option_and_a_missing_import():
    assert not _has_option(_help("funnels"), "--x-maxx") and _has_option(_help("funnels"), "--x-max")
    namespace: dict = {}
    with pytest.raises(NameError):
        exec(blocks("python", "```python\nx = np.zeros(3)\n```\n")[0], namespace)
    assert _takes_value(_help("funnels"), "--plot") and not _takes_value(_help("funnels"), "--json")
    assert _takes_value(_help("iterate"), "-n")
    assert shell_commands("throwmap funnels --omega 3,4 [--plot f.png]  # note\n") == \
        [["throwmap", "funnels", "--omega", "3,4", "--plot", "f.png"]]


def _links(text: str) -> list[str]:
    """The targets of every Markdown link and image outside code, anchors and web addresses left out."""
    prose = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    prose = re.sub(r"`[^`\n]*`", "", prose)
    return [t for t in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", prose) if not re.match(r"[a-z]+://|mailto:", t)]


def test_the_readme_links_nothing_outside_the_repository():
    text = README.read_text(encoding="utf-8")
    assert "shared/paper" not in text and "../" not in text
    for target in _links(text):
        assert (ROOT / target).exists(), f"README links to {target}, which is not in the repository"


@pytest.mark.parametrize("page", [rel(p) for p in PAGES[1:]])
def test_the_docs_link_only_pages_and_files_of_the_site(page):
    """A page's links resolve from the page's own folder to a file inside ``docs/`` (the site has nothing else)."""
    text = (ROOT / page).read_text(encoding="utf-8")
    assert "shared/paper" not in text
    for target in _links(text):
        path = ((ROOT / page).parent / target).resolve()
        assert path.is_relative_to(DOCS.resolve()), f"{page} links to {target}, outside docs/"
        assert path.exists(), f"{page} links to {target}, which is not there"


def test_the_demo_files_listed_are_the_files_it_writes():
    """The README's table of `make demo` outputs names exactly :data:`throwmap.studies.demo.OUTPUTS`
    (which ``run_demo`` checks against what it wrote)."""
    from throwmap.studies.demo import OUTPUTS

    text = README.read_text(encoding="utf-8")
    section = text[text.index("`make demo` (= `throwmap demo --out out`)"):]
    section = section[:section.index("\n## ")]
    listed = re.findall(r"^\| `([\w.]+)` \|", section, flags=re.M)
    assert sorted(listed) == sorted(OUTPUTS)


def test_the_documented_part_file_is_shipped_in_examples():
    """The part file the page on part files shows is ``examples/part.toml`` (commands use it), byte for byte after
    its comment line."""
    text = (ROOT / "examples" / "part.toml").read_text(encoding="utf-8")
    block = next(b for b in page_blocks("toml", rel(PART_FILE_PAGE)) if "[part]" in b and "point_masses" in b)
    assert text.split("\n", 1)[1].strip() == block.strip()
