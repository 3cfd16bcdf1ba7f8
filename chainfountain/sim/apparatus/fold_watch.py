"""'fold': watching the folding roller. A fold whose roller rolls backwards has failed
(the chain piles up in the lower guide); the run ends with :class:`FoldCollapsed` and
a message that says why: no or too small a forward push, too small a solver step, or
(after the fold held) the landing swing, and whether the end guide's catch was lost
first."""

from __future__ import annotations

import math
from collections import deque

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import Clock, RollerUnit
from chainfountain.sim.apparatus.tuning import (
    CATCH_LOST,
    CATCH_STOP,
    COLLAPSE_TIME,
    FOLD_DT_MIN,
    HELD,
    LATE_COLLAPSE,
    RUNAWAY,
    SWING_EVERY,
    SWING_SAMPLES,
)


class FoldCollapsed(RunEnded):
    """'fold': the folding roller has rolled backwards for
    :data:`~.tuning.COLLAPSE_TIME`: the put-down has failed, the chain piles up in the
    lower guide and the fountain falls out of its catch (raised by
    :meth:`~chainfountain.sim.apparatus.Apparatus.after_step`)."""


class FoldWatch:
    """The fold's collapse check and messages."""

    def __init__(self, layout: Layout, upper: RollerUnit, fold: FoldPart, clock: Clock) -> None:
        self.layout = layout
        self.cfg = layout.cfg
        self.upper = upper
        self.lower = fold.lower
        self.fold = fold
        self.clock = clock
        self._back_t = 0.0
        """How long (s) the folding roller has been rolling backwards without a break."""
        self._held_t = 0.0
        """How long (s) the folding roller has rolled at ``v/2`` (within :data:`~.tuning.HELD`),
        sampled every :data:`~.tuning.SWING_EVERY` s."""
        self._held_v: deque[float] = deque(maxlen=SWING_SAMPLES)
        """Chain speed (m/s) every :data:`~.tuning.SWING_EVERY` s while the fold held: the
        speed swing the collapse message reports."""
        self._swing_next = 0.0

    @property
    def speed(self) -> float:
        """Chain speed: twice the pick-up roller speed."""
        return 2.0 * abs(self.upper.speed)

    def check(self, dt: float) -> None:
        """Raise :class:`FoldCollapsed` once the folding roller has rolled backwards for
        :data:`~.tuning.COLLAPSE_TIME` (a chain that keeps running into a stopped fold only piles
        up; nothing after that is the apparatus any more)."""
        v_R = self.lower.speed
        mouth_t = self.fold.mouth_t
        if self.layout.gripped and (mouth_t is not None and self.clock.t - mouth_t >= CATCH_STOP
                                    or self.speed > RUNAWAY * self.cfg.speed):
            raise FoldCollapsed(**self._gripped_collapse(v_R))
        if v_R >= 0.0:
            self._back_t = 0.0
            if self.clock.t >= self._swing_next:  # the hold is sampled, not read every step
                self._swing_next = self.clock.t + SWING_EVERY
                v = self.speed
                if v > 0.0 and abs(v_R / v - 0.5) <= HELD:
                    self._held_t += SWING_EVERY
                    self._held_v.append(v)
            return
        self._back_t += dt
        if self._back_t < COLLAPSE_TIME:
            return
        if self.layout.gripped:
            raise FoldCollapsed(**self._gripped_collapse(v_R))
        clamped = self.layout.h < FOLD_DT_MIN and not self.cfg.fold_clearance
        t = self.clock.t
        if self._held_t >= LATE_COLLAPSE and not clamped:
            cure = ("this contact fold holds only close to the speed it was built for"
                    if self.cfg.swing_damper else
                    "the swing damper holds the swing down (0.5 holds apparatus_special)")
            raise FoldCollapsed(
                self._late_collapse_message(v_R),
                plain=f"At {t:.1f} s the folding roller lost the chain after holding it "
                f"{self._held_t:.0f} s: the chain's speed swung until the fold failed; {cure}")
        push = self.lower.force
        lam, v = self.layout.sim_cfg.chain.linear_density, self.speed
        pushed = (f"a push of {push / (lam * v * v):.2f} lambda*v^2" if push
                  else "no lower cart (Tbar_lc = 0)")
        head = (f"t = {self.clock.t:.2f} s: the folding roller rolls backwards (v_R = {v_R:.2f} "
                f"m/s, steady is about +{0.5 * v:.2f}) with {pushed}: the put-down has failed "
                "and the chain piles up in the lower guide. ")
        if clamped:
            raise FoldCollapsed(
                plain=f"At {t:.1f} s the fold locked: at a time step below "
                f"{FOLD_DT_MIN * 1e3:g} ms the folding roller jams against its table; set "
                "the pymunk step (solver.dt / solver.substeps) back to 0.5 ms",
                message=head + "the pymunk step solver.dt / solver.substeps = "
                f"{self.layout.h:g} s is "
                f"below {FOLD_DT_MIN:g} s, where the folding roller locks between the lower "
                "plate's grooves and the table (with apparatus.fold_clearance = 0 the fold only "
                "holds at a pymunk step of 0.35-0.5 ms; docs/apparatus.md): set "
                "apparatus.fold_clearance = 0.002 (with a lighter lower cart) or a pymunk step "
                "of 0.0005 s")
        cure = ("make the lower cart heavier" if push else
                "this model's fold needs a lower cart to push it, which the paper's does not")
        raise FoldCollapsed(
            plain=f"At {t:.1f} s the folding roller fell behind and the fold collapsed; {cure}",
            message=head + "This model's put-down needs a forward push of about 0.3 lambda*v^2 or "
            "more (docs/apparatus.md); "
            + ("raise the lower cart mass" if push else
               "give the level a second [[carts]] entry (the lower cart)") + "."
            + self._catch_note())

    def _gripped_collapse(self, v_R: float) -> dict[str, str]:
        """The gripped folding roller rolled back, or no link entered the end guide's mouth
        for :data:`~.tuning.CATCH_STOP`: it holds the chain by joints, so it cannot slip;
        the chain stopped arriving as it should. Either the fountain fell past the end
        guide's catch (every measured case, docs/apparatus.md) or the carts took the
        chain far from the speed the level was built for."""
        t, v0 = self.clock.t, float(self.cfg.speed)
        held = sorted(self._held_v)  # the speed in the last 5 s it held the chain
        v = held[len(held) // 2] if held else self.speed
        ran = f"the chain ran at {v:.2f} m/s, built for {v0:g} m/s"
        if v > 1.02 * v0:
            cure = (f"{ran}, and the faster fountain landed beyond the end guide's catch: "
                    "a lighter lower cart (or a heavier upper one) holds it nearer")
        elif v < 0.98 * v0:
            cure = (f"{ran}, and the slower fountain landed short of the end guide's catch: a "
                    "heavier lower cart (or a lighter upper one) keeps it nearer")
        else:
            cure = (f"the fountain landed beside the end guide's mouth and fell past its catch "
                    f"({ran}); a cart a gram or two off the level's moves where it lands")
        if v_R < 0.0:
            head = (f"t = {t:.2f} s: the gripped folding roller rolls backwards (v_R = "
                    f"{v_R:.2f} m/s): the chain no longer arrives at it. ")
        elif self.speed > RUNAWAY * v0:
            head = (f"t = {t:.2f} s: the chain runs away ({self.speed:.2f} m/s, more than "
                    f"{RUNAWAY:g} times the {v0:g} m/s it was built for). ")
            cure = (f"{ran}, then the fountain left the end guide and the lower cart ran the "
                    "chain away: a lighter lower cart (or a heavier upper one) holds it")
        else:
            head = (f"t = {t:.2f} s: no link has entered the end guide through its mouth since "
                    f"t = {self.fold.mouth_t:.2f} s. ")
        return {"plain": f"At {t:.1f} s the fold stopped: {cure}",
                "message": head + cure[0].upper() + cure[1:] + "." + self._catch_note()}

    def _catch_note(self) -> str:
        """'fold': a sentence for the collapse message if the chain had stopped entering
        the end guide through its mouth :data:`~.tuning.CATCH_LOST` s or more before the collapse
        (the fountain landed outside the catch's band and fell into the turn from the
        side), '' otherwise (or before any link entered: nothing to compare). It states
        the order, not a cause. Measured (docs/apparatus.md): the
        catch is lost 1.0-1.3 s before the folding roller rolls back in
        ``apparatus_special`` (starts 2.97-3.06 m/s, the channel's walls; 1.13 s with the
        joint guide from 3.0 m/s), 0.47 s before in ``apparatus_limit``."""
        if (not self.layout.fold_guided or self.fold.mouth_t is None
                or self.clock.t - self.fold.mouth_t < CATCH_LOST):
            return ""
        dr = self.fold.mouth_dr
        where, shape = ("outside", "narrowed") if dr > 0 else ("inside", "widened")
        return (f" The end guide's catch had been lost before that: the chain last entered "
                f"the guide through its mouth at t = {self.fold.mouth_t:.2f} s, "
                f"{100.0 * abs(dr):.1f} cm {where} the first turn's radius (the catch takes "
                f"links within {100.0 * self.fold.capture[0]:.0f} cm); the fountain had {shape} "
                "and after that the chain fell into the turn from the side.")

    def _late_collapse_message(self, v_R: float) -> str:
        """The collapse of a fold that had held the chain for at least
        :data:`~.tuning.LATE_COLLAPSE` s: the chain speed swings with a period of 2-3 s and a
        growing amplitude (the landing swing) until the folding roller loses the chain.
        The push read at this moment (the chain has run away) says nothing about the
        balance, so the message gives the speed the fold held and its swing instead."""
        hv = self._held_v
        lam = self.layout.sim_cfg.chain.linear_density
        v_held = sum(hv) / len(hv) if hv else self.speed
        swing = 0.5 * (max(hv) - min(hv)) if hv else math.nan
        push = self.lower.force / (lam * v_held * v_held)
        return (f"t = {self.clock.t:.2f} s: the folding roller lost the chain "
                f"(v_R = {v_R:.2f} m/s) "
                f"after holding it at v/2 for {self._held_t:.1f} s in all. In its last "
                f"{len(hv) * SWING_EVERY:.0f} s of holding, the chain speed was "
                f"{v_held:.2f} m/s swinging by +-{swing:.2f} m/s (lower cart push "
                f"{push:.2f} lambda*v^2 at that speed): " + self._swing_note()
                + self._catch_note())

    def _swing_note(self) -> str:
        """What the landing swing did, with or without the swing damper."""
        if self.cfg.swing_damper:
            return (f"the swing damper ({self.cfg.swing_damper:g} N*s/m) held the landing swing "
                    "(period 2-3 s) down, yet the fold failed; apparatus_special with 0.5 "
                    "holds 10 minutes at a pymunk step of 0.5 ms from starts within 1 % of "
                    "3.0 m/s, and fails within seconds at other steps or from slower starts "
                    "(docs/apparatus.md).")
        return ("in this model the landing swing (period 2-3 s) grows until the fold fails. "
                "A lower cart a few grams lighter or heavier, a start 2 % faster or slower, a "
                "stiffer catch or longer strands only move the failure by seconds; a swing "
                "damper between the carriages (apparatus.swing_damper = 0.5) holds it down "
                "(docs/apparatus.md, 'The landing swing').")
