"""The report page in a real headless browser (Debian's chromium), on a tiny fake run (no scenario runs
here): it opens on one card per body, above the tables; every image and video loads; nothing is wider than a
1,400 px window; the summary counts are those of the coverage rows computed from metrics.json."""

import json
import re
import subprocess

import imageio.v2 as imageio
import numpy as np
import pytest

from debian_tools import ensure
from shintai.scenarios import registry
from shintai.scenarios.coverage import all_rows
from shintai.scenarios.report import coverage, load_results, summary_counts, write_report

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync", "--window-size=1400,900"]
IDS = ["core.minjerk", "humanoid.tricycle-pedaling", "snake.tracking"]
NOTES = """What it reproduces, in **bold**, with `code` and a <script>alert(1)</script> that stays text.

- a list item
- another, long: 「非常に長い日本語の引用がここに入りますが、ページの幅を超えてはいけません」""" + "あ" * 400 + """

| quantity | thesis | ours |
|---|---|---|
| error | 0.06 m | 0.05 m |
"""


@pytest.fixture(scope="module")
def chromium():
    """Debian's chromium, installed with apt-get when missing (skipped, saying why, where it cannot be)."""
    return ensure("chromium", "chromium")


def browse(chromium, page, tmp_path, *extra):
    out = subprocess.run([chromium, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=15000",
                          *extra, page.as_uri()], capture_output=True, text=True, timeout=180)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout


def selfcheck(text):
    tag = re.search(r'<div id="selfcheck"([^>]*)>', text).group(1)
    return {k: v for k, v in re.findall(r'data-([a-z-]+)="([^"]*)"', tag)}


def tiny_video(path, speed=4.0):
    with imageio.get_writer(path, format="FFMPEG", fps=10, codec="libx264", macro_block_size=2) as w:
        for i in range(10):
            w.append_data(np.full((48, 64, 3), 20 * i, np.uint8))
    path.with_suffix(".json").write_text(json.dumps({"fps": 10, "frames": 10, "speed": speed, "sim_s": 3.6,
                                                     "width": 64, "height": 48}))


def fake_run(out, sid, ok, video=False):
    """A metrics.json like the runner's (its reproduction checks all holding, or the first failing), a
    picture, and a film."""
    sc = registry.get(sid)
    folder = out / sid
    folder.mkdir(parents=True)
    checks = [{"name": c.name or c.metric, "metric": c.metric, "op": c.op, "threshold": 1.0, "value": 0.5,
               "ok": ok or k > 0, "basis": c.basis, "kind": c.kind, **({"row": c.row} if c.row else {})}
              for k, c in enumerate(sc.checks)]
    result = {"scenario": sid, "source": sc.source, "seed": 0, "params": sc.resolve(), "metrics": {},
              "checks": checks, "thesis": {}, "sim_time_s": 3.6, "wall_time_s": 1.0, "notes": NOTES,
              "covers": list(sc.covers), "command": f"shintai run {sid}", "commit": "abc",
              "ok": all(c["ok"] for c in checks)}
    (folder / "metrics.json").write_text(json.dumps(result))
    rng = np.random.default_rng(len(sid))
    imageio.imwrite(folder / "plot.png", rng.integers(0, 255, (90, 120, 3), dtype=np.uint8))
    if video:
        tiny_video(folder / "video.mp4")


@pytest.fixture
def fake_report(tmp_path):
    registry.load_all()
    out = tmp_path / "demo"
    fake_run(out, "core.minjerk", True)
    fake_run(out, "humanoid.tricycle-pedaling", False, video=True)
    fake_run(out, "snake.tracking", True, video=True)
    write_report(out, IDS, "shintai demo")
    return out


def test_the_page_opens_on_the_cards_and_loads_its_media(chromium, fake_report, tmp_path):
    page = fake_report / "index.html"
    text = browse(chromium, page, tmp_path, "--dump-dom")
    check = selfcheck(text)
    assert check["done"] == "1"
    assert int(check["images"]) >= 3 and check["images-ok"] == check["images"]
    assert check["videos"] == "4" and check["videos-ok"] == "4"  # two cards and two table rows
    assert int(check["scroll-width"]) <= int(check["client-width"]) <= 1400  # no horizontal scroll
    # one card per body, the robots first, all above the tables
    cards = re.findall(r'<section class="card" id="card-([a-z]+)" data-scenario="([^"]+)"', text)
    assert [c[0] for c in cards] == ["humanoid", "snake", "core"]
    assert text.index('id="cards"') < text.index('id="rows"') < text.index('id="scenarios"')
    humanoid = text[text.index('id="card-humanoid"'):text.index('id="card-snake"')]
    assert "checks fail" in humanoid and 'class="why"' in humanoid and "×4 time-lapse" in humanoid
    assert "shintai run humanoid.tricycle-pedaling --video" in humanoid
    # notes rendered as HTML, their markup escaped
    assert "<strong>bold</strong>" in text and '<table class="md">' in text and "<script>alert" not in text
    # the counts the page shows are those computed from the metrics.json files on disk
    expected = summary_counts(coverage(load_results(fake_report, IDS)))
    shown = {(seed, status): int(n) for seed, status, n in
             re.findall(r'data-seed="(\d+)" data-status="([^"]+)">(\d+)<', text)}
    assert shown and shown == {(seed, s): n for seed, c in expected.items() for s, n in c.items()}
    # and a person can look at it: the first screen as a picture
    shot = tmp_path / "first-screen.png"
    browse(chromium, page, tmp_path, f"--screenshot={shot}")
    image = imageio.imread(shot)
    assert image.shape[:2] == (900, 1400) and image.std() > 10


def test_a_broken_image_is_seen_by_the_page(chromium, fake_report, tmp_path):
    (fake_report / "core.minjerk" / "broken.png").write_bytes(b"not a png")
    write_report(fake_report, IDS, "shintai demo")
    text = browse(chromium, fake_report / "index.html", tmp_path, "--dump-dom")
    check = selfcheck(text)
    shown = len(re.findall(r'<img[^>]*src="core.minjerk/broken.png"', text))  # on the card and in the table
    assert shown == 2 and int(check["images-ok"]) == int(check["images"]) - shown


def test_only_the_rows_this_run_covered_are_in_the_table(fake_report):
    text = (fake_report / "index.html").read_text()
    table = text[text.index('id="rows"'):text.index('id="summary"')]
    keys = re.findall(r'<tr class="row [^"]+"><td>([^<]+)</td>', table)
    covered = {k for sid in IDS for k in registry.get(sid).covers}
    assert keys and set(keys) == covered
    assert "README" in text[text.index('id="rest"'):text.index('id="rows"')]


def test_every_row_has_a_seed_and_the_rows_are_unique():
    rows = all_rows()  # raises on a duplicate key or an unknown seed
    assert all(r.key.startswith(f"{r.seed}:") and r.where and r.what and r.result for r in rows.values())
