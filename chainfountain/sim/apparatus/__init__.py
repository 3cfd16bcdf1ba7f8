"""The paper's pulley apparatus (section "Generating Steady-State Chain Fountains").

Built by :class:`~chainfountain.sim.world.Simulation` for ``kind = "apparatus"``
(:class:`~chainfountain.sim.config.ApparatusConfig`). Frame: the fountain start
(exit of the upper guide channel) is the origin, ``y`` up, the chain flies in
``+x``; the fountain end is ``H`` below the start.

Path of the chain, upstream to downstream (chain order is the reverse: index 0
is the downstream end, as for the feed):

1. **Upper table** (rough, friction ``table_friction``), the chain resting on
   it in ``-x`` direction toward the pick-up roller. Only ``pickup_rest_links``
   (or ``rest_links``) links ahead of the roller are in the solver; further links
   are added at rest at the upstream end as the roller approaches (they carry no
   force: the tension of the unfolding goes into the table through friction right
   at the roller).
2. **Pick-up roller** (alpha = 0, as ``docs/apparatus.md`` recommends): a
   dynamic disc resting on the chain under its weight, on a carriage that
   slides on a horizontal groove (vertical play through a slot). The chain
   comes off the table at the bottom contact, wraps around the back of the
   roller and leaves on top in ``+x``, the roller following at ``v/2``
   (paper: ``v_R = v/(1 + cos alpha)``). The upper cart is a rope-tied weight,
   as on the roller rig (``research/rigs/pickup.py``): a constant force
   ``m*g*sin(beta)`` on the carriage against its motion, the cart mass added to
   the carriage (an ideal rope over an ideal pulley to a cart on an incline).
3. **Upper plate**: a frictionless static segment at the roller-top height
   carrying the strand from the roller to the channel (without it the strand,
   at ``T < lambda*v**2``, would sag onto the resting chain). Its roller end
   follows the roller every step.
4. **Upper channel**: frictionless two-sided guide (static segment walls with
   a small clearance), horizontal, then a bend of radius ``channel_radius`` up
   to ``alpha0`` and straight to the start: rise ``xi2*H`` from the roller top.
5. **Fountain**: free flight.
6. By variant: ``floor``: a solid floor at the end height (the chain centre
   line lying on it is at ``-H``), the chain piles and the oldest lying links
   leave the solver; ``fold``: an end channel whose mouth sits on the predicted
   fountain end, aligned with the landing tangent, turns the chain and lifts it
   ``xi3*H`` onto the lower plate; the folding roller (mirror image of the
   pick-up: moving in ``+x`` at ``v/2``, the chain wraps around its front) lays
   it onto the lower table, pushed forward by the lower cart; ``open``: the end
   channel turns the chain horizontal and it slides away on a long
   frictionless plate (with ``plate = "groove"``: a frictionless joint guide,
   slide joints to the bend centre then plate grooves, the tail beyond 30
   links lumped into the end link; the moving mass grows at ``lambda*v/2``).

Heights: ``y_up = -xi2*H`` (chain centre line on top of the upper roller),
``y_lo = -H + xi3*H`` (same for the lower roller): the paper's "beaker" and
"bottom". Link radius ``rho``, roller radius ``r``: the table top lies
``3*rho + 2*r`` below the roller-top centre line.

The channels' centre lines and the joint-guide pieces are in
:mod:`chainfountain.sim.guide`; measuring a run (tensions along the path,
``summary.json``'s ``apparatus`` object) is in :mod:`chainfountain.sim.apparatus_report`.

Modules, one part each (each part an object given what it reads; :class:`Apparatus`
composes them): :mod:`.laws` (the measured pick-up and put-down laws, speed selection),
:mod:`.tuning` (the model's numeric choices and their reasons, and :class:`Tuning`, what a
study may vary), :mod:`.layout` (the level's figures and the derived positions the parts
share), :mod:`.parts` (roller units, static segments and walls), :mod:`.core`
(:class:`Apparatus`: build order, feed interface, stepping), :mod:`.upper` (pick-up
roller, upper table, plate and channel), :mod:`.grooves` (the upper plate's grooves),
:mod:`.upper_guide` (the upper joint guide), :mod:`.joints` (holding links in a joint
guide), :mod:`.ends` (floor or end channel), :mod:`.fold` (folding roller and lower
joint guide), :mod:`.grip` (the gripped folding roller), :mod:`.follow` (the end guide
that follows the landing), :mod:`.fold_watch` (the fold's collapse check and messages),
:mod:`.stall_watch` (the stall check), :mod:`.treadmill` (the plate treadmills),
:mod:`.open_tail` ('open': the tail), :mod:`.starter` (the starter motor).

A study varies the model through :class:`Tuning` and the constructor's ``starter`` and
``fountain_path`` (``Apparatus(space, chain, cfg, tuning=Tuning(fold_close_rate=20.0))``),
never by setting attributes of the class.
"""

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus.core import Apparatus, TableUsedUp
from chainfountain.sim.apparatus.fold_watch import FoldCollapsed
from chainfountain.sim.apparatus.laws import (
    CART_GAIN_2CM,
    CART_GAIN_2CM_ERR,
    PICKUP_BAR,
    PICKUP_RIG_2CM,
    PICKUP_RIG_2CM_ERR,
    PUTDOWN_BAR,
    PUTDOWN_RIG_2CM,
    RIG_2CM_LAMBDA,
    braked_fold_speed,
    gripped_putdown,
    pickup_rig_2cm,
    pickup_rig_2cm_drag,
    rig_exit_tension,
    selected_speed,
)
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import RollerUnit
from chainfountain.sim.apparatus.starter import Starter
from chainfountain.sim.apparatus.tuning import Tuning

__all__ = [
    "CART_GAIN_2CM",
    "CART_GAIN_2CM_ERR",
    "PICKUP_BAR",
    "PICKUP_RIG_2CM",
    "PICKUP_RIG_2CM_ERR",
    "PUTDOWN_BAR",
    "PUTDOWN_RIG_2CM",
    "braked_fold_speed",
    "gripped_putdown",
    "RIG_2CM_LAMBDA",
    "Apparatus",
    "FoldCollapsed",
    "Layout",
    "RollerUnit",
    "RunEnded",
    "Starter",
    "TableUsedUp",
    "Tuning",
    "pickup_rig_2cm",
    "pickup_rig_2cm_drag",
    "rig_exit_tension",
    "selected_speed",
]
