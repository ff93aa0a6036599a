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

from shintai.scenarios.coverage import NOT_REPRODUCED, SEEDS, STATUSES, RowStatus, all_rows, status_of
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
    by_id = {r["scenario"]: r for r in results if "demo_variant" not in r}  # a shortened run reproduces nothing
    shortened = {r["scenario"] for r in results if "demo_variant" in r}
    covering = {sid: tuple(sc.covers) for sid, sc in SCENARIOS.items()}
    for r in results:  # the covers a result was produced with
        covering[r["scenario"]] = tuple(r.get("covers", covering.get(r["scenario"], ())))
    statuses = []
    for row in all_rows().values():
        ids = [sid for sid, keys in covering.items() if row.key in keys]
        if ids and not all(sid in by_id for sid in ids):
            short = [sid for sid in ids if sid in shortened]
            reason = (f"only the demo variant of {', '.join(short)} here (not a reproduction)" if short
                      else f"not in this report: {', '.join(ids)}")
            statuses.append(RowStatus(row, NOT_RUN_HERE, reason, tuple(ids), []))
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


def body_lines(out: Path, results: list[dict[str, Any]], statuses: list[RowStatus]) -> list[str]:
    """One line per body, as the page's cards: its headline scenario, what it reproduces, its checks, its film."""
    by_body: dict[str, list[dict[str, Any]]] = {}
    for r in results:
        by_body.setdefault(body_of(r["scenario"]), []).append(r)
    lines = []
    for body in [b for b in BODIES if b in by_body] + sorted(b for b in by_body if b not in BODIES):
        r = headline(by_body[body], out)
        checks = r.get("checks", [])
        held = sum(c["ok"] for c in checks)
        state = ("the run erred" if "error" in r else f"{held}/{len(checks)} checks hold")
        why = "" if status(r) == "pass" else f" ({cell(first_sentence(why_failed(r, statuses)))})"
        films = [f"[{v.name}]({r['scenario']}/{v.name})" + (f", {video_caption(v.with_suffix('.json'))}"
                 if video_caption(v.with_suffix(".json")) else "") for v in media(out, r["scenario"])[0]]
        demo = " — demo variant, not a reproduction" if "demo_variant" in r else ""
        lines.append(f"- **{BODIES.get(body, (body,))[0]}** — `{r['scenario']}`: {summary_of(r['scenario'])} — "
                     f"{state}{why}{demo}" + (f" — film {'; '.join(films)}" if films else ""))
    return lines


