"""The paper's two-step design procedure (section "Generating Steady-State Chain Fountains").

Step 1 fixes the fountain kinematics ``(l, h, H)`` and the speed (``k``); the
free-flight theory gives ``Tbar_0`` and ``Tbar_E``. Step 2 chooses the offsets
``xi2`` ("beaker" below the start) and ``xi3`` ("bottom" above the end) and
cart forces so that the apparatus supplies those tensions:

    Tbar_lc = Tbar_E - 1/2 + xi3*k*H  >= 0
    Tbar_uc = Tbar_0 - 1/2 - xi2*k*H  >= 0    (= Tbar_lc + k*H*(1 - xi2 - xi3))

Carts can only pull, which bounds the offsets: ``xi3 >= (1/2 - Tbar_E)/(k*H)``
and ``xi2 <= (Tbar_0 - 1/2)/(k*H)``. The choice ``xi2 = (Tbar_0 - 1/2)/(k*H)``,
``xi3 = 1 - xi2`` needs no carts at all and exists for every admissible
fountain.

Cart mass: a cart that carries a roller adds the tension ``dT = cart_gain*F_c``
for a force ``F_c = m*g*sin(beta)`` along its track. The paper takes ``cart_gain = 1``
(``Tbar_c = m*g*sin(beta)/(lambda*v^2)``). A loss-free power balance (``F_c*v_R = dT*v``)
gives ``cart_gain = v_R/v = 1/(1 + cos(alpha))``, i.e. 1/2 for the apparatus' rollers,
and that is what the simulated roller rig (``research/rigs/pickup.py``,
``docs/apparatus.md``) measures: pick-up at alpha = 0 0.49, put-down 0.50, with the
strand tension read from the solver's pivot impulses. (A reading summed through the
contacts gives about 1.0 unless pymunk's stale impulses of contacts that touch again are
taken out, as :meth:`chainfountain.sim.measure.ChainReader.arm` does.)
:data:`MEASURED_CART_GAIN` is that value and the default;
pass ``cart_gain=1.0`` for the paper's carts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from chainfountain.theory.apparatus import ApparatusSettings
from chainfountain.theory.fountain import Fountain

MEASURED_CART_GAIN = 0.5
"""Tension added per unit cart force for a roller-carrying cart at alpha = 0, measured with
``research/pickup_study.py`` (the loss-free power balance ``v_R/v``; the paper: 1)."""


class DesignError(ValueError):
    """A design target the paper rules out; the message names the bound and the nearest
    admissible value."""


@dataclass(frozen=True)
class Design:
    """A fountain and an apparatus that generates it."""

    fountain: Fountain
    settings: ApparatusSettings
    lam: float
    slope_uc: float
    slope_lc: float
    cart_gain: float
    label: str
    alternatives: tuple[tuple[str, ApparatusSettings], ...] = field(default=())

    @property
    def m_uc(self) -> float:
        """Upper cart mass (kg) giving ``Tbar_uc``."""
        return _mass(self.settings.T_uc, self.slope_uc, self)

    @property
    def m_lc(self) -> float:
        """Lower cart mass (kg) giving ``Tbar_lc``."""
        return _mass(self.settings.T_lc, self.slope_lc, self)

    @property
    def beaker_drop(self) -> float:
        """``xi2*H``: height of the fountain start above the unfolding table (m)."""
        return self.settings.xi2 * self.fountain.H

    @property
    def bottom_rise(self) -> float:
        """``xi3*H``: height of the folding table above the fountain end (m)."""
        return self.settings.xi3 * self.fountain.H


def _mass(T_bar: float, slope: float, d: Design) -> float:
    f = d.fountain
    force = T_bar * d.lam * f.v**2  # tension the cart must add (N)
    return force / (d.cart_gain * f.g * math.sin(slope)) if force > 0 else 0.0


def xi_limits(f: Fountain) -> tuple[float, float]:
    """``(xi2_max, xi3_min)``: offsets beyond which a cart would have to push."""
    kH = f.k * f.H
    return (f.T0_bar - 0.5) / kH, (0.5 - f.TE_bar) / kH


def check_target(f: Fountain) -> None:
    """Reject fountains the paper rules out, naming the bound and the nearest admissible value."""
    b = f.bounds()
    if not b.tensile_end:
        raise DesignError(
            f"speed v = {f.v:.4g} m/s is below v(k_max) = {f.v_kmax:.4g} m/s: the end force "
            f"would push (Tbar_E = {f.TE_bar:.4g} < 0); nearest admissible: --v {f.v_kmax:.4g} "
            f"(--k {f.k_max:.4g})")
    if not b.below_v_max:
        k_lo = 1.0 / (2.0 * f.H)
        raise DesignError(
            f"speed v = {f.v:.4g} m/s is not below the energy bound v_max = sqrt(2gH) = "
            f"{f.v_max:.4g} m/s; nearest admissible: --v just below {f.v_max:.4g} "
            f"(--k just above {k_lo:.4g})")
    if f.xi >= 1.0:
        raise DesignError(
            f"overshoot h = {f.h:g} m is not below H = {f.H:g} m: the paper's speed bounds leave "
            f"no admissible speed (q*H*(1 - xi) <= 1); nearest admissible: --h below {f.H:g}")


def design(
    f: Fountain,
    lam: float,
    *,
    xi2: float | None = None,
    xi3: float | None = None,
    slope: float = math.radians(30.0),
    cart_gain: float = MEASURED_CART_GAIN,
) -> Design:
    """Offsets and carts that generate fountain ``f`` (linear density ``lam`` kg/m).

    Defaults: with neither offset given, the paper's special case
    ``xi2 = xi3 = 1/2`` when both its carts pull (``Tbar_E >= 1/2 - k*H/2``),
    otherwise the cart-free choice ``xi2 = (Tbar_0 - 1/2)/(k*H)``,
    ``xi3 = 1 - xi2``. With one offset given the other is 1/2 if feasible,
    else the nearest feasible value (its cart force then zero).
    """
    check_target(f)
    if not (math.isfinite(lam) and lam > 0):
        raise DesignError(f"--lambda {lam!r}: allowed: a linear density > 0 kg/m")
    if not (0 < slope <= math.pi / 2):
        raise DesignError(f"slope {slope!r} rad: allowed: (0, pi/2]")
    kH = f.k * f.H
    xi2_max, xi3_min = xi_limits(f)
    for name, val in (("--xi2", xi2), ("--xi3", xi3)):
        if val is not None and not (math.isfinite(val) and val >= 0):
            raise DesignError(f"{name} {val!r}: allowed: a number >= 0")
    if xi2 is not None and xi2 > xi2_max + 1e-12:
        raise DesignError(
            f"--xi2 {xi2:g} needs the upper cart to push (Tbar_uc = "
            f"{f.T0_bar - 0.5 - xi2 * kH:.4g} < 0); nearest admissible: --xi2 {xi2_max:.4g}")
    if xi3 is not None and xi3 < xi3_min - 1e-12:
        raise DesignError(
            f"--xi3 {xi3:g} needs the lower cart to push (Tbar_lc = "
            f"{f.TE_bar - 0.5 + xi3 * kH:.4g} < 0); nearest admissible: --xi3 {xi3_min:.4g}")

    def settings(x2: float, x3: float) -> ApparatusSettings:
        T_lc = max(f.TE_bar - 0.5 + x3 * kH, 0.0)
        T_uc = max(f.T0_bar - 0.5 - x2 * kH, 0.0)
        return ApparatusSettings(xi2=x2, xi3=x3, T_uc=T_uc, T_lc=T_lc, k=f.k, H=f.H)

    half_ok = 0.5 <= xi2_max + 1e-12 and 0.5 >= xi3_min - 1e-12
    cartless = settings(xi2_max, 1.0 - xi2_max)
    alternatives: list[tuple[str, ApparatusSettings]] = []
    if xi2 is None and xi3 is None:
        if half_ok:
            chosen, label = settings(0.5, 0.5), "special case xi2 = xi3 = 1/2"
        else:
            chosen, label = cartless, "no carts: xi2 = (Tbar_0 - 1/2)/(kH), xi3 = 1 - xi2"
    elif xi3 is None:
        assert xi2 is not None
        chosen, label = settings(xi2, max(0.5, xi3_min)), "given xi2"
    elif xi2 is None:
        chosen, label = settings(min(0.5, xi2_max), xi3), "given xi3"
    else:
        chosen, label = settings(xi2, xi3), "given xi2 and xi3"
    if half_ok:
        alternatives.append(("special case xi2 = xi3 = 1/2", settings(0.5, 0.5)))
    alternatives.append(("no carts", cartless))
    alternatives.append(("lowest bottom: xi3 = xi3_min, no lower cart",
                         settings(min(0.5, xi2_max), xi3_min)))
    return Design(fountain=f, settings=chosen, lam=lam, slope_uc=slope, slope_lc=slope,
                  cart_gain=cart_gain, label=label, alternatives=tuple(alternatives))
