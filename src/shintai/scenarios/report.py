"""REPORT.md and index.html for ``shintai reproduce``.

At the top, a summary per thesis: how many of its experiments (the coverage registry's rows,
:mod:`shintai.scenarios.coverage`) are reproduced, reproduced with a stated difference, not reproduced, or
not yet built. Then one row per thesis experiment with its status and one line of reason, the thesis's
result and the scenarios that reproduce it; then one row per scenario: thesis values beside ours (mean ± std
over seeds for a stochastic scenario), every check with its kind, the exact command and the git commit that
produced it, plots and video inline; then each scenario's notes.

The report is built from the ``metrics.json`` files on disk, so a run that stopped half-way still reports
every scenario that finished (and lists the others as not run). Rows whose scenarios were not part of this
report are listed as not run here and left out of the counts.
"""

from __future__ import annotations

import html
import json
from pathlib import Path
from typing import Any

from shintai.scenarios.coverage import SEEDS, STATUSES, RowStatus, all_rows, status_of
from shintai.scenarios.registry import SCENARIOS, get

NOT_RUN_HERE = "not run here"


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
                            "covers": list(sc.covers), "ok": False, "error": "not run (stopped before it finished)"})
    return results


def fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, list):
        return "[" + ", ".join(fmt(v) for v in value[:6]) + (", …]" if len(value) > 6 else "]")
    return "—" if value is None else str(value)


def ours(result: dict[str, Any], metric: str) -> str:
    """Our value of a metric: ``mean ± std (n seeds)`` for a result combined over seeds."""
    value = result.get("metrics", {}).get(metric)
    std = result.get("metrics_std", {}).get(metric)
    if std is None:
        return fmt(value)
    return f"{fmt(value)} ± {fmt(std)} ({len(result.get('seeds', []))} seeds)"


def thesis_vs_ours(result: dict[str, Any]) -> list[tuple[str, str, str, str]]:
    """Rows (quantity, thesis value with its place, ours, metric) for one scenario."""
    rows = []
    for name, ref in result.get("thesis", {}).items():
        metric = ref.get("metric")
        rows.append((name, f"{fmt(ref['value'])} ({ref['where']})", ours(result, metric) if metric else "—",
                     metric or ""))
    return rows


def cell(text: str) -> str:
    """Text for one Markdown table cell."""
    return text.replace("|", "\\|").replace("\n", " ")


def status(result: dict[str, Any]) -> str:
    if "error" in result:
        return "error"
    return "pass" if result.get("ok") else "FAIL"


def check_text(c: dict[str, Any]) -> str:
    kind = {"reproduction": "R", "consistency": "C"}.get(c.get("kind"), "?")
    held = f", held in {c['held_in']} seeds" if "held_in" in c else ""
    return f"{'✓' if c['ok'] else '✗'} [{kind}] {c['name']} {c['op']} {fmt(c['threshold'])} (ours {fmt(c['value'])}{held})"


def checks_text(result: dict[str, Any]) -> str:
    if "error" in result:
        return result["error"]
    return "; ".join(check_text(c) for c in result.get("checks", [])) or "no checks"


def notes_text(result: dict[str, Any]) -> str:
    """The scenario's account (``notes``) and what the run itself added (``extra.notes``)."""
    extra = result.get("extra", {}).get("notes")
    return "\n\n".join(t for t in (result.get("notes"), extra if isinstance(extra, str) else None) if t)


def provenance(result: dict[str, Any]) -> str:
    commit = result.get("commit") or "unknown commit"
    return f"`{result.get('command', 'shintai run ' + result['scenario'])}` at {commit}"


def coverage(results: list[dict[str, Any]]) -> list[RowStatus]:
    """The status of every coverage row, from the results in this report (rows whose scenarios are not in
    it get the status :data:`NOT_RUN_HERE`)."""
    by_id = {r["scenario"]: r for r in results}
    covering = {sid: tuple(sc.covers) for sid, sc in SCENARIOS.items()}
    for r in results:  # the covers a result was produced with
        covering[r["scenario"]] = tuple(r.get("covers", covering.get(r["scenario"], ())))
    statuses = []
    for row in all_rows().values():
        ids = [sid for sid, keys in covering.items() if row.key in keys]
        if ids and not all(sid in by_id for sid in ids):
            statuses.append(RowStatus(row, NOT_RUN_HERE, f"not in this report: {', '.join(ids)}", tuple(ids), []))
        else:
            statuses.append(status_of(row, by_id, {sid: covering[sid] for sid in ids}))
    return statuses


def summary_counts(statuses: list[RowStatus]) -> dict[str, dict[str, int]]:
    """``{seed: {status: n}}`` over the rows of this report (not-run-here rows are not counted)."""
    out = {seed: dict.fromkeys(STATUSES, 0) for seed in SEEDS}
    for s in statuses:
        if s.status != NOT_RUN_HERE:
            out[s.row.seed][s.status] += 1
    return out


