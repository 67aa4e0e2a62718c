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
from pathlib import Path

__all__ = ["markdown_report", "html_report", "experiment_rows"]


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
            throws = f"{t.get('median', float('nan')):.0f} / {t.get('p90', float('nan')):.0f}" if t else ""
        goal = "" if e.get("goal") is None else f"≥ {100 * e['goal']:g} %"
        rows.append([f"{e['title']} ({e['section']}; `experiment {e['experiment']}`)", draft, ours, goal, fails,
                     throws])
    return rows


HEAD = ["experiment", "draft (hardware, Wilson 95 %)", "ours (engine, Wilson 95 %)", "goal", "failures by kind",
        "throws median / p90 (feeding: to capture)"]


def _numbers(d: dict) -> str:
    return json.dumps(d, default=str, ensure_ascii=False, indent=1)[:4000]


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
            lines += [f"### {e['title']} (`experiment {e['experiment']}`, seed {o['seed']})", "", "```json",
                      json.dumps(o["parameters"], default=str, ensure_ascii=False, indent=1), "```", ""]
    for f in rep.figures:
        if f.get("parameters"):
            lines += [f"- `{f['key']}`: `{json.dumps(f['parameters'], default=str, ensure_ascii=False)[:600]}`"]
    lines += ["", "## Errata: where we depart from the draft", "", rep.errata.strip(), ""]
    return "\n".join(lines) + "\n"


def _img(path: Path) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f'<img alt="{html.escape(path.stem)}" src="data:image/png;base64,{data}" style="max-width:100%">'


def _md_inline(text: str) -> str:
    """Markdown lines to HTML paragraphs and lists (bold, code): enough for the errata text."""
    import re

    out, in_list = [], False
    for raw in text.splitlines():
        line = html.escape(raw)
        line = re.sub(r"\*\*(.+?)\*\*", r"<b>\1</b>", line)
        line = re.sub(r"`(.+?)`", r"<code>\1</code>", line)
        m = re.match(r"^\s*(\d+)\.\s+(.*)$", line)
        if m:
            if not in_list:
                out.append("<ol>")
                in_list = True
            out.append(f"<li value=\"{m.group(1)}\">{m.group(2)}")
        elif line.strip():
            out.append(line if in_list else f"<p>{line}</p>")
        elif in_list:
            out.append("")
    if in_list:
        out.append("</ol>")
    return "\n".join(out)


def html_report(rep, out) -> str:
    out = Path(out)
    esc = html.escape
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
             f"<title>throwmap {esc(rep.version)}: the draft reproduced</title>",
             "<style>body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}"
             "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:4px 6px;font-size:13px}"
             "pre{background:#f4f4f4;padding:6px;font-size:12px;overflow-x:auto}</style></head><body>",
             f"<h1>The draft reproduced (throwmap {esc(rep.version)})</h1>",
             f"<p>Size <code>{esc(rep.size)}</code>, started {esc(rep.started)} UTC, {rep.elapsed_s / 60:.1f} min. "
             "Units SI. The draft's numbers are its hardware results (20 trials); ours are engine simulations.</p>"]
    if rep.failed:
        parts.append(f"<p><b>Failed pieces:</b> {esc(', '.join(rep.failed))}</p>")
    parts.append("<h2>The experiments</h2><table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in HEAD) + "</tr>")
    for r in experiment_rows(rep):
        parts.append("<tr>" + "".join(f"<td>{esc(c).replace('**', '')}</td>" for c in r) + "</tr>")
    parts.append("</table><h2>Figures</h2>")
    for f in rep.figures:
        parts.append(f"<h3>{esc(f['draft'])} analogue: <code>{esc(f['key'])}</code></h3>")
        if f.get("error"):
            parts.append(f"<p><b>failed</b>: {esc(f['error'])}</p>")
            continue
        p = out / f["file"]
        parts.append(_img(p) if p.is_file() else f"<p>missing file {esc(str(p))}</p>")
        parts.append(f"<p>{esc(f['caption'])}</p>")
        if f.get("numbers"):
            parts.append(f"<details><summary>numbers</summary><pre>{esc(_numbers(f['numbers']))}</pre></details>")
    parts.append("<h2>Parameters (every value the draft leaves blank is chosen here)</h2>")
    for e in rep.experiments:
        o = e.get("ours")
        if o:
            parts.append(f"<details><summary>{esc(e['title'])} (experiment {esc(e['experiment'])}, seed {o['seed']})"
                         f"</summary><pre>{esc(json.dumps(o['parameters'], default=str, ensure_ascii=False, indent=1))}"
                         "</pre></details>")
    parts.append("<h2>Errata: where we depart from the draft</h2>")
    parts.append(_md_inline(rep.errata))
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"
