"""The ``shintai`` command (contract in DESIGN.md): list, run, reproduce, bench, and demo.

Exit status: 0 every check holds, 1 a check fails or a run errs, 2 a usage or parameter error
(one line on stderr, no traceback).
"""

from __future__ import annotations

import argparse
import contextlib
import fnmatch
import json
import os
import signal
import sys
import threading
import time
from pathlib import Path

from shintai.nervous.cli import add_parser as add_nervous_parser
from shintai.scenarios import registry
from shintai.scenarios.registry import ParameterError
from shintai.scenarios.runner import Progress


class OneLineParser(argparse.ArgumentParser):
    """argparse, but a usage error is one line and exit status 2."""

    def error(self, message):
        self.exit(2, f"shintai: error: {message} (see `shintai {self.prog.split()[-1]} --help`)\n"
                  if " " in self.prog else f"shintai: error: {message} (see `shintai --help`)\n")


def parse_sets(pairs: list[str]) -> dict[str, str]:
    out = {}
    for pair in pairs:
        key, eq, value = pair.partition("=")
        if not eq or not key:
            raise ParameterError(f"--set {pair}: expected KEY=VALUE")
        out[key.strip()] = value.strip()
    return out


def select(pattern: str | None, pool: dict) -> list[str]:
    ids = sorted(pool)
    if pattern:
        ids = [i for i in ids if fnmatch.fnmatch(i, pattern)]
        if not ids:
            raise ParameterError(f"--only {pattern}: matches nothing (see `shintai list`)")
    return ids


def warn_load_errors() -> None:
    for module, err in registry.LOAD_ERRORS.items():
        print(f"shintai: warning: {module} failed to import: {err}", file=sys.stderr)


def cmd_list(args) -> int:
    for sid in sorted(registry.SCENARIOS):
        sc = registry.SCENARIOS[sid]
        print(f"{sid:34s} {sc.source:40s} {sc.summary}")
    return 0


def print_result(result: dict, out: Path, filmed: bool = False) -> None:
    for c in result.get("checks", []):
        mark = "ok  " if c["ok"] else "FAIL"
        print(f"  {mark} {c['name']}: {c['value']} {c['op']} {c['threshold']}  [{c['basis']}]")
    if "error" in result:
        print(f"shintai: error: {result['scenario']}: {result['error']} (partial results kept in {out})",
              file=sys.stderr)
    from shintai.scenarios.report import video_caption

    for video in sorted(out.glob("*.mp4")) if filmed else ():
        caption = video_caption(video.with_suffix(".json"))
        print(f"  film {video}" + (f" ({caption})" if caption else ""))
    print(f"{result['scenario']}: {'pass' if result['ok'] else 'FAIL'} "
          f"(sim {result['sim_time_s']:.3g} s, wall {result['wall_time_s']:.3g} s) -> {out}/metrics.json")


def cmd_run(args) -> int:
    from shintai.scenarios.runner import run_scenario
    from shintai.scenarios.sampling import line, sampled

    if args.seed < 0:
        raise ParameterError(f"--seed {args.seed}: expected a non-negative integer")
    registry.get(args.id)  # unknown id: exit 2 before anything runs
    out = Path(args.out) if args.out else Path("out") / args.id
    with sampled() if args.profile else contextlib.nullcontext() as samples:
        result = run_scenario(args.id, out, parse_sets(args.set), seed=args.seed, video=args.video,
                              quiet=args.quiet, view=args.view)
    print_result(result, out, filmed=args.video)
    if samples is not None:  # --profile: where the run's CPU time went, by layer (scenarios/sampling.py)
        profile = samples.summary(top=10)
        (out / "profile.json").write_text(json.dumps(profile, indent=2) + "\n")
        print(f"  profile: {line(profile)} -> {out}/profile.json")
    return 0 if result["ok"] else 1


def run_one(job: tuple) -> dict:
    """Run one scenario for ``reproduce`` (module level so process and Ray executors can ship it)."""
    from shintai.scenarios.runner import run_scenario

    sid, out, seed, video, *demo = job
    overrides = demo[0] if demo else None  # a demo variant's --set overrides
    result = run_scenario(sid, out, overrides, seed=seed, video=video, quiet=True, demo_variant=bool(overrides))
    return {"scenario": sid, "ok": result["ok"], "error": result.get("error")}


