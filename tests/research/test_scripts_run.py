"""Every research script still starts: ``python -m research.NAME --help`` from the repository
root, and every ``chainfountain``/``research`` name a research module imports (at the top
or inside a function) still exists.

Nothing else runs the scripts (they take minutes to hours), so without this a script whose
imports rot is only found when someone next needs it. ``--help`` parses the arguments and
exits before any study runs; it needs no display. The scripts are run as ``-m`` runs them
(``runpy.run_module`` as ``__main__``) inside this process, which has imported numpy,
pymunk and the package once (44 scripts in about 2 s, where a fresh interpreter each took
29 s on 2 cores); one of them also in a fresh interpreter from the repository root.
"""

from __future__ import annotations

import ast
import contextlib
import importlib
import io
import os
import runpy
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
RESEARCH = ROOT / "research"
SCRIPTS = sorted([p.stem for p in RESEARCH.glob("*.py") if p.stem != "__init__"]
                 + [f"contact_region.{p.stem}" for p in (RESEARCH / "contact_region").glob("*.py")
                    if p.stem != "__init__"])
"""The scripts run as ``python -m research.NAME``: the top-level modules and the study
folders' (``contact_region``)."""
FIRST_PARTY = ("chainfountain", "research")


def _help(name: str) -> tuple[str, int, str]:
    """``python -m research.NAME --help`` in this process: exit code and output."""
    out, argv, code = io.StringIO(), sys.argv, 0
    sys.argv = [f"research.{name}", "--help"]
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out), \
                warnings.catch_warnings():
            # a script another one imports is in sys.modules already; -m runs a fresh
            # copy as __main__ all the same, as here
            warnings.filterwarnings("ignore", "'research\\..*' found in sys.modules",
                                    RuntimeWarning)
            runpy.run_module(f"research.{name}", run_name="__main__", alter_sys=True)
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except Exception as exc:  # an import that rotted: reported, not raised
        code, _ = 1, out.write(f"{type(exc).__name__}: {exc}")
    finally:
        sys.argv = argv
    return name, code, out.getvalue()


@pytest.mark.slow
def test_every_script_answers_help(monkeypatch) -> None:
    assert SCRIPTS, "no research scripts found"
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    results = [_help(name) for name in SCRIPTS]
    failed = [f"research.{n} (exit {rc}):\n{out[-1500:]}" for n, rc, out in results
              if rc != 0 or "usage:" not in out]
    assert not failed, "\n\n".join(failed)


def test_a_script_starts_in_a_fresh_interpreter_from_the_repository_root() -> None:
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", MPLBACKEND="Agg")
    env.pop("DISPLAY", None)
    r = subprocess.run([sys.executable, "-m", f"research.{SCRIPTS[0]}", "--help"], cwd=ROOT,
                       env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "usage:" in r.stdout, r.stdout + r.stderr


def _imported_names(path: Path) -> list[tuple[str, str | None]]:
    """``(module, name)`` for every absolute first-party import in ``path`` (``name`` is
    ``None`` for ``import module``)."""
    out: list[tuple[str, str | None]] = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out += [(a.name, None) for a in node.names if a.name.startswith(FIRST_PARTY)]
        elif (isinstance(node, ast.ImportFrom) and node.level == 0 and node.module
              and node.module.startswith(FIRST_PARTY)):
            out += [(node.module, a.name) for a in node.names]
    return out


@pytest.mark.parametrize("path", sorted(RESEARCH.rglob("*.py")),
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_every_imported_name_exists(path: Path) -> None:
    missing = []
    for module, name in _imported_names(path):
        try:
            mod = importlib.import_module(module)
        except ImportError as e:
            missing.append(f"{module}: {e}")
            continue
        if name is None or name == "*" or hasattr(mod, name):
            continue
        try:
            importlib.import_module(f"{module}.{name}")
        except ImportError:
            missing.append(f"{module}.{name}")
    assert not missing, f"{path.relative_to(ROOT)} imports names that are gone: {missing}"
