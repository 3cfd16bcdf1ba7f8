"""Fuzz the level check and the simulator with mutated level files.

Runs the strategies of ``tests/level/levelfuzz.py`` on ``--examples`` mutants of the shipped
levels (wrong types, NaN/inf, zero/negative/huge numbers, missing and unknown keys, wrong
table shapes, truncated files, random bytes, non-UTF-8) through
:func:`chainfountain.level.io.load` and prints how many were accepted, refused with one
clear line, or gave a traceback (must be 0). Then ``--run-accepted`` of the accepted
mutants (spread over all of them) are built and run ``--seconds`` headless; it prints
how many ran, stopped themselves (RunEnded, by reason), were cut at the wall-time limit,
or gave a traceback (must be 0). Exit status 1 when any traceback was seen.

Run it from the repository root as a module (it imports ``tests.level.levelfuzz``)::

    .venv/bin/python -m benchmarks.fuzz_levels                 # 10000 mutants, 300 runs
    .venv/bin/python -m benchmarks.fuzz_levels --examples 2000 --run-accepted 50 --seed 3
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
import time
import traceback
from pathlib import Path

from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import seed as hypothesis_seed

from tests.level import levelfuzz as lf


def _refusal_kind(msg: str, where: str) -> str:
    rest = msg[len(where) + 2:]
    if rest.startswith("not valid TOML"):
        return "not valid TOML"
    if rest.startswith("not a UTF-8"):
        return "not UTF-8"
    field, _, why = rest.partition(": ")
    if why.startswith("unknown key"):
        return "unknown key"
    return lf.schema_path(field)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--examples", type=int, default=10000, help="mutants to check")
    ap.add_argument("--run-accepted", type=int, default=300, metavar="N",
                    help="accepted mutants to run headless (0: none)")
    ap.add_argument("--seconds", type=float, default=0.3, help="simulated time of each run")
    ap.add_argument("--wall-limit", type=float, default=3.0,
                    help="wall seconds after which a run is cut (a slow but healthy level)")
    ap.add_argument("--seed", type=int, default=0,
                    help="0: the derandomized examples (the same on every machine)")
    args = ap.parse_args(argv)

    tmp = Path(tempfile.mkdtemp(prefix="fuzz_levels_"))
    path = tmp / "mutant.toml"
    counts: collections.Counter[str] = collections.Counter()
    refusals: collections.Counter[str] = collections.Counter()
    accepted: list[tuple[str, lf.io.Level]] = []
    failures: list[tuple[str, str]] = []

    conf = settings(max_examples=args.examples, database=None, deadline=None,
                    derandomize=args.seed == 0, phases=[Phase.generate],
                    suppress_health_check=list(HealthCheck))

    @conf
    @given(lf.mutants())
    def check(mutant: tuple[str, bytes]) -> None:
        how, data = mutant
        counts["tried"] += 1
        try:
            verdict = lf.check_text(data, path)
        except Exception:  # noqa: BLE001 - counted and shown, never raised
            counts["traceback"] += 1
            failures.append((how, traceback.format_exc()))
            return
        if verdict.accepted:
            counts["accepted"] += 1
            assert verdict.level is not None
            accepted.append((how, verdict.level))
        else:
            counts["refused"] += 1
            refusals[_refusal_kind(verdict.message, str(path))] += 1

    if args.seed:
        check = hypothesis_seed(args.seed)(check)
    t0 = time.perf_counter()
    check()
    t_check = time.perf_counter() - t0
    print(f"level check: {counts['tried']} files tried in {t_check:.1f} s")
    print(f"  accepted                  {counts['accepted']}")
    print(f"  refused with one line     {counts['refused']}")
    print(f"  tracebacks                {counts['traceback']}")
    top = ", ".join(f"{k} {n}" for k, n in refusals.most_common(12))
    print(f"  most refused: {top}")

    runs: collections.Counter[str] = collections.Counter()
    reasons: collections.Counter[str] = collections.Counter()
    n_run = min(args.run_accepted, len(accepted))
    t1 = time.perf_counter()
    if n_run:
        step = len(accepted) / n_run
        for i in range(n_run):
            how, level = accepted[int(i * step)]
            try:
                r = lf.run_briefly(level, args.seconds, wall_limit=args.wall_limit)
            except Exception:  # noqa: BLE001
                runs["traceback"] += 1
                failures.append((f"run of {how}", traceback.format_exc()))
                continue
            runs[r.status] += 1
            if r.reason:
                reasons[r.reason] += 1
        t_run = time.perf_counter() - t1
        print(f"accepted mutants run {args.seconds:g} s headless: {n_run} in {t_run:.1f} s")
        print(f"  ran the whole span        {runs['ran']}")
        print(f"  stopped themselves        {runs['stopped']}")
        for why, n in reasons.most_common():
            print(f"    {n:4d}  {why}")
        cut = f"cut at {args.wall_limit:g} s wall time"
        print(f"  {cut:<26}{runs['cut']}")
        print(f"  tracebacks                {runs['traceback']}")
    print(f"wall time {time.perf_counter() - t0:.1f} s")
    for how, tb in failures[:5]:
        print(f"\n--- traceback from {how[:300]}\n{tb}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
