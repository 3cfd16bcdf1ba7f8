"""The pulley apparatus that generates a steady fountain.

Paper, section "Generating Steady-State Chain Fountains": the chain is
unfolded by a roller (scaled force 1/2), rises ``xi2*H`` to the fountain start
(the "beaker" lies ``xi2*H`` below it), flies, lands at the fountain end and
is folded back to rest ``xi3*H`` above it (the raised "bottom"). Carts on
inclined tracks add the scaled forces ``Tbar_uc`` (upper) and ``Tbar_lc``
(lower):

    Tbar_E = 1/2 + Tbar_lc - xi3*k*H
    Tbar_0 = 1/2 + Tbar_uc + xi2*k*H

and steady state needs ``Tbar_0 - Tbar_E = k*H``, i.e.
``Tbar_uc = Tbar_lc + k*H*(1 - xi2 - xi3)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from chainfountain.theory.constants import G0


def cart_force_bar(mass: float, slope: float, lam: float, v: float, g: float = G0) -> float:
    """Scaled force of a cart on an incline, ``m*g*sin(beta)/(lambda*v**2)`` (as the paper
    uses it)."""
    return mass * g * math.sin(slope) / (lam * v**2)


def cart_mass(force_bar: float, slope: float, lam: float, v: float, g: float = G0) -> float:
    """Cart mass giving the scaled force ``force_bar`` on a track of slope ``beta`` (inverse of
    :func:`cart_force_bar`)."""
    return force_bar * lam * v**2 / (g * math.sin(slope))


def apparatus_TE_bar(T_lc: float, xi3: float, k: float, H: float) -> float:
    """End tension the lower mechanism supplies: ``1/2 + Tbar_lc - xi3*k*H``."""
    return 0.5 + T_lc - xi3 * k * H


def apparatus_T0_bar(T_uc: float, xi2: float, k: float, H: float) -> float:
    """Start tension the upper mechanism supplies: ``1/2 + Tbar_uc + xi2*k*H``."""
    return 0.5 + T_uc + xi2 * k * H


def ideal_floor_speed(H: float, xi2: float, F_uc: float, lam: float, g: float = G0) -> float:
    """Speed the idealized beaker with a real floor selects (section "Idealized beaker,
    real floor"): ``Tbar_0 = 1/2 + Tbar_uc + xi2 k H`` meets the fountain's
    ``Tbar_0 = k H`` (``Tbar_E = 0``), so ``v^2 = 2 g (H (1 - xi2) - F_uc/(lambda g))``.
    ``nan`` when the cart holds the chain (no positive ``v^2``)."""
    v2 = 2.0 * g * (H * (1.0 - xi2) - F_uc / (lam * g))
    return math.sqrt(v2) if v2 > 0.0 else math.nan


def ideal_open_speed(H: float, xi2: float, F_uc: float, d: float, lam: float,
                     g: float = G0) -> float:
    """Speed the open arrangement with ideal rollers selects (paper, Fig.
    "pulley_experiment_equiv_ground", right: no deceleration after landing). The landed
    chain runs down a loss-free turn ``d`` below the fountain's end onto a frictionless
    plate and slides away, so the end is pulled by the weight in the turn, ``T_E = lambda
    g d`` (``Tbar_E = k d``) once the speed no longer changes. With the upper half's
    ``Tbar_0 = 1/2 + Tbar_uc + xi2 k H`` and the fountain's ``Tbar_0 = Tbar_E + k H``:
    ``v^2 = 2 g (H (1 - xi2) + d) - 2 F_uc/lambda``. ``nan`` when the cart holds the
    chain (no positive ``v^2``)."""
    v2 = 2.0 * g * (H * (1.0 - xi2) + d) - 2.0 * F_uc / lam
    return math.sqrt(v2) if v2 > 0.0 else math.nan


def ideal_open_TE_bar(v: float, d: float, g: float = G0) -> float:
    """End tension of the open arrangement's loss-free turn of height ``d`` at speed ``v``:
    the weight of the chain in it, ``Tbar_E = k d = g d/v^2``."""
    return g * d / (v * v)


def ideal_fold_TE_bar(v: float, xi3: float, F_lc: float, lam: float, H: float,
                      g: float = G0, drag: float = 0.0) -> float:
    """End tension the ideal full machine's lower half supplies at speed ``v``:
    ``Tbar_E = 1/2 + Tbar_lc - xi3 k H`` with ``Tbar_lc = F_lc/(lambda v^2)`` (paper, section
    "Generating Steady-State Chain Fountains"), less the folding roller's bearing drag
    ``drag*v/2`` (scaled). Negative means the lower strand goes slack."""
    return apparatus_TE_bar((F_lc - 0.5 * drag * v) / (lam * v * v), xi3, g / (v * v), H)


def ideal_fold_T0_bar(v: float, xi2: float, F_uc: float, lam: float, H: float,
                      g: float = G0, drag: float = 0.0) -> float:
    """Start tension the ideal machine's upper half supplies at speed ``v``:
    ``Tbar_0 = 1/2 + Tbar_uc + xi2 k H`` with ``Tbar_uc = F_uc/(lambda v^2)``, plus the
    pick-up roller's bearing drag ``drag*v/2`` (scaled)."""
    return apparatus_T0_bar((F_uc + 0.5 * drag * v) / (lam * v * v), xi2, g / (v * v), H)


def balanced_cart_force(F_lc: float, xi2: float, xi3: float, lam: float, H: float,
                        g: float = G0) -> float:
    """Upper cart force (N) that balances the lower one: ``F_uc = F_lc + lambda g H (1 - xi2
    - xi3)``, the steady-state condition ``Tbar_uc = Tbar_lc + k H (1 - xi2 - xi3)`` times
    ``lambda v^2``. It holds whatever ``v``: a balanced loss-free machine keeps any speed
    (it is neutral), an unbalanced one speeds the chain up or slows it at
    ``imbalance/mass``."""
    return F_lc + lam * g * H * (1.0 - xi2 - xi3)


def ideal_fold_imbalance(F_uc: float, F_lc: float, xi2: float, xi3: float, lam: float,
                         H: float, g: float = G0) -> float:
    """Net force (N) the carts and gravity leave on the chain of a loss-free full machine with
    a taut lower strand: positive speeds it up. ``F_lc + lambda g H (1 - xi2 - xi3) - F_uc``;
    the ``lambda v^2/2`` of the pick-up and of the put-down cancel, so it does not depend
    on ``v``."""
    return balanced_cart_force(F_lc, xi2, xi3, lam, H, g) - F_uc


def ideal_fold_speed(F_uc: float, F_lc: float, xi2: float, xi3: float, drag: float,
                     lam: float, H: float, g: float = G0) -> float:
    """Speed a full machine whose bearings drag with ``drag*v`` selects: the carts' imbalance
    (:func:`ideal_fold_imbalance`) meets the drag, ``v = imbalance/drag``. ``nan`` for a
    loss-free machine (``drag = 0``: neutral) or when the carts hold the chain back."""
    if drag <= 0.0:
        return math.nan
    v = ideal_fold_imbalance(F_uc, F_lc, xi2, xi3, lam, H, g) / drag
    return v if v > 0.0 else math.nan


def ideal_fold_slack_speed(xi3: float, F_lc: float, lam: float, H: float,
                           g: float = G0) -> float:
    """Speed below which the loss-free machine's lower strand goes slack (``Tbar_E`` of
    :func:`ideal_fold_TE_bar` reaches 0): ``v^2 = 2 (g xi3 H - F_lc/lambda)``; 0 if never.
    Below it the end is free, as in the idealized beaker with a real floor, and the machine
    pushes the chain back up to it (the paper's limit case sits exactly here)."""
    v2 = 2.0 * (g * xi3 * H - F_lc / lam)
    return math.sqrt(v2) if v2 > 0.0 else 0.0


def balanced_upper_cart(T_lc: float, xi2: float, xi3: float, k: float, H: float) -> float:
    """Steady-state condition: ``Tbar_uc = Tbar_lc + k*H*(1 - xi2 - xi3)``."""
    return T_lc + k * H * (1.0 - xi2 - xi3)


def imbalance_bar(T_uc: float, T_lc: float, xi2: float, xi3: float, k: float, H: float) -> float:
    """Scaled net force ``Tbar_0 - Tbar_E - k*H`` that the apparatus leaves unbalanced.

    Zero in steady state. Positive means the mechanism holds the chain back
    more than gravity on the free fountain pulls it (the chain decelerates).
    """
    return apparatus_T0_bar(T_uc, xi2, k, H) - apparatus_TE_bar(T_lc, xi3, k, H) - k * H


@dataclass(frozen=True)
class ApparatusSettings:
    """Offsets and scaled cart forces of one apparatus, with the end tensions they supply."""

    xi2: float
    xi3: float
    T_uc: float
    T_lc: float
    k: float
    H: float

    @property
    def T0_bar(self) -> float:
        return apparatus_T0_bar(self.T_uc, self.xi2, self.k, self.H)

    @property
    def TE_bar(self) -> float:
        return apparatus_TE_bar(self.T_lc, self.xi3, self.k, self.H)

    @property
    def feasible(self) -> bool:
        """Both carts pull (``Tbar_uc >= 0`` and ``Tbar_lc >= 0``), as the paper requires."""
        return self.T_uc >= 0.0 and self.T_lc >= 0.0

    @property
    def balanced(self) -> bool:
        return abs(imbalance_bar(self.T_uc, self.T_lc, self.xi2, self.xi3, self.k, self.H)) < 1e-9


def settings_for(TE_bar: float, k: float, H: float, xi2: float, xi3: float) -> ApparatusSettings:
    """Cart forces that make an apparatus with offsets ``xi2, xi3`` supply a fountain's end
    tension ``Tbar_E`` in steady state (the paper's two-step design procedure).

    ``Tbar_lc = Tbar_E - 1/2 + xi3*k*H`` and the balanced ``Tbar_uc``. Carts can
    only pull, so both must be ``>= 0``; the caller checks :attr:`feasible`.
    """
    T_lc = TE_bar - 0.5 + xi3 * k * H
    T_uc = balanced_upper_cart(T_lc, xi2, xi3, k, H)
    return ApparatusSettings(xi2=xi2, xi3=xi3, T_uc=T_uc, T_lc=T_lc, k=k, H=H)


def special_case_k(q: float, h: float, H: float) -> float:
    """``k`` of the special case ``xi2 = xi3 = 1/2``, ``Tbar_lc = 0``.

    Then ``Tbar_0 = 1/2 + k*H/2`` must equal ``1 - k/q - k*h``, so
    ``k = 1/2 / (1/q + h + H/2)``.
    """
    return 0.5 / (1.0 / q + h + 0.5 * H)


def limit_case_xi3(k: float, H: float) -> float:
    """``xi3 = 1/(2*k*H)`` of the limit case ``k = k_max``, ``Tbar_lc = 0``
    (then ``Tbar_E = 0``)."""
    return 1.0 / (2.0 * k * H)


def referred_mass(strand_mass: float, carriage_mass: float, roller_mass: float) -> float:
    """Mass of a pick-up strand with its roller unit, referred to the chain speed ``v``.

    Not in the paper. The carriage (cart included) and the roller move at ``v/2``
    (alpha = 0) and the roller, a uniform disc of radius ``r``, turns at ``v/(2 r)``, so
    their kinetic energy is ``(v**2/2)*((m_c + m_r)/4 + m_r/8)`` beside the strand's
    ``M*v**2/2``. ``strand_mass`` is the chain the roller drives along a fixed path: in
    the apparatus the links between the pick-up and the fountain start; the chain in
    flight is not on a fixed path and does not take part (``docs/apparatus.md``)."""
    for name, m in (("strand_mass", strand_mass), ("carriage_mass", carriage_mass),
                    ("roller_mass", roller_mass)):
        if not m >= 0.0:
            raise ValueError(f"{name} = {m!r}: must be >= 0 kg")
    return strand_mass + 0.25 * (carriage_mass + roller_mass) + 0.125 * roller_mass


def cart_step_speed(t: float | np.ndarray, dF: float, mass: float, gain: float = 0.5,
                    drag: float = 0.0) -> float | np.ndarray:
    """Change of the chain speed a time ``t`` after the upper cart's force steps by ``dF``.

    Not in the paper. Linear response of ``mass * d(dv)/dt = -gain*dF - drag*dv``
    (``mass`` from :func:`referred_mass`), against the same run without the step:

    - ``gain = 1/2`` is the energy balance of an ideal rolling pulley: the cart is
      lifted at ``v_R = v/2``, so it takes the power ``F*v/2`` from the chain;
    - ``gain = 1`` is the paper's momentum law ``Tbar_0 = 1/2 + Tbar_uc + ...``;
    - ``drag = d(T_pickup)/dv`` is the rise of the pick-up's own tension with speed
      (``lambda*v`` for the paper's ``lambda*v**2/2``).

    Returns ``-(gain*dF/drag)*(1 - exp(-drag*t/mass))``, or ``-gain*dF*t/mass`` when
    ``drag = 0``.
    """
    if not mass > 0.0:
        raise ValueError(f"mass = {mass!r}: must be > 0 kg")
    if not drag >= 0.0:
        raise ValueError(f"drag = {drag!r}: must be >= 0 N s/m")
    t = np.asarray(t, dtype=float)
    if drag == 0.0:
        out = -gain * dF * t / mass
    else:
        out = -(gain * dF / drag) * -np.expm1(-drag * t / mass)
    return float(out) if out.ndim == 0 else out


def plate_reaction(t: np.ndarray, v: np.ndarray, R0: float, lam: float,
                   g: float = G0) -> np.ndarray:
    """Reaction force of the horizontal plate under the non-stationary arrangement's tail.

    Paper, section "Generating Steady-State Chain Fountains", the arrangement with "no
    deceleration ... in which the reaction force change is exactly known over time": the
    plate carries the chain that has slid onto it, so its reaction grows by ``lambda*g``
    per metre of chain arriving, ``R(t) = R0 + lambda*g*integral(v dt)``, i.e. at the rate
    ``lambda*g*v``. ``t`` and ``v`` are sampled times and chain speeds (the integral by
    the trapezoidal rule from ``t[0]``, where ``R = R0``).
    """
    t = np.asarray(t, dtype=float)
    v = np.asarray(v, dtype=float)
    if t.shape != v.shape or t.ndim != 1:
        raise ValueError(f"t and v must be 1-d arrays of one length, got {t.shape} and {v.shape}")
    if len(t) == 0:
        return np.zeros(0)
    dist = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    return R0 + lam * g * dist
