"""``chainfountain sweep SWEEP.toml``: a level over a grid of field values, in parallel."""

from __future__ import annotations

import argparse
import os
import sys

from chainfountain.commands.args import integer, path_arg

EXAMPLE = '''base = "paper_tall"
duration = 6.0
seeds = [0, 1]                    # optional
[changes]                         # optional: set in every point
"solver.iterations" = 30
[grid]                            # optional with seeds
"feed.speed" = [5.0, 5.5, 6.0]'''


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "sweep",
        help="run a level over a grid of field values, in parallel, into a results table",
        description="Run the level SWEEP names (base) once for every combination of the "
        "values in its [grid] (and each of its seeds), with its [changes], one process per "
        "job. Each point's resolved level, record and outputs go to OUT/points/<key>/, its key "
        "a hash of what it runs (level, duration, version): a rerun skips exactly the points "
        "recorded under their key and runs the interrupted ones again. Writes "
        "OUT/results.parquet and results.csv (one row per point: the swept fields, status, "
        "reason, key, version, every number of its summary.json) and results.png. Exit "
        "status: 0 every point has its result (refused ones aside); 2 bad input, or every "
        "point refused; 5 a point failed or was interrupted by a lost worker, or none gave "
        "a result; 130 or 143 interrupted by Ctrl-C or SIGTERM (the table holds the "
        "finished points). A sweep file:\n\n" + EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        allow_abbrev=False,
    )
    p.add_argument("sweep", metavar="SWEEP.toml", type=path_arg("a sweep file"))
    p.add_argument("--jobs", type=integer("a number of processes", min=1, max=256),
                   default=None, help="processes at a time (default: this machine's cores, "
                   f"{os.cpu_count() or 1})")
    p.add_argument("--out", type=path_arg("an output folder"), default=None,
                   help="output folder (default runs/sweep-<sweep file name>)")
    p.add_argument("--retry-failed", action="store_true",
                   help="run again the points whose run raised an error (refused levels "
                   "are not retried: they cannot exist)")
    p.add_argument("--dask", metavar="ADDRESS", default=None,
                   help="run the points on a Dask cluster instead: the scheduler's address, "
                   "as 'dask scheduler' prints it (tcp://HOST:8786); each worker needs "
                   "chainfountain installed, no shared disk (outputs come back here)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from chainfountain.headless import Interrupted

    try:
        return _sweep(args)
    except Interrupted as exc:  # before any point ran (a point's run takes its own)
        import signal

        print(f"chainfountain: interrupted by {signal.Signals(exc.signum).name} before any "
              "point ran", file=sys.stderr)
        return 128 + exc.signum


def _sweep(args: argparse.Namespace) -> int:
    from pathlib import Path

    from chainfountain.headless import prepare_out_dir
    from chainfountain.level import resolve
    from chainfountain.study import sweep as sw

    with sw.interruptible():
        spec = sw.load(args.sweep)
        out = prepare_out_dir(args.out or Path("runs") / f"sweep-{args.sweep.stem}")
        jobs = args.jobs or os.cpu_count() or 1
        planned = sw.plan(spec)
        todo, done = sw.pending(spec, out, args.retry_failed, planned)
        total = len(planned)
        swept = ", ".join(spec.columns + (["seeds " + str(spec.seeds)]
                                          if spec.seeds != [None] else []))
        refused = sum(bool(pt.refused) for pt in planned)
        print(f"sweep of {spec.base_name}: {total} points ({swept}); "
              + (f"{refused} refused, " if refused else "")
              + f"{done - refused} recorded before, {len(todo)} to run "
              + (f"on the Dask cluster at {args.dask}" if args.dask else
                 f"on {min(jobs, max(1, len(todo)))} processes"), file=sys.stderr)
        set_here = {**spec.changes, **{p: None for p in spec.grid}}
        taken = sorted(p for p in set_here if p in resolve.CHOSEN)
        acc = spec.changes.get("solver.accuracy", spec.base.sim.solver.accuracy)
        if taken and acc and "solver.accuracy" not in spec.grid:
            print(f"  the sweep sets {', '.join(taken)}, which solver.accuracy = {acc:g} "
                  "chooses: a point where it differs from the accuracy's choice runs with "
                  "the accuracy off, at the value given", file=sys.stderr)
        bar = None
        if not args.quiet and todo:
            from tqdm import tqdm

            bar = tqdm(total=total, initial=done, unit="point", file=sys.stderr,
                       disable=not sys.stderr.isatty())

        def progress(k: int, n: int, left: float) -> None:
            if bar is not None and not bar.disable:
                bar.update(1)
            elif not args.quiet:
                print(f"  {k}/{n} points, about {left / 60:.1f} min left", file=sys.stderr,
                      flush=True)

        try:
            rows = sw.execute(spec, out, jobs, retry_failed=args.retry_failed,
                              progress=progress, dask=args.dask, planned=planned)
            stopped = None
        except sw.Stopped as exc:
            rows, stopped = exc.rows, exc
        finally:
            if bar is not None:
                bar.close()
        png = sw.figure(spec, rows, out / "results.png")
    return report(out, rows, png is not None, stopped)


def report(out, rows: list[dict], png: bool, stopped) -> int:
    """Print what the sweep wrote and how its points ended; the exit status: 0 when every
    point has its result (refused points aside), 2 when every point was refused, 5 when a
    point failed or none gave a result, 128 + the signal's number when one stopped it."""
    from chainfountain.study import sweep as sw

    counts = {s: sum(r.get("status") == s for r in rows) for s in sw.STATUS}
    written = ["results.parquet", "results.csv"] + (["results.png"] if png else [])
    print(f"wrote {out}/" + ", ".join(written) + ": " + (", ".join(
        f"{n} {s.replace('_', ' ')}" for s, n in counts.items() if n) or "no points"))
    for r in rows:
        if r.get("status") in ("refused", "failed"):
            print(f"  {r['point']} {r['status']}: {r['reason']}")
    if stopped is not None:
        print(f"chainfountain: error: {stopped}", file=sys.stderr)
        return stopped.status
    results = counts["done"] + counts["ended_early"]
    if rows and counts["refused"] == len(rows):
        print(f"chainfountain: error: every point of the sweep was refused ({len(rows)}; the "
              f"first: {rows[0]['reason']}); nothing ran", file=sys.stderr)
        return 2
    if not results:
        print("chainfountain: error: no point of the sweep gave a result ("
              + ", ".join(f"{n} {s}" for s, n in counts.items() if n) + ")", file=sys.stderr)
        return 5
    return 0 if counts["failed"] == 0 and counts["interrupted"] == 0 else 5