def write_markdown(out: Path, results: list[dict[str, Any]], statuses: list[RowStatus], title: str) -> Path:
    passed = sum(status(r) == "pass" for r in results)
    counts = summary_counts(statuses)
    lines = [f"# {title}", "", "## Summary per thesis", "",
             "Thesis experiments (every experiment and result figure/table has a row) by status; only reproduction "
             "checks decide.", "", "| thesis | " + " | ".join(STATUSES) + " |", "|---|" + "---|" * len(STATUSES)]
    for seed, name in SEEDS.items():
        lines.append(f"| {seed} {name} | " + " | ".join(str(counts[seed][s]) for s in STATUSES) + " |")
    lines += ["", "## Thesis experiments", "", "| row | where | thesis result | scenarios | status | reason |",
              "|---|---|---|---|---|---|"]
    for s in statuses:
        lines.append(f"| {s.row.key} | {cell(s.row.where)} | {cell(s.row.result)} | {', '.join(s.scenarios) or '—'} | "
                     f"{s.status} | {cell(s.reason)} |")
    lines += ["", "## Scenarios", "", f"{passed} of {len(results)} scenarios pass all their checks "
              "([R] reproduction, [C] consistency).", "",
              "| experiment | source | thesis value | ours | checks | status | command |",
              "|---|---|---|---|---|---|---|"]
    for r in results:
        rows = thesis_vs_ours(r) or [("", "—", "—", "")]
        thesis = "<br>".join(f"{q}: {t}" if q else t for q, t, _, _ in rows)
        mine = "<br>".join(f"{m}: {o}" if m else o for _, _, o, m in rows)
        lines.append(f"| [{r['scenario']}]({r['scenario']}/metrics.json) | {r['source']} | {thesis} | {mine} | "
                     f"{checks_text(r)} | {status(r)} | {provenance(r)} |")
    lines += ["", "Thesis values are quoted, never used as our numbers: every 'ours' is computed from the "
              "simulation. A ✗ is reported as it is; see each scenario's metrics.json for the basis of its checks.",
              "", "## Notes", "", "Per experiment, what it reproduces, and what does not and why (the scenario's "
              "own account, also in its metrics.json `notes`)."]
    for r in results:
        if notes_text(r):
            lines += ["", f"### {r['scenario']} ({status(r)})", "", notes_text(r)]
    path = out / "REPORT.md"
    path.write_text("\n".join(lines) + "\n")
    return path


# The page checks itself once loaded (a headless browser reads the result from the DOM): every image decoded,
# every video playable, and the summary counts as written.
SELF_CHECK = """<script>
window.addEventListener('load', () => {
  const imgs = [...document.images];
  const vids = [...document.querySelectorAll('video')];
  const check = document.getElementById('selfcheck');
  const videoState = () => vids.filter(v => v.readyState >= 1 && !v.error).length;
  const finish = () => {
    check.dataset.images = imgs.length;
    check.dataset.imagesOk = imgs.filter(i => i.complete && i.naturalWidth > 0).length;
    check.dataset.videos = vids.length;
    check.dataset.videosOk = videoState();
    check.dataset.done = '1';
  };
  if (!vids.length) { finish(); return; }
  let left = vids.length;
  vids.forEach(v => { const d = () => { if (--left === 0) finish(); };
    if (v.readyState >= 1 || v.error) d(); else { v.addEventListener('loadedmetadata', d, {once: true});
    v.addEventListener('error', d, {once: true}); } });
  setTimeout(finish, 8000);
});
</script>"""


