"""Figures that run the simulator: a shipped feed level against the paper's theory."""

from __future__ import annotations

from matplotlib.figure import Figure

from chainfountain.figures.hooks import fig_sim_vs_theory

SIM_LEVEL = "paper_tall"
SETTLE_S = 1.5
WINDOW_S = 2.0


def fig_sim_vs_theory_run(level_name: str = SIM_LEVEL) -> tuple[Figure, str]:
    """Run ``level_name`` (settle, then average over a window) and plot it over the catenary."""
    from chainfountain.level import io, library
    from chainfountain.sim import Recorder, Simulation
    from chainfountain.theory import Fountain

    level = io.load(library.resolve(level_name))
    sim = Simulation(level.sim)
    sim.advance(SETTLE_S)
    rec = Recorder(sim)
    sim.advance(WINDOW_S)
    s = rec.summary(window=WINDOW_S)
    ref = sim.reference
    if ref is None:
        raise ValueError(f"level {level_name} has no theory reference")
    feed = level.sim.feed
    f = Fountain.from_launch(feed.speed, feed.launch_angle, feed.drop, g=level.sim.gravity)
    tx, ty = f.curve(400)
    ex = s.extras
    # Launch frame -> the theory's vertex frame.
    sx, sy = ex["x"] - ref.x_rise, ex["y"] - ref.h
    fig, caption = fig_sim_vs_theory(
        sx, sy, tx, ty, sy, ex["tension_bar"], f.q, f.k,
        title=f"Level {level_name}: {sim.n_free} links of "
        f"{level.sim.chain.link_length * 100:g} cm, mean over {WINDOW_S:g} s after {SETTLE_S:g} s",
    )
    caption += (f" Simulated with level {level_name} (feed {feed.speed:g} m/s, absorbing floor "
                f"{feed.drop:g} m below the launch point, so Tbar_E = 0).")
    return fig, caption
