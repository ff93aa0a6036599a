"""REPORT.md and index.html for ``shintai reproduce``: per experiment, the thesis value, ours, the checks.

The report is built from the ``metrics.json`` files on disk, so a run that stopped half-way still
reports every scenario that finished (and lists the others as not run).
"""

from __future__ import annotations

import html
import json
from pathlib import Path
from typing import Any

from shintai.scenarios.registry import get


def load_results(out: Path, ids: list[str]) -> list[dict[str, Any]]:
    """The metrics.json of each scenario under ``out/<id>``; a stub for those that did not finish."""
    results = []
    for sid in ids:
        path = out / sid / "metrics.json"
        if path.exists():
            results.append(json.loads(path.read_text()))
        else:
            sc = get(sid)
            results.append({"scenario": sid, "source": sc.source, "metrics": {}, "checks": [], "thesis": {},
                            "ok": False, "error": "not run (stopped before it finished)"})
    return results


def fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, list):
        return "[" + ", ".join(fmt(v) for v in value[:6]) + (", …]" if len(value) > 6 else "]")
    return "—" if value is None else str(value)


def thesis_vs_ours(result: dict[str, Any]) -> list[tuple[str, str, str, str]]:
    """Rows (quantity, thesis value with its place, ours, agreement note) for one scenario."""
    rows = []
    for name, ref in result.get("thesis", {}).items():
        metric = ref.get("metric")
        ours = result.get("metrics", {}).get(metric) if metric else None
        rows.append((name, f"{fmt(ref['value'])} ({ref['where']})", fmt(ours) if metric else "—",
                     metric or ""))
    return rows


def status(result: dict[str, Any]) -> str:
    if "error" in result:
        return "error"
    return "pass" if result.get("ok") else "FAIL"


def checks_text(result: dict[str, Any]) -> str:
    if "error" in result:
        return result["error"]
    return "; ".join(f"{'✓' if c['ok'] else '✗'} {c['name']} {c['op']} {fmt(c['threshold'])} "
                     f"(ours {fmt(c['value'])})" for c in result.get("checks", [])) or "no checks"


def notes_text(result: dict[str, Any]) -> str:
    """The scenario's account (``notes``) and what the run itself added (``extra.notes``)."""
    extra = result.get("extra", {}).get("notes")
    return "\n\n".join(t for t in (result.get("notes"), extra if isinstance(extra, str) else None) if t)


def write_markdown(out: Path, results: list[dict[str, Any]], title: str) -> Path:
    passed = sum(status(r) == "pass" for r in results)
    lines = [f"# {title}", "", f"{passed} of {len(results)} scenarios pass all their checks.", "",
             "| experiment | source | thesis value | ours | checks | status |",
             "|---|---|---|---|---|---|"]
    for r in results:
        rows = thesis_vs_ours(r) or [("", "—", "—", "")]
        thesis = "<br>".join(f"{q}: {t}" if q else t for q, t, _, _ in rows)
        ours = "<br>".join(f"{m}: {o}" if m else o for _, _, o, m in rows)
        lines.append(f"| [{r['scenario']}]({r['scenario']}/metrics.json) | {r['source']} | {thesis} | {ours} | "
                     f"{checks_text(r)} | {status(r)} |")
    lines += ["", "Thesis values are quoted, never used as our numbers: every 'ours' is computed from the "
              "simulation. A ✗ is reported as it is; see each scenario's metrics.json for the basis of its checks.",
              "", "## Notes", "", "Per experiment, its model, what reproduces, and what does not and why (the scenario's "
              "own account, also in its metrics.json `notes`)."]
    for r in results:
        if notes_text(r):
            lines += ["", f"### {r['scenario']} ({status(r)})", "", notes_text(r)]
    path = out / "REPORT.md"
    path.write_text("\n".join(lines) + "\n")
    return path


def write_html(out: Path, results: list[dict[str, Any]], title: str) -> Path:
    e = html.escape
    rows = []
    for r in results:
        sid = r["scenario"]
        pngs = sorted((out / sid).glob("*.png")) if (out / sid).exists() else []
        imgs = "".join(f'<a href="{e(sid)}/{e(p.name)}"><img src="{e(sid)}/{e(p.name)}" width="260"></a>'
                       for p in pngs)
        video = (f'<br><video src="{e(sid)}/video.mp4" width="320" controls></video>'
                 if (out / sid / "video.mp4").exists() else "")
        thesis = "<br>".join(e(f"{q}: {t}") for q, t, _, _ in thesis_vs_ours(r)) or "—"
        ours = "<br>".join(e(f"{m}: {o}") for _, _, o, m in thesis_vs_ours(r) if m) or "—"
        checks = "<br>".join(e(c) for c in checks_text(r).split("; "))
        cls = status(r).lower()
        notes = (f'<details><summary>notes</summary><pre>{e(notes_text(r))}</pre></details>'
                 if notes_text(r) else "")
        rows.append(f'<tr class="{cls}"><td><a href="{e(sid)}/metrics.json">{e(sid)}</a><br><small>{e(r["source"])}'
                    f'</small>{notes}</td><td>{thesis}</td><td>{ours}</td><td>{checks}</td><td>{e(status(r))}</td>'
                    f"<td>{imgs}{video}</td></tr>")
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>{e(title)}</title>
<style>body{{font-family:sans-serif;margin:1.5em}}table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:6px;vertical-align:top;font-size:13px}}
tr.pass td:nth-child(5){{color:#080}}tr.fail td:nth-child(5),tr.error td:nth-child(5){{color:#b00;font-weight:bold}}
img{{margin:2px;border:1px solid #ddd}}pre{{white-space:pre-wrap;max-width:38em;font-size:12px}}</style></head><body>
<h1>{e(title)}</h1><p>{sum(status(r) == "pass" for r in results)} of {len(results)} scenarios pass all their checks.
Thesis values are quoted beside ours; ours are computed from the simulation.</p>
<table><tr><th>experiment</th><th>thesis value</th><th>ours</th><th>checks</th><th>status</th><th>pictures</th></tr>
{''.join(rows)}</table></body></html>
"""
    path = out / "index.html"
    path.write_text(page)
    return path


def write_report(out: Path, ids: list[str], title: str = "shintai reproduction report") -> list[dict[str, Any]]:
    results = load_results(out, ids)
    write_markdown(out, results, title)
    write_html(out, results, title)
    return results
