"""One steady chain fountain: the object theory, simulator, app and CLI share."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from chainfountain.theory import catenary, tension
from chainfountain.theory.constants import G0
from chainfountain.theory.kinematics import acosh1p, solve_q


@dataclass(frozen=True)
class Fountain:
    """A steady inverted-catenary fountain (paper, section "Inverted Catenary").

    Defined by its geometry ``l`` (horizontal distance start to end), ``h``
    (overshoot of the vertex above the start), ``H`` (drop from start to end),
    all in metres, and ``k = g/v**2`` (1/m). ``q`` follows from the geometry by
    Eq. (kinemat_constraint). Coordinates are in the vertex frame: vertex at
    the origin, ``y`` up, chain moving in ``+x``.

    Build one with :meth:`from_geometry`, :meth:`from_launch` or
    :meth:`from_forces`.
    """

    l: float  # noqa: E741 - the paper's symbol
    h: float
    H: float
    k: float
    g: float = G0
    q: float = field(default=float("nan"))

    def __post_init__(self) -> None:
        for name in ("l", "h", "H", "k", "g"):
            val = getattr(self, name)
            if not isinstance(val, int | float) or not math.isfinite(val):
                raise ValueError(f"{name} must be a finite number (got {val!r})")
        if self.l <= 0 or self.H <= 0 or self.h < 0 or self.k <= 0 or self.g <= 0:
            raise ValueError(
                f"need l > 0, H > 0, h >= 0, k > 0, g > 0 "
                f"(got l={self.l:g}, h={self.h:g}, H={self.H:g}, k={self.k:g}, g={self.g:g})"
            )
        if not math.isfinite(self.q):
            object.__setattr__(self, "q", float(solve_q(self.l, self.h, self.H)))

    # ----- constructors -------------------------------------------------------------
    @classmethod
    def from_geometry(
        cls,
        l: float,  # noqa: E741
        h: float,
        H: float,
        *,
        k: float | None = None,
        v: float | None = None,
        g: float = G0,
    ) -> Fountain:
        """Fountain with geometry ``(l, h, H)`` and speed given as ``k`` or ``v`` (exactly one)."""
        if (k is None) == (v is None):
            raise ValueError("give exactly one of k and v")
        if k is None:
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise ValueError(f"v must be a finite number > 0 (got {v!r})")
            k = tension.k_of_v(v, g)
        return cls(l=float(l), h=float(h), H=float(H), k=float(k), g=float(g))

    @classmethod
    def from_launch(
        cls, v: float, alpha0: float, H: float, TE_bar: float = 0.0, g: float = G0
    ) -> Fountain:
        """Fountain made by launching the chain at speed ``v`` and angle ``alpha0`` (rad above
        horizontal) with end tension ``TE_bar`` at a floor ``H`` below the launch point.

        From ``Tbar_0 - Tbar_E = k*H`` and ``Tbar_0 = 1 - k/(q*cos(alpha0))``:
        ``q = k/(cos(alpha0)*(1 - Tbar_0))``; from ``cos(alpha0) = 1/(1 + q*h)``:
        ``h = (1/cos(alpha0) - 1)/q``; ``l`` then follows from the curve.
        Needs ``0 < alpha0 < pi/2`` and ``Tbar_E + k*H < 1``.
        """
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"v must be a finite number > 0 (got {v!r})")
        if not (math.isfinite(alpha0) and 0 < alpha0 < math.pi / 2):
            raise ValueError(f"alpha0 must be in (0, pi/2) rad (got {alpha0!r})")
        if not (math.isfinite(H) and H > 0):
            raise ValueError(f"H must be a finite number > 0 (got {H!r})")
        if not (math.isfinite(TE_bar) and TE_bar >= 0):
            raise ValueError(f"TE_bar must be >= 0 (got {TE_bar!r})")
        k = tension.k_of_v(v, g)
        T0 = TE_bar + k * H
        if T0 >= 1.0:
            v_need = math.sqrt(g * H / (1.0 - TE_bar)) if TE_bar < 1 else float("inf")
            raise ValueError(
                f"no fountain: Tbar_E + k*H = {T0:.4g} must be < 1; "
                f"need v > {v_need:.4g} m/s for H = {H:g} m"
            )
        c0 = math.cos(alpha0)
        q = k / (c0 * (1.0 - T0))
        h = (1.0 / c0 - 1.0) / q
        l_ = float(acosh1p(q * (h + H)) + acosh1p(q * h)) / q
        return cls(l=l_, h=h, H=float(H), k=k, g=float(g), q=q)

    @classmethod
    def from_forces(
        cls,
        T0_bar: float,
        k: float,
        l: float,  # noqa: E741
        H: float,
        g: float = G0,
    ) -> tuple[Fountain, ...]:
        """Fountains with start tension ``T0_bar``, ``k``, span ``l`` and drop ``H``.

        ``Tbar_0 = 1 - k/q - k*h`` gives ``1 + q*h = q*c`` with ``c = (1 - Tbar_0)/k``;
        Eq. (kinemat_constraint) becomes ``acosh(q*(c+H)) + acosh(q*c) = q*l`` for
        ``q >= 1/c`` (``h >= 0``). Its left side minus ``q*l`` is concave, so there
        are zero, one or two solutions; all are returned, lowest ``h`` first.
        """
        for name, val in (("T0_bar", T0_bar), ("k", k), ("l", l), ("H", H)):
            if not math.isfinite(val):
                raise ValueError(f"{name} must be a finite number (got {val!r})")
        if not 0 <= T0_bar < 1:
            raise ValueError(f"T0_bar must be in [0, 1) (got {T0_bar:g})")
        if k <= 0 or l <= 0 or H <= 0:
            raise ValueError("k, l and H must be > 0")
        c = (1.0 - T0_bar) / k

        def G(q: float) -> float:
            return float(
                acosh1p(max(q * (c + H) - 1.0, 0.0)) + acosh1p(max(q * c - 1.0, 0.0)) - q * l
            )

        q_lo = 1.0 / c
        # Maximum of the concave G: G'(q) = (c+H)/sqrt((q(c+H))^2-1) + c/sqrt((qc)^2-1) - l.
        def dG(q: float) -> float:
            return (c + H) / math.sqrt((q * (c + H)) ** 2 - 1) + c / math.sqrt(
                max((q * c) ** 2 - 1, 1e-300)
            ) - l

        q_hi = q_lo * 2.0
        while G(q_hi) > 0 or dG(q_hi) > 0:
            q_hi *= 2.0
            if q_hi > 1e12 * q_lo:
                return ()
        roots: list[float] = []
        g_lo = G(q_lo)
        if g_lo >= 0:
            roots.append(brentq(G, q_lo, q_hi, xtol=1e-15, rtol=1e-14))
        else:
            if dG(q_lo * (1 + 1e-12)) <= 0:
                return ()
            q_peak = brentq(dG, q_lo * (1 + 1e-12), q_hi, xtol=1e-15, rtol=1e-14)
            if G(q_peak) < 0:
                return ()
            roots.append(brentq(G, q_lo, q_peak, xtol=1e-15, rtol=1e-14))
            roots.append(brentq(G, q_peak, q_hi, xtol=1e-15, rtol=1e-14))
        out = []
        for q in roots:
            h = max(c - 1.0 / q, 0.0)
            out.append(cls(l=float(l), h=h, H=float(H), k=float(k), g=float(g), q=q))
        return tuple(sorted(out, key=lambda f: f.h))

    # ----- derived quantities ---------------------------------------------------------
    @property
    def v(self) -> float:
        """Chain speed (m/s), ``v = sqrt(g/k)``."""
        return math.sqrt(self.g / self.k)

    @property
    def qH(self) -> float:
        """Scaled shape parameter ``qbar = q*H`` (paper Fig. "sol")."""
        return self.q * self.H

    @property
    def xi(self) -> float:
        """``xi = h/H``."""
        return self.h / self.H

    @property
    def kappa(self) -> float:
        """``kappa = l/H``."""
        return self.l / self.H

    @property
    def T0_bar(self) -> float:
        """Scaled start tension ``1 - k/q - k*h``."""
        return tension.T0_bar(self.q, self.k, self.h)

    @property
    def TE_bar(self) -> float:
        """Scaled end tension ``1 - k/q - k*(h+H)``."""
        return tension.TE_bar(self.q, self.k, self.h, self.H)

    @property
    def k_max(self) -> float:
        """``k_max = q/(1 + q*(h+H))`` (zero end tension)."""
        return tension.k_max(self.q, self.h, self.H)

    @property
    def v_min(self) -> float:
        """The paper's ``v_min = sqrt(g*(h+H))``."""
        return tension.v_min(self.h, self.H, self.g)

    @property
    def v_kmax(self) -> float:
        """Speed at ``k_max``: the exact lower bound for a tensile end force."""
        return tension.v_kmax(self.q, self.h, self.H, self.g)

    @property
    def v_max(self) -> float:
        """The paper's rough energy bound ``v_max = sqrt(2*g*H)``."""
        return tension.v_max(self.H, self.g)

    def k_range(self) -> tuple[float, float]:
        """Admissible ``k`` for this geometry: ``(1/(2H), k_max]`` (may be empty)."""
        return tension.k_min_energy(self.H), self.k_max

    def bounds(self) -> tension.BoundCheck:
        """Which of the paper's bounds this fountain satisfies."""
        return tension.check_bounds(self.q, self.h, self.H, self.k, self.g)

    def force_ranges(self) -> tension.ForceRanges:
        """Admissible end-tension ranges for this geometry, Eq. (range_forces)."""
        return tension.force_ranges(self.q, self.h, self.H)

    @property
    def start(self) -> tuple[float, float]:
        """Fountain start (beaker) in the vertex frame."""
        return (-float(acosh1p(self.q * self.h)) / self.q, -self.h)

    @property
    def end(self) -> tuple[float, float]:
        """Fountain end (floor) in the vertex frame."""
        return (float(acosh1p(self.q * (self.h + self.H))) / self.q, -(self.h + self.H))

    @property
    def alpha0(self) -> float:
        """Launch angle above horizontal (rad): ``cos(alpha0) = 1/(1 + q*h)``."""
        return math.acos(1.0 / (1.0 + self.q * self.h))

    @property
    def alphaE(self) -> float:
        """Landing angle below horizontal (rad): ``cos(alphaE) = 1/(1 + q*(h+H))``."""
        return math.acos(1.0 / (1.0 + self.q * (self.h + self.H)))

    @property
    def length(self) -> float:
        """Arc length of the free chain from start to end (m)."""
        return float(catenary.s_of_x(self.end[0], self.q) - catenary.s_of_x(self.start[0], self.q))

    def y_of_x(self, x: ArrayLike) -> NDArray[np.float64]:
        """Height of the curve, Eq. (func_graph)."""
        return catenary.y_of_x(x, self.q)

    def tension_bar(self, y: ArrayLike) -> NDArray[np.float64]:
        """Scaled tension ``1 - k/q + k*y`` at height ``y`` (vertex frame)."""
        return tension.tension_bar(y, self.q, self.k)

    def tension(self, y: ArrayLike, lam: float) -> NDArray[np.float64]:
        """Tension (N) at height ``y`` for linear density ``lam`` (kg/m)."""
        return lam * self.g / self.k * self.tension_bar(y)

    def curve(self, n: int = 200) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``n`` points equally spaced in arc length from start to end (vertex frame)."""
        return catenary.sample_curve(self.start[0], self.end[0], self.q, n)

    def with_k(self, k: float) -> Fountain:
        """The same geometry at another speed."""
        return Fountain(l=self.l, h=self.h, H=self.H, k=k, g=self.g, q=self.q)

    def to_dict(self) -> dict[str, Any]:
        """All headline numbers as plain floats (the CLI's ``--json`` object)."""
        b = self.bounds()
        return {
            "l": self.l,
            "h": self.h,
            "H": self.H,
            "g": self.g,
            "q": self.q,
            "qH": self.qH,
            "k": self.k,
            "v": self.v,
            "k_max": self.k_max,
            "v_min": self.v_min,
            "v_kmax": self.v_kmax,
            "v_max": self.v_max,
            "T0_bar": self.T0_bar,
            "TE_bar": self.TE_bar,
            "alpha0_deg": math.degrees(self.alpha0),
            "alphaE_deg": math.degrees(self.alphaE),
            "vertex": [0.0, 0.0],
            "start": list(self.start),
            "end": list(self.end),
            "length": self.length,
            "bounds_ok": b.ok,
            "bounds": {
                "tensile_start": b.tensile_start,
                "tensile_end": b.tensile_end,
                "above_v_min": b.above_v_min,
                "below_v_max": b.below_v_max,
            },
        }
