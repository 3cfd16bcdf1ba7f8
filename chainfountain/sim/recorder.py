"""Recording measurements of a running :class:`~chainfountain.sim.world.Simulation`.

A :class:`Recorder` attached to a simulation samples every ``sample_interval``
seconds: it reads all link velocities just before the sampled step and the full
state right after it (two batch calls) and, when read, derives the signed joint tension
(momentum balance, see :mod:`chainfountain.sim.measure`), chain speed, stretch
and geometry. :meth:`Recorder.summary` time-averages over a window and
compares with the paper's prediction.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from chainfountain.sim import fastbody
from chainfountain.sim.config import RecordingConfig
from chainfountain.sim.measure import (
    ChainState,
    Profiles,
    Sample,
    Summary,
    fit_catenary,
    joint_forces,
    landing_x,
    link_ends,
    signed_tension,
    steady_time,
    vertex_of,
)

if TYPE_CHECKING:
    from chainfountain.sim.world import Simulation


class Recorder:
    """Samples measurements of the free chain of a fed fountain.

    Parameters
    ----------
    sim:
        The simulation; the recorder attaches itself (``sim.recorder = self``).
    cfg:
        Sampling interval, averaging window, steady-state tolerance; defaults to
        ``sim.config.recording``.
    profiles:
        Also keep per-link profiles (tension, position, speed) of every sample,
        needed for the tension comparison in :meth:`summary`.
    max_profiles:
        Bound on the kept profiles (long headless runs): when exceeded, every
        other profile is dropped and from then on only every ``2**m``-th sample
        keeps its profile, so they stay evenly spaced in time. ``None`` keeps
        all (then ``profiles[i]`` belongs to ``samples[i]``; with a bound, use
        :attr:`Profiles.t`).
    max_samples:
        Bound on the kept scalar samples: when exceeded, every other sample is
        dropped and from then on the recorder samples half as often, so the
        samples stay evenly spaced in time and the memory stays bounded however
        long the run. ``None`` keeps all.
    """

    def __init__(self, sim: Simulation, cfg: RecordingConfig | None = None, *,
                 profiles: bool = True, max_profiles: int | None = None,
                 max_samples: int | None = None) -> None:
        self.sim = sim
        self.cfg = cfg if cfg is not None else sim.config.recording
        self.every = max(1, int(round(self.cfg.sample_interval / sim.dt)))
        self.keep_profiles = profiles
        if max_profiles is not None and max_profiles < 2:
            raise ValueError(f"max_profiles = {max_profiles}: at least 2 (or None)")
        if max_samples is not None and max_samples < 2:
            raise ValueError(f"max_samples = {max_samples}: at least 2 (or None)")
        self.max_profiles = max_profiles
        self.max_samples = max_samples
        self._stride = 1
        """Samples are taken at every ``every * _stride``-th step (doubles when thinned)."""
        self._profile_stride = 1
        self._n_analysed = 0
        self._samples: list[Sample] = []
        self._profiles: list[Profiles] = []
        self._raw: list[tuple] = []
        self._ap_samples: list = []
        sim.recorder = self

    def wants(self, step_index: int) -> bool:
        """True when step number ``step_index`` (1-based) is to be sampled."""
        if step_index % self.every:
            return False
        return self._stride == 1 or (step_index // self.every - 1) % self._stride == 0

    def clear(self) -> None:
        """Forget all samples."""
        self._samples.clear()
        self._profiles.clear()
        self._raw.clear()
        self._ap_samples.clear()
        self._stride = 1
        self._profile_stride = 1
        self._n_analysed = 0

    def _want_profile(self) -> bool:
        """Whether the sample being analysed keeps its profile (see ``max_profiles``)."""
        i = self._n_analysed
        self._n_analysed += 1
        return self.keep_profiles and i % self._profile_stride == 0

    def _add_profile(self, prof: Profiles) -> None:
        self._profiles.append(prof)
        if self.max_profiles is not None and len(self._profiles) > self.max_profiles:
            del self._profiles[1::2]
            self._profile_stride *= 2

    # ------------------------------------------------------------------ sampling
    def take(self, pre: ChainState, post: ChainState, contacts: np.ndarray | None = None) -> None:
        """Record the states before and after the last time step ``dt`` and the contact
        impulses on each link summed over its pymunk steps (analysed lazily).

        Only the raw arrays are stored here (the batch reads are fresh copies),
        so recording costs little more than the two batch reads; the derived
        quantities are computed when :attr:`samples` or :meth:`summary` is read.
        """
        sim = self.sim
        n = sim.n_free
        if n < 2:
            return
        app = getattr(sim, "apparatus", None)
        if app is not None:
            lo = app.lower
            roller = (app.upper.x, app.upper.speed, lo.x if lo else float("nan"),
                      lo.speed if lo else float("nan"))
            pivots, mouth = None, None
            if app.fold_guided:
                mouth = app.fold_mouth  # before the bookkeeping: this step's guided links
                # joint force sizes: the lower guide's correction (no contact involved)
                pivots = np.array([abs(lk.up_joint.impulse) if lk.up_joint is not None
                                   else np.nan for lk in sim.chain.links]) / sim.h
            pivot_x = None
            if app.gripped:
                # the joint forces' components along x: the gripped fold's plate strand
                # (its size rings, fastbody.pivot_impulse)
                pivot_x = np.array([fastbody.pivot_impulse(lk.up_joint)[0]
                                    if lk.up_joint is not None else np.nan
                                    for lk in sim.chain.links]) / sim.h
            lower = None
            if app.guided:  # 'open': which links the tail's grooves and the turn hold
                end = sim.chain.links[0].body
                lower = (app.tail_grooved, len(app.turn_held), end.mass, end.moment)
            self._raw.append(("apparatus", sim.time, pre.velocity, post, contacts, roller,
                              pivots, pre.angular_velocity, lower, pivot_x, mouth))
            return
        end_force = sim.ends.end_force
        if end_force is not None:  # the floor's pull is an external force on link 0
            if contacts is None:
                contacts = np.zeros((len(post.angle), 2))
            contacts[0] += np.asarray(end_force) * sim.dt
        tail = sim.slide_away  # its reaction is recorded from the first landed link on
        reaction = tail.plate_reaction if tail is not None and tail.links else float("nan")
        self._raw.append((sim.time, n, sim.ends.speed, sim.ends.floor_y, pre.velocity, post,
                          contacts, reaction))

    @property
    def samples(self) -> list[Sample]:
        """All recorded samples (derived on first access)."""
        self._process()
        return self._samples

    @property
    def profiles(self) -> list[Profiles]:
        """Per-link profiles of all samples (when ``profiles=True``)."""
        self._process()
        return self._profiles

    def _process(self) -> None:
        raw, self._raw = self._raw, []
        for rec in raw:
            if rec[0] == "apparatus":
                self._analyse_apparatus(*rec[1:])
            else:
                self._analyse(*rec)
        self._thin()

    def _thin(self) -> None:
        """Keep at most ``max_samples`` samples (see the class docstring)."""
        if self.max_samples is None or len(self._samples) <= self.max_samples:
            return
        del self._samples[1::2]
        if len(self._ap_samples) > len(self._samples):
            del self._ap_samples[1::2]
        self._stride *= 2

    @property
    def apparatus_samples(self) -> list:
        """Per-sample apparatus measurements
        (:class:`chainfountain.sim.apparatus_report.ApparatusSample`; apparatus levels only)."""
        self._process()
        return self._ap_samples

    def _analyse_apparatus(self, t: float, pre_vel: np.ndarray, post: ChainState,
                           contacts: np.ndarray, roller: tuple,
                           pivots: np.ndarray | None, pre_w: np.ndarray,
                           lower: tuple | None, pivot_x: np.ndarray | None,
                           mouth: int | None = None) -> None:
        from chainfountain.sim.apparatus_report import analyse

        sim = self.sim
        s, prof = analyse(sim.apparatus, t, pre_vel, post, contacts, sim.dt,
                          sim.chain.cfg.linear_density, roller, pivots, pre_w, lower,
                          pivot_x, mouth)
        self._ap_samples.append(s)
        sp = prof["speed"]
        self._samples.append(Sample(
            t=t, vertex_x=s.vertex_x, vertex_y=s.vertex_y, landing_x=s.end_x,
            speed_mean=s.v, speed_min=float(np.min(sp)), speed_max=float(np.max(sp)),
            stretch=s.stretch, n_free=s.n_flight, T0_bar=s.T0_bar))
        if self._want_profile():
            self._add_profile(Profiles(tension_bar=prof["tension_bar"], x=prof["x"],
                                       y=prof["y"], speed=sp, t=t))

    def _analyse(self, t: float, n: int, v_feed: float, floor_y: float, pre_vel: np.ndarray,
                 post: ChainState, contacts: np.ndarray | None, reaction: float) -> None:
        sim = self.sim
        chain = sim.chain
        L = chain.L
        pre = ChainState(position=post.position, angle=post.angle, velocity=pre_vel,
                         angular_velocity=post.angular_velocity)
        forces = joint_forces(pre, post, chain.mass, sim.dt, sim.g, n, contacts)
        tension, _ = signed_tension(forces, post, n)
        v = v_feed if v_feed > 0 else 1.0
        tbar = tension / (chain.cfg.linear_density * v * v)
        front, back = link_ends(post, L)
        free = np.empty((n + 1, 2))
        free[0] = front[0]
        m = min(n, len(front) - 1)
        free[1 : m + 1] = 0.5 * (back[:m] + front[1 : m + 1])
        if m < n:  # no upstream neighbour: the last free link's back end
            free[n] = back[n - 1]
        gaps = np.linalg.norm(back[:m] - front[1 : m + 1], axis=1)
        stretch = float(gaps.sum() / (n * L))
        speed = np.hypot(post.velocity[:n, 0], post.velocity[:n, 1])
        xv, yv = vertex_of(free)
        sm = float(speed.mean())
        self._samples.append(Sample(
            t=t, vertex_x=xv, vertex_y=yv,
            landing_x=landing_x(post, L, floor_y),
            speed_mean=sm, speed_min=float(speed.min()), speed_max=float(speed.max()),
            stretch=stretch, n_free=n, T0_bar=float(tbar[n - 1]), plate_reaction=reaction,
        ))
        if self._want_profile():
            self._add_profile(Profiles(
                tension_bar=tbar[::-1].copy(), x=free[1:, 0][::-1].copy(),
                y=free[1:, 1][::-1].copy(), speed=speed[::-1].copy(), t=t,
            ))

    # ------------------------------------------------------------------ readout
    def series(self, name: str) -> np.ndarray:
        """One recorded scalar (a :class:`Sample` field) as an array over samples."""
        return np.array([getattr(s, name) for s in self.samples], dtype=float)

    def steady_from(self, window: float | None = None) -> float | None:
        """Time from which vertex height and mean speed stay within the steady tolerance
        (``None`` if they never do, or for less than the level's averaging window
        ``recording.window``, as the window's "steady" readout asks: a run that settles
        in its last samples is not steady); ``window`` as in :meth:`summary`."""
        window = self.cfg.window if window is None else window
        t = self.series("t")
        tol, smooth = self.cfg.steady_tolerance, self.cfg.smoothing
        ts = steady_time(t, self.series("vertex_y"), tol, smooth, window)
        tv = steady_time(t, self.series("speed_mean"), tol, smooth, window)
        if ts is None or tv is None:
            return None
        since = max(ts, tv)
        return since if float(t[-1]) - since >= self.cfg.window - 1e-9 else None

    def summary(self, window: float | None = None, t_end: float | None = None) -> Summary:
        """Time averages over the last ``window`` seconds (ending at ``t_end``)."""
        if not self.samples:
            raise ValueError("no samples recorded")
        window = self.cfg.window if window is None else window
        t = self.series("t")
        t1 = float(t[-1]) if t_end is None else t_end
        sel = np.flatnonzero((t >= t1 - window - 1e-12) & (t <= t1 + 1e-12))
        if len(sel) == 0:
            raise ValueError("no samples in the window")

        def mean(name: str) -> float:
            return float(np.mean(self.series(name)[sel]))

        spread = (self.series("speed_max") - self.series("speed_min")) / self.series("speed_mean")
        tension_rms = float("nan")
        q_fit = float("nan")
        uniform = float("nan")
        extras: dict = {}
        failed: dict[str, str] = {}
        if self.keep_profiles and self.profiles:
            lo, hi = float(t[sel[0]]), float(t[sel[-1]])
            profs = [p for p in self.profiles if lo - 1e-12 <= p.t <= hi + 1e-12]
            if not profs:  # thinned profiles: the nearest one to the window's end
                profs = [min(self.profiles, key=lambda p: abs(p.t - hi))]
            nmin = min(len(p.tension_bar) for p in profs)
            tb = np.mean([p.tension_bar[:nmin] for p in profs], axis=0)
            ya = np.mean([p.y[:nmin] for p in profs], axis=0)
            xa = np.mean([p.x[:nmin] for p in profs], axis=0)
            nsp = min(len(p.speed) for p in profs)
            sp = np.mean([p.speed[:nsp] for p in profs], axis=0)
            uniform = float(np.max(np.abs(sp - sp.mean())) / sp.mean())
            extras.update(tension_bar=tb, x=xa, y=ya, speed=sp)
            pts = np.column_stack((xa, ya))
            xv0, yv0 = vertex_of(pts)
            cat = getattr(self.sim, "catenary", None)
            q0 = cat.q if cat is not None else 1.0
            try:
                _, _, q_fit = fit_catenary(pts, xv0, yv0, q0)
            except (np.linalg.LinAlgError, ValueError, FloatingPointError) as exc:
                failed["catenary fit"] = f"{type(exc).__name__}: {exc}"
            ref = self.sim.reference
            if ref is not None:
                resid = tb - ref.tension_profile(xa, ya)
                tension_rms = float(np.sqrt(np.mean(resid**2)))
                extras["tension_resid"] = resid
        steady = self.steady_from(window)
        return Summary(
            t0=float(t[sel[0]]), t1=float(t[sel[-1]]), samples=len(sel),
            vertex_x=mean("vertex_x"), vertex_y=mean("vertex_y"),
            landing_x=mean("landing_x"), q_fit=q_fit,
            speed_mean=mean("speed_mean"), speed_uniformity=uniform,
            speed_spread_inst=float(np.mean(spread[sel])),
            stretch_max=float(np.max(self.series("stretch")[sel])),
            T0_bar=mean("T0_bar"), tension_rms=tension_rms, steady_from=steady, extras=extras,
            failed=failed,
        )
