"""The pictures of the window in the docs, made again.

Usage::

    xvfb-run -s "-screen 0 1920x1080x24" .venv/bin/python -m research.window_pictures window
    .venv/bin/python -m research.window_pictures offscreen
    xvfb-run -s "-screen 0 1920x1080x24" .venv/bin/python -m research.window_pictures clip

``window`` opens the real window (1920x1080, projector mode) on every demonstration level
(the picker's levels that form from rest), lets it run ``--seconds`` of wall time from its
start, takes a picture of the whole window in the student view, presses E and takes one in
the expert view (``docs/img/window/<level>_student.png``, ``_expert.png``; the screen is read
with ImageMagick's ``import``, the keys sent with ``xdotool``, both from Debian's packages),
and writes ``docs/window_pictures.md``. ``clip`` records 2 s of ``apparatus_special_gripped``
steady in the window (G, then G again: ``docs/img/window/flow.gif``). ``offscreen`` renders
the pictures of docs/apparatus.md at the times their captions give (SDL's dummy driver,
1280x760, every frame 1/60 s of simulated time, so the same picture every time).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "img" / "window"
CLI = [sys.executable, "-m", "chainfountain"]


def demo_levels() -> list[str]:
    from chainfountain.app import paths

    out = []
    for _label, path in paths.list_levels()[1:]:
        if path is None:
            break
        out.append(path.stem)
    return out


def _window_id(timeout: float = 20.0) -> str:
    """The window's X id, read off ``xwininfo -root -tree`` (the title is "chainfountain";
    with no window manager ``xdotool search --name`` finds nothing)."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        r = subprocess.run(["xwininfo", "-root", "-tree"], capture_output=True, text=True)
        for line in r.stdout.splitlines():
            if '"chainfountain"' in line:
                return line.split()[0]
        time.sleep(0.3)
    raise RuntimeError("no chainfountain window appeared")


def _shot(path: Path) -> None:
    subprocess.run(["import", "-window", "root", str(path)], check=True)
    from PIL import Image

    img = Image.open(path).convert("RGB")
    img.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(path, optimize=True)


def _key(win: str, name: str) -> None:
    """Press a key in the window as a person does (the focus on it, then XTEST; a key sent
    to a window with ``--window`` is a synthetic event SDL ignores)."""
    subprocess.run(["xdotool", "windowfocus", "--sync", win], check=False,
                   capture_output=True)
    subprocess.run(["xdotool", "key", name], check=True)


def window(seconds: float) -> None:
    """Student and expert pictures of every demo level in a real window."""
    OUT.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, CHAINFOUNTAIN_NO_AUTOSAVE="1",
               CHAINFOUNTAIN_HOME="/tmp/chainfountain-pictures")
    rows = []
    for name in demo_levels():
        proc = subprocess.Popen(CLI + ["play", name, "--size", "1920x1080", "--projector"],
                                env=env, cwd=ROOT)
        try:
            win = _window_id()
            time.sleep(seconds)
            _shot(OUT / f"{name}_student.png")
            _key(win, "e")
            time.sleep(1.5)
            _shot(OUT / f"{name}_expert.png")
        finally:
            proc.terminate()
            proc.wait(timeout=20)
        rows.append(name)
        print(f"{name}: pictures taken", flush=True)
    write_page(rows, seconds)


def write_page(names: list[str], seconds: float) -> None:
    from chainfountain.app import paths
    from chainfountain.level import library

    lines = ["# The window on every demonstration level", "",
             "Each demonstration level (those that start at rest and form their fountain) in",
             "a real 1920x1080 window under Xvfb, in projector mode, "
             f"{seconds:g} s of wall time after it opened:",
             "first the student view (the level's own sliders, plain words), then the expert "
             "view",
             "(E: every field, the paper's symbols, the graphs). Made by `xvfb-run -s "
             '"-screen 0',
             '1920x1080x24" .venv/bin/python -m research.window_pictures window`.', ""]
    for name in names:
        title = paths.level_title(library.resolve(name))
        lines += [f"## {title} (`{name}`)", "",
                  f"![{name}, student view](img/window/{name}_student.png)", "",
                  f"![{name}, expert view](img/window/{name}_expert.png)", ""]
    (ROOT / "docs" / "window_pictures.md").write_text("\n".join(lines))


def clip(name: str, wait: float, length: float) -> None:
    """A clip of a steady fountain from the window (G starts and stops it)."""
    OUT.mkdir(parents=True, exist_ok=True)
    home = Path("/tmp/chainfountain-pictures")
    shutil.rmtree(home / "captures", ignore_errors=True)
    env = dict(os.environ, CHAINFOUNTAIN_NO_AUTOSAVE="1", CHAINFOUNTAIN_HOME=str(home))
    proc = subprocess.Popen(CLI + ["play", name, "--size", "1920x1080", "--projector"],
                            env=env, cwd=ROOT)
    try:
        win = _window_id()
        time.sleep(wait)
        _key(win, "g")
        time.sleep(length)
        _key(win, "g")
        time.sleep(8.0)  # the clip is written in the background
    finally:
        proc.terminate()
        proc.wait(timeout=30)
    clips = sorted((home / "captures").glob("*.gif"))
    if not clips:
        raise RuntimeError("no clip was written")
    shrink(clips[-1], OUT / "flow.gif", 0.5)
    print(f"clip: {OUT / 'flow.gif'} ({(OUT / 'flow.gif').stat().st_size / 1e6:.1f} MB)")


