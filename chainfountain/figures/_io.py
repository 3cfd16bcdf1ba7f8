"""Atomic figure output: PNG + SVG + caption text, each via temp file and ``os.replace``."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # headless; must precede pyplot (no-op if already Agg)

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

__all__ = ["atomic_write_bytes", "save_figure", "plt"]


def _umask() -> int:
    old = os.umask(0)
    os.umask(old)
    return old


def _tmp_in(directory: Path, suffix: str) -> tuple[int, Path]:
    """Temp file next to the target, with ordinary permissions (mkstemp makes 0600)."""
    fd, name = tempfile.mkstemp(prefix=".tmp-", suffix=suffix, dir=directory)
    os.chmod(name, 0o666 & ~_umask())
    return fd, Path(name)


def atomic_write_bytes(path: Path, data: bytes) -> Path:
    """Write ``data`` to ``path`` via a temp file in the same directory, then ``os.replace``."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = _tmp_in(path.parent, path.suffix)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def save_figure(
    fig: Figure,
    out_dir: Path,
    name: str,
    caption: str,
    formats: Sequence[str] = ("png", "svg"),
    dpi: int = 110,
) -> list[Path]:
    """Save ``fig`` as ``out_dir/<name>.<fmt>`` for each format plus ``<name>.txt`` (caption).

    Every file is written atomically; metadata dates are stripped so output is
    reproducible. The figure is closed afterwards.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    try:
        for fmt in formats:
            path = out_dir / f"{name}.{fmt}"
            fd, tmp = _tmp_in(out_dir, f".{fmt}")
            os.close(fd)
            meta = {"Date": None} if fmt == "svg" else {"Software": None} if fmt == "png" else {}
            try:
                fig.savefig(tmp, format=fmt, dpi=dpi, metadata=meta, bbox_inches="tight")
                os.replace(tmp, path)
            except BaseException:
                tmp.unlink(missing_ok=True)
                raise
            written.append(path)
        text = caption.strip() + "\n"
        written.append(atomic_write_bytes(out_dir / f"{name}.txt", text.encode()))
    finally:
        plt.close(fig)
    return written