def write_markdown(out: Path, results: list[dict[str, Any]], statuses: list[RowStatus], title: str) -> Path:
    passed = sum(status(r) == "pass" for r in results)
    counts = summary_counts(statuses)
    lines = [f"# {title}", "", "## Bodies", "", *body_lines(out, results, statuses), "", "## Summary per thesis", "",
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
# every video playable, the page's width (no horizontal scroll), and the summary counts as written.
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
    check.dataset.scrollWidth = document.documentElement.scrollWidth;
    check.dataset.clientWidth = document.documentElement.clientWidth;
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

# the bodies in the order a visitor meets them: the four theses' robots first, then the shared layers
BODIES = {"humanoid": ("Humanoid on vehicles", "000"), "snake": ("Wheeled snake", "001"),
          "spine": ("Variable-flexibility spine", "003"), "quadruped": ("Learning quadruped", "004"),
          "nervous": ("nervous, the middle layer", "003"), "core": ("Shared runtime", None),
          "evolve": ("Genetic algorithm", None), "sim": ("MuJoCo layer", None)}
LONG_TEXT = 220  # characters of a table cell shown before the rest folds into <details>

PAGE_STYLE = """body{font-family:sans-serif;margin:1.2em auto;max-width:1340px;padding:0 12px;line-height:1.35}
h1{margin:.2em 0}.lead{color:#444;margin:.3em 0 1em}
#cards{display:grid;grid-template-columns:repeat(auto-fill,minmax(310px,1fr));gap:14px;margin-bottom:1.5em}
.card{border:1px solid #ccc;border-radius:8px;padding:10px;background:#fafafa;min-width:0}
.card h2{font-size:17px;margin:0 0 2px}.card .thesis{font-size:12px;color:#666;margin:0 0 6px}
.card video,.card img.key{width:100%;height:100%;object-fit:contain;background:#000;display:block}
.card img.key{background:#fff}
.card .media{aspect-ratio:4/3;background:#eee;border-radius:4px;overflow:hidden}
.card p{font-size:13px;margin:6px 0}.card .caption{font-size:11px;color:#555;margin:2px 0 0}
.badge{display:inline-block;border-radius:10px;padding:1px 8px;font-size:12px;font-weight:bold}
.badge.pass{background:#dfd;color:#060}.badge.fail{background:#fdd;color:#900}.badge.error{background:#fdd;color:#900}
.badge.demo{background:#ffe9b3;color:#6a4b00}
.why{font-size:12px;color:#700;margin:4px 0}.why details{color:#333}code{font-size:11px;overflow-wrap:anywhere}
table{border-collapse:collapse;margin-bottom:1.5em;width:100%;table-layout:fixed}
td,th{border:1px solid #ccc;padding:5px;vertical-align:top;font-size:12.5px;overflow-wrap:anywhere;text-align:left}
table#summary{width:auto;table-layout:auto}
tr.pass td.st{color:#080}tr.fail td.st,tr.error td.st{color:#b00;font-weight:bold}
tr.reproduced .status{color:#080}tr.not-reproduced .status{color:#b00}tr.not-yet-built .status{color:#888}tr.not-comparable .status{color:#a60}
td img{max-width:100%;height:auto;margin:2px 0;border:1px solid #ddd}td video{max-width:100%}
details summary{cursor:pointer;color:#245}.notes{max-width:60em;font-size:13px}
.notes table.md{width:auto;table-layout:auto}pre{white-space:pre-wrap;font-size:12px}"""


def body_of(sid: str) -> str:
    return sid.split(".", 1)[0]


def folded(text: str) -> str:
    """Escaped text for a table cell; a long one (a Japanese quotation with its translation) shows its start
    and folds the rest into ``<details>``."""
    e = html.escape
    if len(text) <= LONG_TEXT:
        return e(text)
    cut = text.rfind(" ", 0, LONG_TEXT)
    cut = cut if cut > LONG_TEXT // 2 else LONG_TEXT
    return f"{e(text[:cut])} <details><summary>more</summary>{e(text[cut:])}</details>"


def video_caption(meta_path: Path) -> str:
    """What the film is: its time-lapse factor and how much sim time it shows (from ``video.json``)."""
    try:
        meta = json.loads(meta_path.read_text())
    except (OSError, ValueError):
        return ""
    speed, sim_s, fps, frames = meta.get("speed", 1), meta.get("sim_s"), meta.get("fps"), meta.get("frames")
    pace = "real time" if abs(speed - 1) < 1e-9 else f"×{speed:g} time-lapse"
    span = f", {sim_s:.3g} s of sim time in {frames / fps:.3g} s" if sim_s and fps and frames else ""
    return pace + span


def media(out: Path, sid: str) -> tuple[list[Path], list[Path]]:
    folder = out / sid
    if not folder.exists():
        return [], []
    return sorted(folder.glob("*.mp4")), sorted(folder.glob("*.png"))


def summary_of(sid: str) -> str:
    sc = SCENARIOS.get(sid)
    return sc.summary if sc is not None else ""


def why_failed(result: dict[str, Any], statuses: list[RowStatus]) -> str:
    """One line on why a scenario does not pass: its rows' declared reasons, else its failing checks."""
    if "error" in result:
        return result["error"]
    reasons = [s.reason for s in statuses if result["scenario"] in s.scenarios and s.status == NOT_REPRODUCED
               and s.reason]
    failed = [c for c in result.get("checks", []) if not c["ok"]]
    if "demo_variant" in result:  # what the variant measured and got wrong, not what it did not measure
        failed = [c for c in failed if c["value"] is not None and c["threshold"] is not None] or failed
    checks = "; ".join(f"{c['name']} {fmt(c['value'])} (needs {c['op']} {fmt(c['threshold'])})" for c in failed[:3])
    return "; ".join(dict.fromkeys(reasons)) or (f"fails {checks}" if checks else "")


def first_sentence(text: str, limit: int = 150) -> str:
    """``text`` up to its last sentence or clause end within ``limit`` characters (else its last word)."""
    if len(text) <= limit:
        return text
    ends = [i + 1 for i, ch in enumerate(text[:limit]) if ch in ".;:" and (i + 1 == len(text) or text[i + 1] == " ")]
    space = text.rfind(" ", 0, limit)
    cut = ends[-1] if ends and ends[-1] > 40 else (space if space > 40 else limit)
    return text[:cut].rstrip(" ;:") + " …"


def one_line(text: str, limit: int = 150) -> str:
    """Escaped: the first sentence (or clause) of ``text`` up to ``limit`` characters; the rest folds into
    ``<details>``."""
    e = html.escape
    if len(text) <= limit:
        return e(text)
    return f"{e(first_sentence(text, limit))} <details><summary>why, in full</summary>{e(text)}</details>"


KEY_PICTURE = ("view", "3d", "path", "pose", "snapshot", "walk")  # a picture of the robot, before a plot


def key_picture(pngs: list[Path]) -> Path:
    return min(pngs, key=lambda p: (not any(k in p.stem for k in KEY_PICTURE), p.name))


def headline(results: list[dict[str, Any]], out: Path) -> dict[str, Any]:
    """The scenario a body's card shows: a demo scenario, else one with a video, else the first."""
    def rank(r):
        sc = SCENARIOS.get(r["scenario"])
        return (not (sc is not None and sc.demo), not media(out, r["scenario"])[0], r["scenario"])
    return min(results, key=rank)


def card(body: str, results: list[dict[str, Any]], out: Path, statuses: list[RowStatus]) -> str:
    e = html.escape
    name, seed = BODIES.get(body, (body, None))
    thesis = f"seed {seed} · {SEEDS[seed]}" if seed in SEEDS else "used by every body"
    r = headline(results, out)
    sid = r["scenario"]
    videos, pngs = media(out, sid)
    if videos:
        v = videos[0]
        caption = video_caption(v.with_suffix(".json"))
        poster = v.with_suffix(".poster.jpg")
        poster = f' poster="{e(sid)}/{e(poster.name)}"' if poster.is_file() else ""
        picture = (f'<div class="media"><video src="{e(sid)}/{e(v.name)}"{poster} controls muted loop '
                   f'preload="metadata"></video></div>'
                   + (f'<p class="caption">{e(caption)}</p>' if caption else ""))
    elif pngs:
        key = key_picture(pngs)
        picture = f'<div class="media"><img class="key" src="{e(sid)}/{e(key.name)}" alt="{e(key.stem)}"></div>'
    else:
        picture = ""
    checks = r.get("checks", [])
    # a demo variant (fewer modes, a shorter run) may not compute every metric a check reads: not measured,
    # which is not the same as failing; in a full run a missing metric does fail its check
    unmeasured = [c for c in checks if not c["ok"] and (c["value"] is None or c["threshold"] is None)]
    unmeasured = unmeasured if "demo_variant" in r else []
    held = sum(c["ok"] for c in checks)
    failed = len(checks) - held - len(unmeasured)
    st = status(r)
    badge = {"pass": f"✓ {held}/{len(checks)} checks hold", "FAIL": f"✗ {failed} of {len(checks)} checks fail",
             "error": "✗ the run erred"}[st]
    if unmeasured and st == "FAIL":
        badge = (f"✗ {failed} check{' fails' if failed == 1 else 's fail'}, {held} hold, {len(unmeasured)} not "
                 "measured by this variant")
    why = "" if st == "pass" else f'<div class="why">{one_line(why_failed(r, statuses))}</div>'
    demo = ""
    if "demo_variant" in r:
        sets = ", ".join(f"{k}={v}" for k, v in r["demo_variant"].get("params", {}).items())
        demo = (f' <span class="badge demo" title="the demo\'s own run, not a reproduction">demo variant'
                f'{": " + e(sets) if sets else ""}</span>')
    others = ""
    if len(results) > 1:
        passed = sum(status(x) == "pass" for x in results)
        others = f'<p>{len(results)} {e(name.lower())} scenarios in this run: {passed} pass all their checks.</p>'
    command = r.get("command", f"shintai run {sid}") + (" --video" if videos else "")
    return (f'<section class="card" id="card-{e(body)}" data-scenario="{e(sid)}"><h2>{e(name)}</h2>'
            f'<p class="thesis">{e(thesis)}</p>{picture}'
            f'<p><a href="#sc-{e(sid)}"><b>{e(sid)}</b></a> <small>({e(r.get("source", ""))})</small>: '
            f'{e(summary_of(sid))}</p>'
            f'<p><span class="badge {st.lower()}">{e(badge)}</span>{demo}</p>{why}{others}'
            f'<p><code>{e(command)}</code></p></section>')


def readme_link(out: Path) -> str:
    """A link to the README's reproduction table: relative when this checkout's README is on disk."""
    import os

    import shintai

    readme = Path(shintai.__file__).resolve().parents[2] / "README.md"
    if readme.is_file():
        try:
            return html.escape(os.path.relpath(readme, out.resolve()) + "#reproduction")
        except ValueError:
            pass
    return "README.md#reproduction"


def write_html(out: Path, results: list[dict[str, Any]], statuses: list[RowStatus], title: str) -> Path:
    from shintai.scenarios.markdown import to_html

    e = html.escape
    counts = summary_counts(statuses)
    by_body: dict[str, list[dict[str, Any]]] = {}
    for r in results:
        by_body.setdefault(body_of(r["scenario"]), []).append(r)
    order = [b for b in BODIES if b in by_body] + sorted(b for b in by_body if b not in BODIES)
    cards = "".join(card(b, by_body[b], out, statuses) for b in order)
    passed = sum(status(r) == "pass" for r in results)
    failed = [r["scenario"] for r in results if status(r) != "pass"]
    lead = (f"{len(results)} scenarios ran: {passed} pass all their checks"
            + (f", {len(failed)} do not ({', '.join(failed)}; each card says why)." if failed else ".")
            + " Each card is one body: its film or key picture, what it reproduces, its checks and the command "
              "that reruns it. Thesis values are quoted beside ours below; ours are computed from the simulation.")
    summary = "".join(
        f'<tr><td>{e(seed)} {e(name)}</td>' + "".join(
            f'<td class="count" data-seed="{seed}" data-status="{e(s)}">{counts[seed][s]}</td>' for s in STATUSES)
        + "</tr>" for seed, name in SEEDS.items())
    covered = [s for s in statuses if s.status != NOT_RUN_HERE and s.scenarios]
    not_built = sum(1 for s in statuses if not s.scenarios)
    rest = len(statuses) - len(covered) - not_built
    row_html = "".join(
        f'<tr class="row {e(s.status.replace(" ", "-"))}"><td>{e(s.row.key)}</td><td>{e(s.row.where)}<br>'
        f'<small>{folded(s.row.what)}</small></td><td>{folded(s.row.result)}</td>'
        f'<td>{e(", ".join(s.scenarios) or "—")}</td><td class="status">{e(s.status)}</td>'
        f'<td>{folded(s.reason)}</td></tr>' for s in covered)
    rows, notes = [], []
    for r in results:
        sid = r["scenario"]
        videos, pngs = media(out, sid)
        imgs = "".join(f'<a href="{e(sid)}/{e(p.name)}"><img src="{e(sid)}/{e(p.name)}" alt="{e(p.stem)}"></a>' for p in pngs)
        video = "".join(f'<video src="{e(sid)}/{e(v.name)}" controls preload="metadata"></video>'
                        f'<br><small>{e(video_caption(v.with_suffix(".json")))}</small>' for v in videos)
        thesis = "<br>".join(folded(f"{q}: {t}") for q, t, _, _ in thesis_vs_ours(r)) or "—"
        mine = "<br>".join(e(f"{m}: {o}") for _, _, o, m in thesis_vs_ours(r) if m) or "—"
        checks = "<br>".join(e(c) for c in checks_text(r).split("; "))
        demo = "<br><b>demo variant</b> (not a reproduction)" if "demo_variant" in r else ""
        if notes_text(r):
            notes.append(f'<details class="notes" id="notes-{e(sid)}"><summary>{e(sid)} ({e(status(r))})</summary>'
                         f'{to_html(notes_text(r))}</details>')
        rows.append(f'<tr class="{status(r).lower()}" id="sc-{e(sid)}"><td><a href="{e(sid)}/metrics.json">{e(sid)}</a>'
                    f'<br><small>{e(r.get("source", ""))}</small>{demo}'
                    + (f'<br><a href="#notes-{e(sid)}">notes</a>' if notes_text(r) else "")
                    + f'</td><td>{thesis}</td><td>{mine}</td><td>{checks}</td><td class="st">{e(status(r))}</td>'
                    f'<td><code>{e(provenance(r))}</code></td><td>{video}{imgs}</td></tr>')
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>{e(title)}</title>
<meta name="viewport" content="width=device-width, initial-scale=1"><style>{PAGE_STYLE}</style></head><body>
<h1>{e(title)}</h1><p class="lead">{e(lead)}</p><div id="selfcheck"></div>
<div id="cards">{cards}</div>
<h2 id="covered">Thesis experiments this run covered</h2>
<p id="rest">{len(covered)} of the theses' {len(statuses)} experiments and result figures are covered by the
scenarios of this run; only reproduction checks decide. Of the others, {rest} are covered by scenarios not run here
and {not_built} are not yet built: <a href="{readme_link(out)}">the README's reproduction table</a> has all of
them.</p>
<table id="rows"><colgroup><col style="width:9%"><col style="width:22%"><col style="width:30%"><col style="width:13%">
<col style="width:9%"><col style="width:17%"></colgroup>
<tr><th>row</th><th>where</th><th>thesis result</th><th>scenarios</th><th>status</th><th>reason</th></tr>
{row_html}</table>
<h2>Summary per thesis</h2><p>This run's thesis experiments by status.</p>
<table id="summary"><tr><th>thesis</th>{''.join(f'<th>{e(s)}</th>' for s in STATUSES)}</tr>{summary}</table>
<h2>Scenarios</h2><p>{passed} of {len(results)} scenarios pass all their checks ([R] reproduction, [C] consistency).</p>
<table id="scenarios"><colgroup><col style="width:13%"><col style="width:17%"><col style="width:13%">
<col style="width:22%"><col style="width:5%"><col style="width:12%"><col style="width:18%"></colgroup>
<tr><th>experiment</th><th>thesis value</th><th>ours</th><th>checks</th><th>status</th>
<th>command</th><th>pictures</th></tr>
{''.join(rows)}</table>
<h2>Notes</h2><p>Each scenario's own account: what it reproduces, what differs and why.</p>
{''.join(notes)}{SELF_CHECK}</body></html>
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
