"""Figure generation: files, atomic writes, captions, hooks with synthetic data."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from chainfountain import figures
from chainfountain.figures import fig_apparatus, fig_sim_vs_theory, save_figure
from chainfountain.figures.paper import example_fountain, fig_force_ranges

pytestmark = pytest.mark.xdist_group("figures")  # one worker draws the figures (20 s of run)


@pytest.fixture(scope="module")
def out(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, list[Path]]:
    d = tmp_path_factory.mktemp("figs")
    return d, figures.main(d, progress=False, dpi=60)


@pytest.mark.slow
def test_main_writes_all(out: tuple[Path, list[Path]]) -> None:
    d, written = out
    names = set(figures.FIGURES)
    assert names == {"sol", "schematic_chain_fountain", "force_ranges", "sim_vs_theory",
                     "apparatus"}
    expected = {d / f"{n}.{ext}" for n in names for ext in ("png", "svg", "txt")}
    assert set(written) == expected
    for p in expected:
        assert p.stat().st_size > 100
    assert not [p for p in d.iterdir() if p.name.startswith(".tmp-")]
    for n in names:
        assert (d / f"{n}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert b"<svg" in (d / f"{n}.svg").read_bytes()[:2000]
        assert (d / f"{n}.txt").read_text().startswith(f"Fig. {n}")


@pytest.mark.slow
def test_captions_carry_numbers(out: tuple[Path, list[Path]]) -> None:
    d, _ = out
    assert "44.20" in (d / "sol.txt").read_text()
    sch = (d / "schematic_chain_fountain.txt").read_text()
    from chainfountain.figures.paper import paper_stiff_fountains

    a = paper_stiff_fountains()["A"]
    assert f"A: h={a.h:.3f} m, l={a.l:.3f} m" in sch and "D: h=0.280 m, l=0.330 m" in sch
    assert "0.4301" in (d / "force_ranges.txt").read_text()


@pytest.mark.slow
def test_files_readable_by_others(out: tuple[Path, list[Path]]) -> None:
    d, written = out
    umask = os.umask(0)
    os.umask(umask)
    for p in written:
        assert p.stat().st_mode & 0o444 == 0o444 & ~umask


def test_unknown_name() -> None:
    with pytest.raises(KeyError):
        figures.main(Path("/nonexistent"), names=["nope"], progress=False)


def test_failed_save_leaves_no_temp(tmp_path: Path) -> None:
    fig, _ = fig_force_ranges(n=10)
    with pytest.raises(ValueError):
        save_figure(fig, tmp_path, "bad", "x", formats=("png", "no-such-format"))
    assert [p.name for p in tmp_path.iterdir()] == ["bad.png"]


def test_force_ranges_numbers() -> None:
    f = example_fountain()
    assert f.qH == pytest.approx(44.20, abs=0.01)
    assert f.k_max == pytest.approx(0.4301, abs=1e-4)


def test_apparatus_hook(tmp_path: Path) -> None:
    t = np.linspace(0, 1, 50)
    data = {
        "chain": np.c_[t, np.sin(3 * t)],
        "fountain": np.c_[t[:20], 1 - (t[:20] - 0.1) ** 2],
        "pulleys": [(0.0, 0.0, 0.05), (1.0, 0.0, 0.05)],
        "carts": [{"x": 0.5, "y": -0.2, "w": 0.1, "h": 0.05, "angle": 0.3}],
        "tracks": [((0.3, -0.3), (0.7, -0.1))],
        "forces": [
            {"x": 0.0, "y": 0.0, "fx": 0.0, "fy": 2.0, "label": "T0"},
            {"x": 1.0, "y": 0.0, "fx": 1.0, "fy": 0.0, "label": "TE"},
        ],
        "labels": [(0.5, 0.5, "beaker")],
    }
    fig, caption = fig_apparatus(data)
    arrows = [a for a in fig.axes[0].texts if a.get_text() == ""]
    assert len(arrows) == 2
    assert "apparatus" in caption
    paths = save_figure(fig, tmp_path, "apparatus", caption, dpi=50)
    assert all(p.exists() for p in paths)
    with pytest.raises(ValueError):
        fig_apparatus({"chain": np.zeros(5)})


def test_sim_vs_theory_hook(tmp_path: Path) -> None:
    f = example_fountain()
    tx, ty = f.curve(200)
    rng = np.random.default_rng(1)
    sx = tx[::4] + rng.normal(0, 1e-3, tx[::4].size)
    sy = ty[::4]
    Ty = np.linspace(-f.h - f.H, 0, 30)
    Tb = 1 - f.k / f.q + f.k * Ty + 0.01
    fig, caption = fig_sim_vs_theory(sx, sy, tx, ty, Ty, Tb, f.q, f.k, sim_y_spread=sy * 0 + 0.01)
    assert "RMS tension deviation 0.01" in caption
    rms = float(caption.split("RMS distance to the curve ")[1].split(" m")[0])
    assert 1e-4 < rms < 2e-3
    paths = save_figure(fig, tmp_path, "sim_vs_theory", caption, formats=("png",), dpi=50)
    assert [p.suffix for p in paths] == [".png", ".txt"]
    with pytest.raises(ValueError):
        fig_sim_vs_theory(sx, sy[:-1], tx, ty, Ty, Tb, f.q, f.k)


@pytest.mark.slow
def test_sim_vs_theory_states_its_agreement_with_the_paper(
        out: tuple[Path, list[Path]]) -> None:
    """The figure runs ``paper_tall`` as it ships until it is steady and says so; what its
    caption states about the agreement is what the paper predicts: the averaged chain
    within a centimetre of the catenary (RMS), the tension within 0.01 of
    ``1 - k/q + k*y``, the vertex height within 1 % of the paper's."""
    import re

    d, _ = out
    cap = (d / "sim_vs_theory.txt").read_text()
    since = float(re.search(r"steady since ([\d.]+) s", cap).group(1))
    t0 = float(re.search(r"mean over ([\d.]+)-([\d.]+) s", cap).group(1))
    assert since <= t0, cap
    assert float(re.search(r"RMS distance to the curve ([\d.e-]+) m", cap).group(1)) < 0.01
    assert float(re.search(r"RMS tension deviation ([\d.e-]+?)\.\s", cap).group(1)) < 0.01
    vertex = float(re.search(r"\(([+-][\d.]+) %\)\.$", cap.strip()).group(1))
    assert abs(vertex) < 1.0, cap


def test_sim_vs_theory_says_when_its_run_is_not_steady() -> None:
    """Too short a run (2.5 s: the fountain is still forming from its stub) is drawn, and
    the caption says it is not steady."""
    from chainfountain.figures.simulated import fig_sim_vs_theory_run

    fig, cap = fig_sim_vs_theory_run(duration=2.5)
    import matplotlib.pyplot as plt

    plt.close(fig)
    assert "NOT steady over the window" in cap
