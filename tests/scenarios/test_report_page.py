"""The report page in a real headless browser (Debian's chromium): it renders, every image and video loads,
and the summary counts on the page are those of the coverage rows computed from metrics.json."""

import json
import re
import subprocess

import imageio.v2 as imageio
import numpy as np
import pytest

from debian_tools import ensure
from shintai.cli import main
from shintai.scenarios import registry
from shintai.scenarios.coverage import all_rows
from shintai.scenarios.report import coverage, summary_counts, write_report

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


@pytest.fixture(scope="module")
def chromium():
    """Debian's chromium, installed with apt-get when missing (skipped, saying why, where it cannot be)."""
    return ensure("chromium", "chromium")


def dom(chromium, page, tmp_path):
    out = subprocess.run([chromium, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=15000",
                          "--dump-dom", page.as_uri()], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout


def selfcheck(text):
    tag = re.search(r'<div id="selfcheck"([^>]*)>', text).group(1)
    return {k: v for k, v in re.findall(r'data-([a-z-]+)="([^"]*)"', tag)}


def tiny_video(path):
    with imageio.get_writer(path, format="FFMPEG", fps=10, codec="libx264", macro_block_size=2) as w:
        for i in range(10):
            w.append_data(np.full((64, 64, 3), 20 * i, np.uint8))


def test_page_renders_loads_its_media_and_counts_as_metrics_json(chromium, tmp_path):
    assert main(["reproduce", "--only", "core.*", "--out", str(tmp_path), "--executor", "serial"]) == 0
    tiny_video(tmp_path / "core.minjerk" / "video.mp4")
    ids = ["core.minjerk", "core.search-index"]
    write_report(tmp_path, ids)
    text = dom(chromium, tmp_path / "index.html", tmp_path)
    check = selfcheck(text)
    assert check["done"] == "1"
    assert int(check["images"]) >= 2 and check["images-ok"] == check["images"]
    assert check["videos"] == "1" and check["videos-ok"] == "1"
    # the counts the page shows are those computed from the metrics.json files on disk
    registry.load_all()
    results = [json.loads((tmp_path / sid / "metrics.json").read_text()) for sid in ids]
    expected = summary_counts(coverage(results))
    shown = {(seed, status): int(n) for seed, status, n in
             re.findall(r'data-seed="(\d+)" data-status="([^"]+)">(\d+)<', text)}
    assert shown and shown == {(seed, s): n for seed, c in expected.items() for s, n in c.items()}
    assert "shintai run core.minjerk" in text  # the command that produced each result


def test_a_broken_image_is_seen_by_the_page(chromium, tmp_path):
    assert main(["reproduce", "--only", "core.minjerk", "--out", str(tmp_path), "--executor", "serial"]) == 0
    (tmp_path / "core.minjerk" / "broken.png").write_bytes(b"not a png")
    write_report(tmp_path, ["core.minjerk"])
    check = selfcheck(dom(chromium, tmp_path / "index.html", tmp_path))
    assert int(check["images-ok"]) == int(check["images"]) - 1


def test_every_row_has_a_seed_and_the_rows_are_unique():
    rows = all_rows()  # raises on a duplicate key or an unknown seed
    assert all(r.key.startswith(f"{r.seed}:") and r.where and r.what and r.result for r in rows.values())
