"""The paper's analytic results (Mayet & Pfeiffer, "Generating Steady-State Chain Fountains").

SI units throughout. Scaled tensions ``Tbar = T/(lambda*v**2)``, ``k = g/v**2``.
"""

from chainfountain.theory.apparatus import (
    ApparatusSettings,
    apparatus_T0_bar,
    apparatus_TE_bar,
    balanced_upper_cart,
    cart_force_bar,
    cart_mass,
    cart_step_speed,
    imbalance_bar,
    limit_case_xi3,
    referred_mass,
    settings_for,
    special_case_k,
)
from chainfountain.theory.catenary import alpha_of_s, alpha_of_x, s_of_x, y_of_x
from chainfountain.theory.constants import G0
from chainfountain.theory.forces import (
    pickup_force,
    pickup_force_bar,
    pickup_roller_speed,
    putdown_force,
    putdown_force_bar,
)
from chainfountain.theory.fountain import Fountain
from chainfountain.theory.kinematics import solve_q, solve_qH
from chainfountain.theory.tension import (
    BoundCheck,
    ForceRanges,
    T0_bar,
    TE_bar,
    check_bounds,
    force_ranges,
    k_max,
    k_of_v,
    tension_bar,
    v_kmax,
    v_max,
    v_min,
    v_of_k,
)

__all__ = [
    "G0",
    "ApparatusSettings",
    "BoundCheck",
    "ForceRanges",
    "Fountain",
    "T0_bar",
    "TE_bar",
    "alpha_of_s",
    "alpha_of_x",
    "apparatus_T0_bar",
    "apparatus_TE_bar",
    "balanced_upper_cart",
    "cart_force_bar",
    "cart_mass",
    "cart_step_speed",
    "check_bounds",
    "force_ranges",
    "imbalance_bar",
    "k_max",
    "k_of_v",
    "limit_case_xi3",
    "referred_mass",
    "pickup_force",
    "pickup_force_bar",
    "pickup_roller_speed",
    "putdown_force",
    "putdown_force_bar",
    "s_of_x",
    "settings_for",
    "solve_q",
    "solve_qH",
    "special_case_k",
    "tension_bar",
    "v_kmax",
    "v_max",
    "v_min",
    "v_of_k",
    "y_of_x",
]
