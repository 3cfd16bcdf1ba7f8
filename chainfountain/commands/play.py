"""``chainfountain play [LEVEL]``: the interactive window (headless without a display)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from chainfountain.commands.args import integer, path_arg, shown, writable_file
from chainfountain.errors import UserError

MAX_FRAMES = 216_000
"""Most frames ``--frames`` renders: an hour of simulated time at 60 frames per second."""


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(p) for p in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{shown(text[:40])} is not a window size; allowed: WIDTHxHEIGHT, e.g. 1280x760"
        ) from None
    if not (640 <= w <= 8000 and 400 <= h <= 8000):
        raise argparse.ArgumentTypeError(
            f"{w:.6g}x{h:.6g} is out of range; allowed: width 640-8000, height 400-8000 pixels")
    return w, h


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "play",
        help="open the interactive window on a level (default: the built-in level)",
        description=(
            "Open the chain fountain window on LEVEL (a .toml file, or the name of a level "
            "shipped or in the user folder). Without a display it runs the level headless. "
            "--frames N renders N frames off-screen (SDL dummy driver, 1/60 s of simulated "
            "time each) and exits; --screenshot FILE saves the last one as PNG."
        ),
        allow_abbrev=False,
    )
    p.add_argument("level", nargs="?", metavar="LEVEL", help="level file or name")
    p.add_argument("--frames", type=integer("a number of frames", min=1, max=MAX_FRAMES),
                   metavar="N",
                   help="render N frames off-screen and exit")
    p.add_argument("--screenshot", type=path_arg("a .png file"), metavar="FILE.png",
                   help="with --frames: save the last frame as PNG (default 120 frames)")
    p.add_argument("--size", type=_size, metavar="WxH", help="window size (default 1280x760)")
    p.add_argument("--paused", action="store_true", help="start paused")
    p.add_argument("--projector", action="store_true",
                   help="projector mode: larger text and parts, the window's size kept "
                   "(P in the window)")
    p.add_argument("--out", type=path_arg("an output folder"), metavar="DIR",
                   help="output folder of a headless run (no display); "
                   "default runs/<level name>")
    p.set_defaults(func=run)


def resolve_level(text: str) -> Path:
    """A level file path from a path or a level name (shipped or in the user folder)."""
    from chainfountain.level import library

    return library.resolve(text)


def run(args: argparse.Namespace) -> int:
    from chainfountain.level import io

    level = None
    source = None
    refused: UserError | None = None
    if args.level is not None:
        try:
            source = resolve_level(args.level)
            level = io.load(source)
        except UserError as exc:  # one line; in a window it is also shown there
            refused, source = exc, None
    if args.screenshot is not None and args.screenshot.suffix.lower() != ".png":
        raise UserError(f"argument --screenshot: {str(args.screenshot)!r} must end in .png")
    offscreen = args.frames is not None or args.screenshot is not None
    if offscreen and args.out is not None:
        raise UserError(f"argument --out: {str(args.out)!r} has no effect with --frames or "
                        "--screenshot (it is the folder of a headless run without a display); "
                        "allowed: --out without --frames and --screenshot")
    if args.screenshot is not None:
        writable_file(args.screenshot, "--screenshot")
    from chainfountain.app import launch

    if refused is not None and offscreen:
        raise refused
    if offscreen:
        frames = args.frames if args.frames is not None else 120
        return launch.open_app(level, source, frames=frames, screenshot=args.screenshot,
                               size=args.size, offscreen=True, paused=args.paused,
                               projector=args.projector)
    ok, why = launch.display_available()
    if refused is not None and not ok:
        raise refused
    if not ok:
        from chainfountain.app.session import default_level

        return launch.run_headless(level or default_level(), why, out_dir=args.out)
    if refused is not None:  # a teacher looks at the screen: the window says it too
        print(f"chainfountain: error: {refused}", file=sys.stderr)
        launch.open_app(None, None, size=args.size, projector=args.projector,
                        notice=refused_notice(refused))
        return 2
    return launch.open_app(level, source, size=args.size, paused=args.paused,
                           projector=args.projector)


def refused_notice(exc: UserError) -> str:
    """What the window says, paused on the default level, when the level asked for on the
    command line could not be opened."""
    return (f"could not open that level: {exc}. The window shows the default level "
            "instead; L opens another")