def expected_walls(ids: list[str], out: Path) -> dict[str, float]:
    """Each scenario's expected wall time, for a time-left estimate that knows runs differ in length: the
    previous run's in ``out`` (its metrics.json), else the scenario's declared ``estimate_s``, else the
    median of the others (1 s if none is known)."""
    known = {}
    for sid in ids:
        try:
            wall = json.loads((out / sid / "metrics.json").read_text()).get("wall_time_s")
        except (OSError, ValueError):
            wall = None
        wall = wall if isinstance(wall, (int, float)) and wall > 0 else registry.SCENARIOS[sid].estimate_s
        if wall:
            known[sid] = float(wall)
    values = sorted(known.values())
    fallback = values[len(values) // 2] if values else 1.0
    return {sid: known.get(sid, fallback) for sid in ids}


class WeightedProgress:
    """``progress(done, total)`` for an executor's map over scenario jobs, as the fraction of the expected
    wall time finished: a job counts as finished once its metrics.json is newer than the start (the
    executor only reports counts); where that cannot be seen (a remote cluster), the count's fraction."""

    def __init__(self, bar, jobs: list[tuple], walls: dict[str, float]):
        self.bar, self.jobs, self.walls = bar, jobs, walls
        self.total = sum(walls[j[0]] for j in jobs) or 1.0
        self.start = time.time()

    def finished(self) -> list[tuple]:
        done = []
        for job in self.jobs:
            try:
                if (Path(job[1]) / "metrics.json").stat().st_mtime >= self.start:
                    done.append(job)
            except OSError:
                pass
        return done

    def __call__(self, done: int, total: int) -> None:
        seen = self.finished()
        fraction = (sum(self.walls[j[0]] for j in seen) / self.total if len(seen) == done
                    else done / max(total, 1))
        self.bar(1.0 if done == total else min(fraction, 0.999), f"{done}/{total} runs done")


def reproduce(ids: list[str], out: Path, executor: str, seed: int, video: bool, title: str,
              address: str | None = None, checks_only_ran: bool = False, seeds: int = 1, quiet: bool = False,
              demo: bool = False) -> int:
    """Run ``ids`` (a stochastic scenario ``seeds`` times, seeds ``seed`` … ``seed + seeds − 1``, combined
    as mean ± std) on an executor, then write REPORT.md and index.html from what finished. ``demo``: run
    each scenario's declared demo variant (``demo_params``), labelled as such."""
    from shintai.evolve.executors import make_executor
    from shintai.scenarios.report import write_report
    from shintai.scenarios.seeds import write_combined

    from shintai.scenarios.runner import output_folder

    output_folder(out)

    def films(sid):  # with the parameters it runs with (a demo variant's, in the demo)
        sc = registry.SCENARIOS[sid]
        return video and sc.demo_video and sc.films(sc.resolve(sc.demo_params if demo else None))

    def seeds_of(sid):
        return list(range(seed, seed + seeds)) if seeds > 1 and registry.SCENARIOS[sid].stochastic else None

    def demo_of(sid):
        return (registry.SCENARIOS[sid].demo_params or None) if demo else None

    jobs = []
    for sid in ids:
        many = seeds_of(sid)
        jobs += ([(sid, str(out / sid / f"seed-{s}"), s, films(sid) and s == seed, demo_of(sid)) for s in many]
                 if many else [(sid, str(out / sid), seed, films(sid), demo_of(sid))])
    # the longest runs first: a pool then ends with short ones instead of waiting on one long straggler
    walls = expected_walls(ids, out)
    jobs.sort(key=lambda job: -walls[job[0]])
    progress = WeightedProgress(Progress("reproduce", quiet=quiet), jobs, walls)

    summaries = []
    try:
        with make_executor(executor, address=address) as ex:
            summaries = ex.map(run_one, jobs, progress=progress)
    finally:  # a report of whatever finished, even if the run was interrupted
        for sid in ids:
            if seeds_of(sid):
                try:
                    write_combined(registry.SCENARIOS[sid], out / sid, seeds_of(sid))
                except FileNotFoundError:
                    pass
        results = write_report(out, ids, title)
    for s in summaries if not quiet else ():
        print(f"  {'pass' if s['ok'] else 'FAIL'} {s['scenario']}" + (f": {s['error']}" if s["error"] else ""))
    print(f"{sum(r.get('ok', False) for r in results)}/{len(results)} pass -> {out}/REPORT.md, {out}/index.html")
    if checks_only_ran:  # the demo shows failing checks in its report; only a run that errs fails it
        return 0 if not any("error" in r for r in results) else 1
    return 0 if all(r.get("ok") for r in results) else 1


def cmd_reproduce(args) -> int:
    ids = select(args.only, registry.SCENARIOS)
    if args.seeds < 1:
        raise ParameterError(f"--seeds {args.seeds}: expected a positive integer")
    return reproduce(ids, Path(args.out), args.executor, args.seed, video=args.video,
                     title="shintai reproduction report", address=args.address, seeds=args.seeds, quiet=args.quiet)


def cmd_demo(args) -> int:
    ids = registry.demo_ids()
    return reproduce(ids, Path(args.out), args.executor, 0, video=not args.no_video, title="shintai demo",
                     checks_only_ran=True, quiet=args.quiet, demo=True)


def cmd_bench(args) -> int:
    from shintai.scenarios.sampling import line, sampled

    ids = select(args.only, registry.BENCHMARKS)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    results = {}
    for bid in ids:
        print(f"bench: {bid} ...", file=sys.stderr)
        t0 = time.perf_counter()
        with sampled() as samples:  # where the benchmark's CPU time went (scenarios/sampling.py)
            try:
                results[bid] = registry.BENCHMARKS[bid].run()
            except Exception as exc:  # noqa: BLE001 - one benchmark failing keeps the others
                results[bid] = {"error": f"{type(exc).__name__}: {exc}".splitlines()[0]}
        results[bid]["bench_wall_s"] = time.perf_counter() - t0
        print(f"  {bid}: " + ", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                                       for k, v in results[bid].items() if not isinstance(v, dict)))
        results[bid]["profile"] = profile = samples.summary()
        print(f"    profile: {line(profile)}")
        (out / "bench.json").write_text(json.dumps(results, indent=2) + "\n")
    print(f"-> {out}/bench.json")
    return 1 if any("error" in r for r in results.values()) else 0


def cmd_model(args) -> int:
    from shintai.sim.export import UnknownModel, export, load_models

    models = load_models()
    if args.list or args.id is None:
        for mid in sorted(models):
            print(f"{mid:28s} {models[mid].summary}")
        return 0
    try:
        path = export(args.id, args.out)
    except UnknownModel as exc:
        raise ParameterError(exc.args[0]) from None
    print(f"{args.id} -> {path} (open with MuJoCo's simulate: python -m mujoco.viewer --mjcf={path})")
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = OneLineParser(prog="shintai", description="Robot bodies of four theses: run, reproduce, benchmark.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    sub.add_parser("list", help="every scenario: id, source, summary").set_defaults(fn=cmd_list)

    r = sub.add_parser("run", help="run one scenario")
    r.add_argument("id")
    r.add_argument("--out", help="output folder (default out/ID)")
    r.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="override a parameter")
    r.add_argument("--seed", type=int, default=0)
    r.add_argument("--video", action="store_true", help="render video.mp4 (MuJoCo scenarios)")
    r.add_argument("--view", action="store_true", help="show the run live in MuJoCo's viewer (needs a display)")
    r.add_argument("--quiet", action="store_true", help="no progress on stderr")
    r.add_argument("--profile", action="store_true",
                   help="sample where the CPU time goes (physics, control, recording, …) into profile.json")
    r.set_defaults(fn=cmd_run)

    executors = ("serial", "process", "ray")
    rep = sub.add_parser("reproduce", help="run many scenarios, write REPORT.md and index.html")
    rep.add_argument("--only", help="glob over scenario ids, e.g. 'snake.*'")
    rep.add_argument("--out", default="out/reproduce")
    rep.add_argument("--executor", choices=executors, default="process")
    rep.add_argument("--address", help="Ray cluster address (with --executor ray); default: RAY_ADDRESS or local")
    rep.add_argument("--seed", type=int, default=0, help="first seed")
    rep.add_argument("--seeds", type=int, default=1,
                     help="run each stochastic scenario with this many seeds and report mean ± std")
    rep.add_argument("--video", action="store_true", help="film the scenarios that can be filmed")
    rep.add_argument("--quiet", action="store_true", help="no progress on stderr")
    rep.set_defaults(fn=cmd_reproduce)

    d = sub.add_parser("demo", help="one headline scenario per body, with videos, into out/demo")
    d.add_argument("--out", default="out/demo")
    d.add_argument("--executor", choices=executors, default="process")
    d.add_argument("--no-video", action="store_true")
    d.add_argument("--quiet", action="store_true", help="no progress on stderr")
    d.set_defaults(fn=cmd_demo)

    mo = sub.add_parser("model", help="export a body's MuJoCo model as MJCF (or --list the models)")
    mo.add_argument("id", nargs="?", help="model id (see --list)")
    mo.add_argument("--list", action="store_true", help="every model id with a summary")
    mo.add_argument("--out", default="out/models", help="output folder (default out/models)")
    mo.set_defaults(fn=cmd_model)

    add_nervous_parser(sub)

    b = sub.add_parser("bench", help="run the benchmarks, write bench.json")
    b.add_argument("--only", help="glob over benchmark ids")
    b.add_argument("--out", default="out/bench")
    b.set_defaults(fn=cmd_bench)
    return p


def interrupt_on_sigterm(signum, frame) -> None:
    """SIGTERM (a cancelled job) ends a run like Ctrl-C: finished results are kept, pools closed."""
    raise KeyboardInterrupt


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if threading.current_thread() is not threading.main_thread():
        return run_command(args)
    previous = signal.signal(signal.SIGTERM, interrupt_on_sigterm)
    try:
        return run_command(args)
    finally:
        signal.signal(signal.SIGTERM, previous)


def run_command(args: argparse.Namespace) -> int:
    """Run the parsed sub-command; usage errors exit 2, interruptions 130."""
    if getattr(args, "registry", True):  # the nervous server needs no scenario registry
        registry.load_all()
        warn_load_errors()
    try:
        return args.fn(args)
    except ParameterError as exc:
        print(f"shintai: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader went away (`shintai list | head`): stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except KeyboardInterrupt:
        print("shintai: interrupted (finished results are kept)", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
