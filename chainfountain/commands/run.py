"""``chainfountain run LEVEL --headless``: run a level without a window and write results."""

from __future__ import annotations

import argparse
import sys

from chainfountain.commands.args import integer, number, path_arg
from chainfountain.errors import UserError
from chainfountain.exits import EXIT_HELP
from chainfountain.options import DURATION, SEED


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="run a level headless and write summary.json, CSVs and a snapshot",
        description="Run LEVEL (a .toml path or a shipped level name) without a window. "
        "Writes summary.json, tensions.csv, speed.csv and snapshot.png into --out (apparatus "
        "levels also apparatus.csv; the 'open' arrangement reaction.png; a scene level "
        "summary.json, probe_<name>.csv per probe and scene.png). FIELD=VALUE arguments "
        "change the level's fields first (chainfountain run paper_tall feed.speed=6 "
        "initial.seed=2), as a sweep's [changes] do. " + EXIT_HELP,
        allow_abbrev=False,
    )
    p.add_argument("level", metavar="LEVEL", help="level file or name (e.g. paper_tall)")
    p.add_argument("overrides", nargs="*", metavar="FIELD=VALUE",
                   help="set level fields first, checked as the level file is: any path of "
                   "docs/levels.md, list items included (feed.speed=6, carts[0].mass=0.2, "
                   "scene.pins[0].release=0.1, feed.drive=ideal_floor)")
    p.add_argument("--headless", action="store_true",
                   help="run without a window (the only mode of 'run'; accepted for clarity)")
    p.add_argument("--duration", type=number(DURATION.what, min=DURATION.min,
                                             min_inclusive=DURATION.min_inclusive,
                                             max=DURATION.max),
                   default=None, help="simulated seconds (default 8; 20 for a fed level that "
                   "starts from its stub, to form and then be averaged, 40 for an ideal "
                   "machine's, which settles after its starter; 20 for an apparatus level "
                   "started from rest; one without a treadmill: its apparatus.duration; a "
                   "scene or beaker: its own duration)")
    p.add_argument("--out", type=path_arg("an output folder"), default=None,
                   help="output folder (default runs/<level name>)")
    p.add_argument("--seed", type=integer(SEED.what, min=SEED.min), default=None,
                   help="override the level's random seed (kind 'feed'; kind 'scene' with "
                   "scene.jitter; kinds 'beaker' and 'apparatus': a seed above 0 nudges "
                   "every moving body by 1e-12 of its velocity, which picks another of "
                   "the run's chaotic outcomes)")
    p.add_argument("--error-bars", action="store_true",
                   help="also estimate the discretisation error (kind 'feed': two short runs "
                   "from the catenary at the level's link length and step and at half of "
                   "both, as 'chainfountain converge'; into summary.json's error_bars. Kind "
                   "'apparatus': the level again at half its step, how far that moves the "
                   "speed and the flight's figures; into apparatus.flight.step)")
    p.add_argument("--no-refine", action="store_true",
                   help="a scene with a closed form: skip its second run at half the step "
                   "(most of the command's time); its figures then carry no step error bar, "
                   "and summary.json's closed_form_step says why")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


NO_REFINE = "chainfountain run --no-refine skipped the run at half the step"
"""Why a scene's figures have no step error bar when ``--no-refine`` is given."""


def run(args: argparse.Namespace) -> int:
    from chainfountain.headless import (
        RunSummary,
        apparatus_refine,
        check_run,
        default_duration,
        default_out_dir,
        describe_outputs,
        exit_status,
        prepare_out_dir,
        run_level,
        scene_refine,
    )
    from chainfountain.level import io, library
    from chainfountain.level.io import LevelError
    from chainfountain.sim.kinds import kind_of

    level = overridden(io.load(library.resolve(args.level)), args.overrides)
    check_run(level, args.duration, args.seed, names=("argument --duration", "argument --seed"))
    kind = kind_of(level.sim)
    rerun = args.error_bars and kind.half_step_bars  # no error model: again at dt/2
    if args.error_bars and not rerun:
        from chainfountain.refine import refined_config

        try:  # the refinement's checks, before anything is written
            refined_config(level.sim, 2, level.meta.name)
        except UserError as exc:
            raise UserError(f"argument --error-bars: {exc}; a contact machine (kind "
                            "'apparatus') is run again at half its step") from None
    if rerun:
        if args.no_refine:
            raise UserError("argument --no-refine: not allowed with --error-bars, which "
                            "runs this level again at half its step")
        try:
            io.check_consistency(apparatus_refine.halved(level), "at half the step")
        except LevelError as exc:
            raise UserError(f"argument --error-bars: {exc}") from None
    out = prepare_out_dir(args.out or default_out_dir(level))
    bars = None
    if args.error_bars and not rerun:
        from chainfountain.refine import refine

        print("estimating the discretisation error (chainfountain converge) ...",
              file=sys.stderr)
        bars = refine(level.sim, level.meta.name, progress=None if args.quiet else (
            lambda m: print("  " + m, file=sys.stderr, flush=True))).as_dict()
    duration = args.duration or default_duration(level)
    scene_again = not kind.fountain and scene_refine.refusal(level) is None
    again = ""
    if rerun or (scene_again and not args.no_refine):
        again = ", then again at half its step for the figures' step error"
    print(f"running {level.meta.name} headless for {duration:g} simulated s{again} ...",
          file=sys.stderr)
    half: bool | str = rerun
    if not kind.fountain:
        half = NO_REFINE if args.no_refine else True
    path = run_level(level, out, duration, seed=args.seed, progress=not args.quiet,
                     error_bars=bars, half_step=half)
    summary = RunSummary.load(path)
    print(describe_outputs(path, summary))
    return exit_status(summary)


def overridden(level, overrides: list[str]):
    """``level`` with the command line's ``FIELD=VALUE`` arguments set (each value read as
    its field's type; validated as a level file: one line naming the field otherwise)."""
    from chainfountain.level import paths
    from chainfountain.study import with_changes

    if not overrides:
        return level
    changes = {}
    for arg in overrides:
        field, eq, text = arg.partition("=")
        if not eq or not field:
            raise UserError(f"argument FIELD=VALUE: {arg!r} has no '='; allowed: a field "
                            "path, '=' and a value, e.g. feed.speed=6")
        changes[field] = paths.parse_value(field, text, "argument FIELD=VALUE")
    return with_changes(level, changes, where="argument FIELD=VALUE")
