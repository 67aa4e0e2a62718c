"""The reproduction's reports: Markdown (figures linked) and one self-contained HTML file (figures inline as PNG
data, no network), both from a :class:`~throwmap.reproduce.run.Reproduction`.

Sections: the experiments table (the draft's hardware result, 20 trials, against ours with Wilson 95 % intervals,
the goal rate, failures by kind), the figures with captions and the numbers they show, the parameters each
experiment used (every value the draft leaves blank is one of them), and the errata (where we depart from the
draft).
"""

from __future__ import annotations

import base64
import html
import json
import math
from pathlib import Path

from ..serial import json_ready

__all__ = ["markdown_report", "html_report", "experiment_rows", "parameter_rows"]


def _pct(k, n) -> str:
    return "n/a" if not n else f"{100 * k / n:.1f} %"


def _ci(ci) -> str:
    return f"[{100 * ci[0]:.1f}, {100 * ci[1]:.1f}] %"


def experiment_rows(rep) -> list[list[str]]:
    """The experiments table as text cells: experiment, draft, ours, goal, failures, throws (median / p90)."""
    rows = []
    for e in rep.experiments:
        d = e["draft"]
        draft = f"{d['successes']}/{d['n']} = {_pct(d['successes'], d['n'])} {_ci(d['ci95'])}"
        o = e.get("ours")
        if e.get("error") or o is None:
            ours, fails, throws = f"**failed**: {e.get('error')}", "", ""
        else:
            ours = f"{o['successes']}/{o['n']} = {_pct(o['successes'], o['n'])} {_ci(o['ci95'])}"
            fails = ", ".join(f"{k} {v}" for k, v in sorted(o["failures"].items(), key=lambda kv: -kv[1])) or "none"
            t = o.get("throws") or {}
            med, p90 = t.get("median"), t.get("p90")
            throws = (f"{med:.0f} / {p90:.0f}" if all(isinstance(v, (int, float)) and math.isfinite(v)
                                                      for v in (med, p90)) else "")
        goal = "" if e.get("goal") is None else f"≥ {100 * e['goal']:g} %"
        rows.append([f"{e['title']} ({e['section']}; `experiment {e['experiment']}`)", draft, ours, goal, fails,
                     throws])
    return rows


HEAD = ["experiment", "draft (hardware, Wilson 95 %)", "ours (engine, Wilson 95 %)", "goal", "failures by kind",
        "throws median / p90 (feeding: to capture)"]


LIST_MAX = 12
"""Lists longer than this are shown by their first :data:`LIST_MAX` items and a count of the rest."""


def _trim(obj):
    """``obj`` made JSON-ready (non-finite numbers → null) with long lists cut to :data:`LIST_MAX` items and a note."""
    if isinstance(obj, dict):
        return {k: _trim(v) for k, v in obj.items()}
    if isinstance(obj, list):
        head = [_trim(v) for v in obj[:LIST_MAX]]
        return head + ([f"… {len(obj) - LIST_MAX} more"] if len(obj) > LIST_MAX else [])
    if isinstance(obj, float):
        return float(f"{obj:.6g}")
    return obj


def _numbers(d: dict) -> str:
    """The numbers behind a figure as valid, readable JSON: null where a number is not finite, 6 significant
    digits, long lists cut (every value that was cut says how many items it lost)."""
    return json.dumps(_trim(json_ready(d)), ensure_ascii=False, indent=1, allow_nan=False)


def _value(v) -> str:
    """One parameter value as text: numbers to 4 significant digits, ∞ for infinity, lists in brackets."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return "∞" if v == math.inf else "−∞" if v == -math.inf else "n/a" if v != v else f"{v:.4g}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if v is None:
        return "—"
    return str(v)


def parameter_rows(d: dict, prefix: str = "") -> list[tuple[str, str]]:
    """A nested parameters dict as ``(dotted name, value text)`` rows (SI: the name's suffix says the unit)."""
    rows = []
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            rows += parameter_rows(v, name + ".")
        else:
            rows.append((name, _value(v)))
    return rows


def _md_table(rows: list[tuple[str, str]]) -> list[str]:
    cell = lambda t: str(t).replace("|", "\\|")  # noqa: E731 - a pipe inside a cell would end it
    return ["| parameter | value |", "|---|---|"] + [f"| `{cell(a)}` | {cell(b)} |" for a, b in rows]


def markdown_report(rep) -> str:
    lines = [f"# The draft reproduced (throwmap {rep.version})", "",
             f"Size `{rep.size}`, started {rep.started} UTC, {rep.elapsed_s / 60:.1f} min on {rep.workers or 'all'} "
             f"worker(s). Units SI. The draft's numbers are its hardware results; ours are engine (pymunk) "
             f"simulations of the same experiments, each trial from a random drop with noise.", ""]
    if rep.failed:
        lines += [f"**Failed pieces:** {', '.join(rep.failed)} (reasons below).", ""]
    lines += ["## The experiments", "", "| " + " | ".join(HEAD) + " |", "|" + "---|" * len(HEAD)]
    lines += ["| " + " | ".join(r) + " |" for r in experiment_rows(rep)]
    lines += ["", "## Figures", ""]
    for f in rep.figures:
        lines.append(f"### {f['draft']} analogue: `{f['key']}`")
        lines.append("")
        if f.get("error"):
            lines.append(f"**failed**: {f['error']}")
        else:
            lines.append(f"![{f['draft']}]({f['file']})")
            lines.append("")
            lines.append(f"{f['caption']} ({f['seconds']:.0f} s)")
            if f.get("numbers"):
                lines += ["", "```json", _numbers(f["numbers"]), "```"]
        lines.append("")
    lines += ["## Parameters (every value the draft leaves blank is chosen here)", ""]
    for e in rep.experiments:
        o = e.get("ours")
        if o:
            lines += [f"### {e['title']} (`experiment {e['experiment']}`, seed {o['seed']})", ""]
            lines += _md_table(parameter_rows(json_ready(o["parameters"]))) + [""]
    for f in rep.figures:
        if f.get("parameters"):
            lines += [f"### Figure `{f['key']}`", ""] + _md_table(parameter_rows(json_ready(f["parameters"]))) + [""]
    lines += ["", "## Errata: where we depart from the draft", "", rep.errata.strip(), ""]
    return "\n".join(lines) + "\n"


def _img(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f"data:image/png;base64,{data}"


STYLE = ("body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}"
         "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:4px 6px;font-size:13px}"
         "pre{background:#f4f4f4;padding:6px;font-size:12px;overflow-x:auto}img{max-width:100%}")


def html_report(rep, out) -> str:
    """The Markdown report rendered to one self-contained HTML page (Python-Markdown: tables, code blocks), its
    figures inlined as PNG data (a missing figure file is named in its place)."""
    import re

    import markdown

    out = Path(out)

    def inline(m):
        p = out / m.group(2)
        return f"![{m.group(1)}]({_img(p)})" if p.is_file() else f"*missing file {p}*"

    text = re.sub(r"!\[([^\]]*)\]\(([^)]+)\)", inline, markdown_report(rep))
    body = markdown.markdown(text, extensions=["tables", "fenced_code"], output_format="html")
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
            f"<title>throwmap {html.escape(rep.version)}: the draft reproduced</title><style>{STYLE}</style></head>"
            f"<body>\n{body}\n</body></html>\n")
