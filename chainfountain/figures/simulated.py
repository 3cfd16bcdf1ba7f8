"""Figures that run the simulator: a shipped feed level against the paper's theory."""

from __future__ import annotations

from matplotlib.figure import Figure

from chainfountain.figures.hooks import fig_sim_vs_theory

SIM_LEVEL = "paper_tall"
DURATION_S = 20.0
"""Simulated seconds of the run: ``paper_tall`` forms from its stub in 8-10 s, so 20 s
leave it steady for at least the window (``chainfountain run``'s default for a fed level
that starts from its stub)."""
WINDOW_S = 2.0
"""The last simulated seconds the figure averages."""


def fig_sim_vs_theory_run(level_name: str = SIM_LEVEL,
                          duration: float = DURATION_S) -> tuple[Figure, str]:
    """Run ``level_name`` as it ships for ``duration`` s, average its last
    :data:`WINDOW_S` s and plot it over the catenary. The caption says whether the run
    was steady over that window (``recording.steady_tolerance``) and how far the measured
    vertex lies from the paper's."""
    from chainfountain.level import io, library
    from chainfountain.sim import Recorder, Simulation
    from chainfountain.theory import Fountain

    level = io.load(library.resolve(level_name))
    sim = Simulation(level.sim)
    rec = Recorder(sim, max_profiles=4 * int(WINDOW_S / level.sim.recording.sample_interval))
    sim.advance(duration)
    steady = rec.steady_from()
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
    when = (f"steady since {steady:.1f} s" if steady is not None and steady <= s.t0
            else "NOT steady over the window: compare with care")
    fig, caption = fig_sim_vs_theory(
        sx, sy, tx, ty, sy, ex["tension_bar"], f.q, f.k,
        title=f"Level {level_name}: {sim.n_free} links of "
        f"{level.sim.chain.link_length * 100:g} cm, mean over {s.t0:.1f}-{s.t1:.1f} s "
        f"({when})",
    )
    err = s.vertex_y / ref.h - 1.0
    caption += (f" Simulated with level {level_name} as it ships (from its stub, feed "
                f"{feed.speed:g} m/s, absorbing floor {feed.drop:g} m below the launch "
                f"point, so Tbar_E = 0) for {duration:g} s, {when}; mean over "
                f"{s.t0:.1f}-{s.t1:.1f} s. Vertex height {s.vertex_y:.4f} m against the "
                f"paper's {ref.h:.4f} m ({100 * err:+.2f} %).")
    return fig, caption
