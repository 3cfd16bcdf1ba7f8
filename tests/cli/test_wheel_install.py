"""An install that is not this checkout works from any folder: the wheel carries the
levels and everything else a run reads.

How, and why so: the package is copied out of the checkout (so nothing of the checkout
can be found by accident) and built into a wheel with this environment's setuptools,
offline (``pip wheel --no-deps --no-build-isolation``). The wheel goes into a fresh
virtual environment made without pip, installed by this environment's pip (``--python``),
``--no-deps``: the real dependencies (numpy, pymunk, pygame-ce, ...) come from this test
environment's site-packages through a ``.pth`` line in the new environment. A ``.pth``
line only adds a folder to ``sys.path``: the ``.pth`` files inside that folder are not
read, so this checkout's editable install (an ``__editable__`` finder found through its
own ``.pth``) stays out, and ``chainfountain`` can only be imported from the wheel, as
the test checks. Installing the dependencies again from the registry would test pip, not
the package, and cost minutes. The commands then run from an empty folder elsewhere."""

from __future__ import annotations

import os
import shutil
import site
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run(*args: str, cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    r = subprocess.run(list(args), cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, (args, r.returncode, r.stdout[-2000:], r.stderr[-2000:])
    return r


@pytest.mark.slow
def test_a_wheel_installed_elsewhere_runs_from_any_folder(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src / name)
    shutil.copytree(ROOT / "chainfountain", src / "chainfountain",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    _run(sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "--no-build-isolation",
         "--wheel-dir", str(tmp_path / "dist"), str(src), cwd=tmp_path)
    (wheel,) = (tmp_path / "dist").glob("chainfountain-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    shipped = {p.name for p in (ROOT / "chainfountain" / "levels").glob("*.toml")}
    assert {n.rsplit("/", 1)[1] for n in names if n.startswith("chainfountain/levels/")} \
        == shipped
    assert not [n for n in names if n.startswith(("tests/", "docs/", "research/"))]

    venv = tmp_path / "venv"
    _run(sys.executable, "-m", "venv", "--without-pip", str(venv), cwd=tmp_path)
    py = venv / "bin" / "python"
    purelib = subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()"
                              "['purelib'])"], capture_output=True, text=True,
                             check=True).stdout.strip()
    deps = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"],
            *site.getsitepackages()}
    Path(purelib, "test-dependencies.pth").write_text("\n".join(sorted(deps)) + "\n")
    _run(sys.executable, "-m", "pip", "--python", str(py), "install", "--quiet", "--no-deps",
         "--no-index", str(wheel), cwd=tmp_path)

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(SDL_VIDEODRIVER="dummy", CHAINFOUNTAIN_HOME=str(tmp_path / "home"),
               PATH=f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}")
    where = _run(str(py), "-c", "import chainfountain, sys; print(chainfountain.__file__)",
                 cwd=elsewhere, env=env).stdout.strip()
    assert Path(where).is_relative_to(venv), where
    cf = str(venv / "bin" / "chainfountain")
    assert _run(cf, "--version", cwd=elsewhere, env=env).stdout.startswith("chainfountain ")
    listed = _run(cf, "levels", cwd=elsewhere, env=env).stdout
    assert {line.split()[0] for line in listed.splitlines()} == {Path(n).stem for n in shipped}
    assert str(venv) in listed
    # the window itself (what 'chainfountain' opens), drawn off-screen for two frames
    _run(cf, "play", "beaker", "--frames", "2", "--screenshot", "shot.png", cwd=elsewhere,
         env=env)
    assert (elsewhere / "shot.png").stat().st_size > 1000
    _run(cf, "run", "beaker", "--headless", "--duration", "0.3", "--quiet", "--out", "b",
         cwd=elsewhere, env=env)
    assert (elsewhere / "b" / "summary.json").is_file()
    (elsewhere / "s.toml").write_text('base = "wide_low"\nduration = 0.2\n[grid]\n'
                                      '"feed.speed" = [4.0, 4.5]\n')
    r = _run(cf, "sweep", "s.toml", "--jobs", "2", "--quiet", "--out", "sw", cwd=elsewhere,
             env=env)
    assert "2 done" in r.stdout and (elsewhere / "sw" / "results.parquet").is_file()