def shrink(src: Path, dst: Path, scale: float) -> None:
    """A GIF at ``scale`` of its size (for the docs: the window's clip is full size)."""
    from PIL import Image, ImageSequence

    gif = Image.open(src)
    w, h = gif.size
    size = (int(w * scale) // 2 * 2, int(h * scale) // 2 * 2)
    frames = [f.convert("RGB").resize(size, Image.Resampling.LANCZOS).quantize(
        colors=64, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        for f in ImageSequence.Iterator(gif)]
    frames[0].save(dst, save_all=True, append_images=frames[1:], loop=0, optimize=True,
                   duration=gif.info.get("duration", 50), disposal=1)


OFFSCREEN = (
    # level, seconds, file, window size, expert view, (at s, field, value) or None
    ("ideal_fold", 10.0, "ideal_fold_window.png", (1280, 760), True, None),
    ("ideal_special", 12.0, "ideal_special_window.png", (1280, 760), True, None),
    ("apparatus_special", 4.0, "apparatus_special_window.png", (1280, 760), True, None),
    ("ideal_open", 14.0, "ideal_open_window.png", (1280, 760), True, None),
    ("apparatus_fold_gripped", 10.2, "apparatus_fold_gripped_window.png", (1280, 760), True,
     None),
    ("apparatus_fold_gripped", 15.0, "apparatus_fold_gripped_follow.png", (1280, 760), True,
     (3.0, "carts[0].mass", 0.027)),
    ("beaker", 13.0, "beaker_window.png", (1280, 800), False, None),
    ("apparatus_fountain_d_kmax", 1.03, "apparatus_fountain_d_kmax_window.png", (1280, 760),
     False, None),
    ("apparatus_fountain_d", 1.03, "apparatus_fountain_d_window.png", (1280, 760), False,
     None),
)
"""The docs' off-screen pictures of the window (docs/apparatus.md, docs/beaker.md): each
frame 1/60 s of simulated time, so the same picture every time."""


def offscreen() -> None:
    """The docs' pictures, rendered off-screen at the times of their captions."""
    os.environ["SDL_VIDEODRIVER"] = "dummy"
    import pygame

    from chainfountain.app.session import Session
    from chainfountain.app.window import App
    from chainfountain.level import io, library

    img = ROOT / "docs" / "img"
    for name, seconds, file, size, expert, change in OFFSCREEN:
        app = App(Session(io.load(library.resolve(name))), size=size, offscreen=True)
        try:
            if expert:
                app.toggle_expert()
            while app.session.sim.time < seconds - 1e-9:
                if change is not None and app.session.sim.time >= change[0]:
                    app.set_field(change[1], change[2])
                    change = None
                app.run_frame()
            app.session.messages.clear()
            app._plot_cache = app._ro = None
            app.draw()
            pygame.image.save(app.screen, str(img / file))
        finally:
            app.finish()
        print(f"{file}: {app.session.sim.time:.2f} s")
    from_rest(img / "apparatus_fold_gripped_from_rest.png")


def from_rest(path: Path) -> None:
    """apparatus_fold_gripped's scene at 0.77, 2.3 and 12 s from rest, side by side."""
    os.environ["SDL_VIDEODRIVER"] = "dummy"
    import pygame

    from chainfountain.app.session import Session
    from chainfountain.app.window import App
    from chainfountain.level import io, library

    app = App(Session(io.load(library.resolve("apparatus_fold_gripped"))), size=(1280, 760),
              offscreen=True)
    parts = []
    try:
        for t in (0.77, 2.3, 12.0):
            while app.session.sim.time < t - 1e-9:
                app.run_frame()
            app._still_rect = app.scene_rect  # the scene as pictures take it: no overlays
            app.draw()
            app._still_rect = None
            parts.append(app._still)
    finally:
        app.finish()
    w, h = parts[0].get_size()
    sheet = pygame.Surface((w, 3 * h))
    for i, p in enumerate(parts):
        sheet.blit(p, (0, i * h))
    pygame.image.save(sheet, str(path))
    print(f"{path.name}: 0.77, 2.3, 12 s")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("window", "clip", "offscreen"))
    ap.add_argument("--seconds", type=float, default=14.0,
                    help="wall seconds each level runs before its picture")
    args = ap.parse_args()
    if args.what == "window":
        window(args.seconds)
    elif args.what == "clip":
        clip("apparatus_special_gripped", 14.0, 2.0)
    else:
        offscreen()
    return 0


if __name__ == "__main__":
    sys.exit(main())
