"""Stepping a level headless: progress display, signals and why a run ended (the run loop
is :mod:`chainfountain.headless.stepper`)."""

from __future__ import annotations

import contextlib
import math
import signal
import sys
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass

MAX_PROFILES = 2000
"""Per-link profiles kept in memory by a headless run (thinned evenly beyond; 40 s at 50 Hz)."""
MAX_SAMPLES = 100_000
"""Scalar samples kept by a headless run (thinned evenly beyond: 1000 s at 100 Hz)."""
LOG_PROGRESS_EVERY = 30.0
"""Wall seconds between progress lines when stderr is not a terminal (a log file)."""


class _LogProgress:
    """Progress for a log file (stderr not a terminal): one line at most every
    :data:`LOG_PROGRESS_EVERY` wall seconds, so a long run in a batch job is not silent."""

    def __init__(self, total: float, label: str) -> None:
        self.total, self.label = total, label
        self.n = 0.0
        self.t0 = self.last = time.perf_counter()

    def update(self, dn: float) -> None:
        self.n += dn
        now = time.perf_counter()
        if now - self.last < LOG_PROGRESS_EVERY:
            return
        self.last = now
        el = now - self.t0
        left = el * (self.total - self.n) / self.n if self.n > 0 else math.nan
        print(f"  {self.label}: {self.n:.2f}/{self.total:.2f} sim s "
              f"({100 * self.n / self.total:.0f} %), {el:.0f} s elapsed, about {left:.0f} s left",
              file=sys.stderr, flush=True)

    def __enter__(self) -> _LogProgress:
        return self

    def __exit__(self, *exc: object) -> None:
        return None


def _progress(total: float, enabled: bool, label: str = "run"):
    """A tqdm bar on a terminal, :class:`_LogProgress` lines otherwise, nothing if disabled."""
    from tqdm import tqdm

    if enabled and not sys.stderr.isatty():
        return _LogProgress(total, label)
    return tqdm(total=round(total, 3), unit="sim s", disable=not enabled,
                bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} sim s [{elapsed}<{remaining}]",
                file=sys.stderr, leave=False)


class Interrupted(Exception):
    """SIGINT (Ctrl-C) or SIGTERM arrived while a headless run was simulating."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


@dataclass
class Ending:
    """Why a run stopped before its duration."""

    cause: str
    """``"machine"`` (the apparatus cannot go on), ``"diverged"`` (the watchdog) or
    ``"interrupted"`` (a signal)."""
    reason: str
    signum: int | None = None


@contextlib.contextmanager
def _signals_raise() -> Iterator[None]:
    """While simulating, SIGINT and SIGTERM raise :class:`Interrupted` (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: object) -> None:
        raise Interrupted(signum)

    old = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)


@contextlib.contextmanager
def _signals_deferred(received: list[int]) -> Iterator[None]:
    """While the outputs are written, a signal is noted in ``received`` (and said), not
    obeyed, so no output is left half-written; the caller exits afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: object) -> None:
        received.append(signum)
        print(f"chainfountain: {signal.Signals(signum).name}: finishing the outputs first",
              file=sys.stderr, flush=True)

    old = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)
