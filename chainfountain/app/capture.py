"""Screenshots and clips, written in background threads so the window never stalls.

Clips are MP4 when ``imageio`` with its ffmpeg plugin is installed and an
animated GIF otherwise (GIF frames are encoded with Pillow, which comes with
matplotlib); they are taken in simulated time. Frames are handed over as raw RGB bytes
through a bounded queue; the writer thread converts, quantises and writes them.
"""

from __future__ import annotations

import math
import queue
import threading
import time
from pathlib import Path

import pygame


def timestamp() -> str:
    return time.strftime("%Y%m%d-%H%M%S")


_CLAIMED: set[Path] = set()
_CLAIM_LOCK = threading.Lock()


def unique_path(folder: Path, stem: str, suffix: str) -> Path:
    """``folder/stem.suffix``, or with ``-2``, ``-3``... when that exists or was
    already handed out in this process (two captures in one second get two names
    even while the first is still being written in the background)."""
    with _CLAIM_LOCK:
        p = folder / f"{stem}{suffix}"
        i = 2
        while p.exists() or p in _CLAIMED:
            p = folder / f"{stem}-{i}{suffix}"
            i += 1
        if len(_CLAIMED) > 4096:  # bounded: old names exist on disk by now
            _CLAIMED.clear()
        _CLAIMED.add(p)
        return p


