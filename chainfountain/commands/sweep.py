"""``chainfountain sweep SWEEP.toml``: a level over a grid of field values, in parallel."""

from __future__ import annotations

import argparse
import os
import sys

from chainfountain.commands.args import integer, path_arg

EXAMPLE = '''base = "paper_tall"
duration = 6.0
[grid]
"feed.speed" = [5.0, 5.5, 6.0]'''


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "sweep",
        help="run a level over a grid of field values, in parallel, into a results table",
        description="Run the level SWEEP names (base) once for every combination of the "
        "values in its [grid] (and each of its seeds), one process per job. Each point's "
        "outputs go to OUT/points/<id>/; a rerun skips the points already recorded. Writes "
        "OUT/results.parquet and results.csv (one row per point: the swept fields, status, "
        "reason, every number of its summary.json) and results.png. A sweep file:\n\n"
        + EXAMPLE,
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
    from pathlib import Path

    from chainfountain.headless import prepare_out_dir
    from chainfountain.study import sweep as sw

    spec = sw.load(args.sweep)
    out = prepare_out_dir(args.out or Path("runs") / f"sweep-{args.sweep.stem}")
    jobs = args.jobs or os.cpu_count() or 1
    todo, done = sw.pending(spec, out, args.retry_failed)
    total = done + len(todo)
    print(f"sweep of {spec.base_name}: {total} points ({', '.join(spec.grid)}"
          + (f", seeds {spec.seeds}" if spec.seeds != [None] else "") + f"); {done} recorded "
          f"before, {len(todo)} to run "
          + (f"on the Dask cluster at {args.dask}" if args.dask else
             f"on {min(jobs, max(1, len(todo)))} processes"), file=sys.stderr)
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

    rows = sw.execute(spec, out, jobs, retry_failed=args.retry_failed, progress=progress,
                      dask=args.dask)
    if bar is not None:
        bar.close()
    png = sw.figure(spec, rows, out / "results.png")
    counts = {s: sum(r.get("status") == s for r in rows) for s in sw.STATUS}
    written = ["results.parquet", "results.csv"] + (["results.png"] if png else [])
    print(f"wrote {out}/" + ", ".join(written) + ": " + ", ".join(
        f"{n} {s.replace('_', ' ')}" for s, n in counts.items() if n))
    for r in rows:
        if r.get("status") in ("refused", "failed"):
            print(f"  {r['point']} {r['status']}: {r['reason']}")
    return 0 if counts["failed"] == 0 else 5