def write_html(out: Path, results: list[dict[str, Any]], statuses: list[RowStatus], title: str) -> Path:
    e = html.escape
    counts = summary_counts(statuses)
    summary = "".join(
        f'<tr><td>{e(seed)} {e(name)}</td>' + "".join(
            f'<td class="count" data-seed="{seed}" data-status="{e(s)}">{counts[seed][s]}</td>' for s in STATUSES)
        + "</tr>" for seed, name in SEEDS.items())
    row_html = "".join(
        f'<tr class="row {e(s.status.replace(" ", "-"))}"><td>{e(s.row.key)}</td><td>{e(s.row.where)}<br>'
        f'<small>{e(s.row.what)}</small></td><td>{e(s.row.result)}</td><td>{e(", ".join(s.scenarios) or "—")}</td>'
        f'<td class="status">{e(s.status)}</td><td>{e(s.reason)}</td></tr>' for s in statuses)
    rows = []
    for r in results:
        sid = r["scenario"]
        pngs = sorted((out / sid).glob("*.png")) if (out / sid).exists() else []
        imgs = "".join(f'<a href="{e(sid)}/{e(p.name)}"><img src="{e(sid)}/{e(p.name)}" width="260" '
                       f'alt="{e(p.stem)}"></a>' for p in pngs)
        videos = sorted((out / sid).glob("*.mp4")) if (out / sid).exists() else []
        video = "".join(f'<br><video src="{e(sid)}/{e(v.name)}" width="320" controls preload="metadata"></video>'
                        for v in videos)
        thesis = "<br>".join(e(f"{q}: {t}") for q, t, _, _ in thesis_vs_ours(r)) or "—"
        mine = "<br>".join(e(f"{m}: {o}") for _, _, o, m in thesis_vs_ours(r) if m) or "—"
        checks = "<br>".join(e(c) for c in checks_text(r).split("; "))
        notes = (f'<details><summary>notes</summary><pre>{e(notes_text(r))}</pre></details>'
                 if notes_text(r) else "")
        rows.append(f'<tr class="{status(r).lower()}"><td><a href="{e(sid)}/metrics.json">{e(sid)}</a><br><small>'
                    f'{e(r["source"])}</small>{notes}</td><td>{thesis}</td><td>{mine}</td><td>{checks}</td>'
                    f'<td>{e(status(r))}</td><td><code>{e(provenance(r))}</code></td><td>{imgs}{video}</td></tr>')
    passed = sum(status(r) == "pass" for r in results)
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>{e(title)}</title>
<style>body{{font-family:sans-serif;margin:1.5em}}table{{border-collapse:collapse;margin-bottom:1.5em}}
td,th{{border:1px solid #ccc;padding:6px;vertical-align:top;font-size:13px}}
tr.pass td:nth-child(5){{color:#080}}tr.fail td:nth-child(5),tr.error td:nth-child(5){{color:#b00;font-weight:bold}}
tr.reproduced .status{{color:#080}}tr.not-reproduced .status{{color:#b00}}tr.not-yet-built .status{{color:#888}}tr.not-comparable .status{{color:#a60}}
img{{margin:2px;border:1px solid #ddd}}pre{{white-space:pre-wrap;max-width:38em;font-size:12px}}
code{{font-size:11px}}</style></head><body>
<h1>{e(title)}</h1><div id="selfcheck"></div>
<h2>Summary per thesis</h2><p>Thesis experiments by status; only reproduction checks decide.</p>
<table id="summary"><tr><th>thesis</th>{''.join(f'<th>{e(s)}</th>' for s in STATUSES)}</tr>{summary}</table>
<h2>Thesis experiments</h2>
<table id="rows"><tr><th>row</th><th>where</th><th>thesis result</th><th>scenarios</th><th>status</th><th>reason</th></tr>
{row_html}</table>
<h2>Scenarios</h2><p>{passed} of {len(results)} scenarios pass all their checks ([R] reproduction, [C] consistency).
Thesis values are quoted beside ours; ours are computed from the simulation.</p>
<table id="scenarios"><tr><th>experiment</th><th>thesis value</th><th>ours</th><th>checks</th><th>status</th>
<th>command</th><th>pictures</th></tr>
{''.join(rows)}</table>{SELF_CHECK}</body></html>
"""
    path = out / "index.html"
    path.write_text(page)
    return path


README_BEGIN = "<!-- reproduction:begin"
README_END = "<!-- reproduction:end -->"


def readme_section(results: list[dict[str, Any]], statuses: list[RowStatus]) -> str:
    """The README's reproduction table: the summary per thesis and one line per thesis experiment (status,
    reason, our reproduction checks), from the same statuses as REPORT.md — so the two agree."""
    counts = summary_counts(statuses)
    commits = sorted({r.get("commit") for r in results if r.get("commit")})
    lines = [f"{README_BEGIN} (written by scripts/readme_table.py from `shintai reproduce` at "
             f"{', '.join(commits) or 'an unknown commit'}) -->", "",
             "| thesis | " + " | ".join(STATUSES) + " |", "|---|" + "---|" * len(STATUSES)]
    for seed, name in SEEDS.items():
        lines.append(f"| {seed} {name} | " + " | ".join(str(counts[seed][s]) for s in STATUSES) + " |")
    lines += ["", "| row | where | scenarios | status | why | our reproduction checks |", "|---|---|---|---|---|---|"]
    for s in statuses:
        checks = "; ".join(f"{'✓' if c['ok'] else '✗'} {c['name']} {fmt(c['value'])} {c['op']} {fmt(c['threshold'])}"
                           for c in s.checks) or "—"
        lines.append(f"| {s.row.key} | {cell(s.row.where)} | {', '.join(f'`{i}`' for i in s.scenarios) or '—'} | "
                     f"{s.status} | {cell(s.reason)} | {cell(checks)} |")
    return "\n".join(lines + ["", README_END])


def write_report(out: Path, ids: list[str], title: str = "shintai reproduction report") -> list[dict[str, Any]]:
    results = load_results(out, ids)
    statuses = coverage(results)
    write_markdown(out, results, statuses, title)
    write_html(out, results, statuses, title)
    return results