def save_png(surface: pygame.Surface, path: Path) -> Path:
    """Write ``surface`` to ``path`` as PNG (parent created), atomically."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".part.png")
    pygame.image.save(surface, str(tmp))
    tmp.replace(path)
    return path


class BackgroundSaver:
    """Saves PNG copies of surfaces in a worker thread."""

    def __init__(self) -> None:
        self._threads: list[threading.Thread] = []
        self.errors: list[str] = []
        self.done: list[Path] = []

    def save(self, surface: pygame.Surface, path: Path) -> None:
        copy = surface.copy()

        def work() -> None:
            try:
                self.done.append(save_png(copy, path))
            except (OSError, pygame.error) as exc:
                self.errors.append(f"screenshot failed: {exc}")

        t = threading.Thread(target=work, name="chainfountain-png", daemon=False)
        t.start()
        self._threads.append(t)
        self._threads = [th for th in self._threads if th.is_alive()]

    def wait(self, timeout: float = 30.0) -> None:
        for t in self._threads:
            t.join(timeout)
        self._threads.clear()


def mp4_available() -> bool:
    """True when imageio with an ffmpeg backend can write MP4."""
    try:
        import imageio.v2  # noqa: F401
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        return False
    return True


GIF_FRAME_BUDGET = 160e6
"""Bytes a GIF clip's frames may hold in memory (one byte per pixel once quantised): a
full-resolution scene of 590 x 760 pixels keeps up to 356 frames, 17.8 s at 20 frames/s
(a GIF's frame times are whole hundredths of a second, so 20 or 10 frames/s play at the
true speed; 15 would play 10 % fast); an MP4 streams to disk and stops at
``max_seconds``."""


class ClipRecorder:
    """Collects frames in simulated time and writes an animated GIF (or MP4) in a worker
    thread.

    Call :meth:`offer` every drawn frame with the simulation's time: the clip keeps one
    frame per ``1/fps`` s of *simulated* time, so it plays at the true speed whatever the
    machine managed (a frame drawn after a longer step is repeated, a paused or
    slow-motion stretch adds frames only as simulated time passes). ``crop`` (a rect of
    the surface) is what is recorded, at ``scale`` (1: full resolution). :meth:`stop`
    finishes the file in the background; :meth:`wait` blocks until it is written.
    """

    def __init__(self, path: Path, fps: float = 15.0, scale: float = 1.0,
                 max_seconds: float = 120.0, crop: pygame.Rect | None = None) -> None:
        self.path = path
        self.fps = fps
        self.scale = scale
        self.crop = crop
        self.max_frames = int(max_seconds * fps)
        self.frames = 0
        self.error: str | None = None
        self.finished = False
        self._t0: float | None = None
        self._q: queue.Queue = queue.Queue(maxsize=64)
        self._mp4 = path.suffix.lower() == ".mp4"
        if not self._mp4 and crop is not None:
            w, h = crop.size
            self.max_frames = min(self.max_frames,
                                  int(GIF_FRAME_BUDGET / max(1.0, w * h * scale * scale)))
        path.parent.mkdir(parents=True, exist_ok=True)
        self._thread = threading.Thread(target=self._work, name="chainfountain-clip",
                                        daemon=False)
        self._thread.start()
        self.recording = True

    @property
    def seconds(self) -> float:
        """Simulated seconds recorded so far."""
        return self.frames / self.fps

    def offer(self, surface: pygame.Surface, sim_time: float) -> bool:
        """Take this frame as often as simulated time asks (``sim_time``, s); returns False
        once the clip is full (then it stops itself)."""
        if not self.recording:
            return False
        if self._t0 is None or sim_time < self._t0 + (self.frames - 1) / self.fps - 1e-9:
            self._t0 = sim_time - self.frames / self.fps  # the start, or a reset (R)
        due = int(math.floor((sim_time - self._t0) * self.fps + 1e-6)) + 1
        n = min(due - self.frames, 4)  # more than 4 at once: a jump, not a slow machine
        if n <= 0:
            return True
        if due - self.frames > n:
            self._t0 = sim_time - (self.frames + n - 1) / self.fps
        src = surface.subsurface(self.crop) if self.crop is not None else surface
        block = 16 if self._mp4 else 2  # H.264 wants sizes divisible by 16
        w = max(block, int(src.get_width() * self.scale) // block * block)
        h = max(block, int(src.get_height() * self.scale) // block * block)
        if (w, h) != src.get_size():
            src = pygame.transform.smoothscale(src, (w, h))
        data = pygame.image.tobytes(src, "RGB")
        for _ in range(n):
            try:
                self._q.put((src.get_size(), data), timeout=1.0)
            except queue.Full:  # the writer is stuck: count the frame, keep the time
                pass
            self.frames += 1
            if self.frames >= self.max_frames:
                self.stop()
                return False
        return True

    def stop(self) -> None:
        """Stop taking frames; the file is finished in the background."""
        if self.recording:
            self.recording = False
            self._q.put(None)

    def wait(self, timeout: float | None = 120.0) -> bool:
        """Block until the file is written; True on success."""
        self.stop()
        self._thread.join(timeout)
        return self.finished and self.error is None

    @property
    def busy(self) -> bool:
        return self._thread.is_alive()

    # ------------------------------------------------------------------ worker
    def _work(self) -> None:
        try:
            if self._mp4:
                self._work_mp4()
            else:
                self._work_gif()
            self.finished = True
        except Exception as exc:  # noqa: BLE001 - reported in the window, never raised
            self.error = f"clip failed: {exc}"
            while True:  # drain so offer() never blocks
                try:
                    if self._q.get_nowait() is None:
                        break
                except queue.Empty:
                    break

    def _work_gif(self) -> None:
        from PIL import Image

        frames: list = []
        while True:
            item = self._q.get()
            if item is None:
                break
            size, data = item
            img = Image.frombytes("RGB", size, data)
            frames.append(img.quantize(colors=64, method=Image.Quantize.MEDIANCUT,
                                       dither=Image.Dither.NONE))
        if not frames:
            raise RuntimeError("no frames recorded")
        tmp = self.path.with_name(self.path.name + ".part.gif")
        frames[0].save(tmp, save_all=True, append_images=frames[1:],
                       duration=int(round(1000 / self.fps)), loop=0, optimize=False,
                       disposal=1)
        tmp.replace(self.path)

    def _work_mp4(self) -> None:
        import imageio.v2 as iio
        import numpy as np

        tmp = self.path.with_name(self.path.stem + ".part.mp4")
        writer = iio.get_writer(tmp, fps=self.fps, codec="libx264", quality=7)
        try:
            while True:
                item = self._q.get()
                if item is None:
                    break
                (w, h), data = item
                writer.append_data(np.frombuffer(data, dtype=np.uint8).reshape(h, w, 3))
        finally:
            writer.close()
        tmp.replace(self.path)
