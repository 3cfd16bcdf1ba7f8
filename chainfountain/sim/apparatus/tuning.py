"""The apparatus model's numeric choices: sizes, bands, rates and times that are not in
the paper, each with the reason for its value (``docs/apparatus.md`` has the runs).

The code that uses them is in the part's module. What a study may vary is a
:class:`Tuning`, passed to :class:`~chainfountain.sim.apparatus.Apparatus` (its defaults
are the shipped model's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

WALL_R = 0.002
"""Radius of channel wall segments (m)."""
FUNNEL = (0.06, 0.02)
"""Length and half-opening (m) of the funnel before the end channel's mouth."""
CATCH = (0.05, 0.0)
"""Length along the landing tangent and outward flare (m) by which the 'open' variant's
one-sided catch wall reaches up above the end channel's mouth (the fountain above its
end lies outside the tangent, on the catenary's convex side)."""
OPEN_CAPTURE = (0.02, math.radians(3.0))
"""'open' joint guide: capture band (m) around the turn's radius and angular margin
before the mouth (rad) within which a falling link is taken into the guide."""
OPEN_CLOSE_RATE = 0.2
"""Speed (m/s) at which the outer limit of a link captured outside the 'open' guide's
radius closes in to it."""
FOLD_CAPTURE = (0.06, math.radians(3.0))
"""'fold' joint guide: capture band (m) and angular margin (rad) of the first turn.
Wider than 'open''s: the fountain's landing point wanders by several centimetres
(docs/apparatus.md), and a link captured off the radius
is held there (its limits close in at :data:`FOLD_CLOSE_RATE`), so a wide band costs
nothing while the chain lands on the radius."""
FOLD_CLOSE_RATE = 5.0
"""Speed (m/s) at which the limits of a link captured off a joint guide's turn (the
'fold' guide's; the upper joint guide's too) close in to ``R -+ PLAY``: a 6-cm offset
closes in 12 ms, while the link moves about two link lengths, so the catch acts as a
stiff funnel at the mouth. Measured
(docs/apparatus.md): at a close rate of 0.5 m/s the landing point's oscillation grew
until the catch was lost at about 4.3 s (both treadmills on); at 2, 5 and 20 m/s the
run held to 8 s, at 5 m/s to about 13 s."""
FOLLOW_CAPTURE = (0.30, math.radians(40.0))
"""'fold' with a following end guide (``apparatus.end_follow``): the first turn's capture
band (m) and angular margin (rad). The guide follows the landing's mean; its mouth takes
the landing's swing, several centimetres after a cart is changed."""
FOLLOW_CLOSE_RATE = 20.0
"""Joint guides with a following end guide: the close rate (m/s) instead of
:data:`FOLD_CLOSE_RATE`. At 5 m/s a link caught 10-20 cm off the radius rides the turn
on a larger radius for a while, the guide's path grows and the fountain loses its stored
length; at 20 m/s a 10-cm offset closes in 5 ms (research/notes/apparatus_notebook.md, "a start from
rest for the gripped fold")."""
FOLLOW_TAU = 0.5
"""Time (s) over which a following end guide averages the landing's offset."""
FOLLOW_SPEED = 0.05
"""Fastest a following end guide moves (m/s)."""
FOLLOW_TRAVEL = 0.30
"""Farthest a following end guide moves from where the level puts it (m, either way)."""
TAIL_KEEP = 30
"""'open': links kept in the lower plate grooves; the tail beyond is lumped into the
end link (:meth:`~.open_tail.OpenTail.lump_tail`)."""
LO_START = 0.15
"""'fold': start distance (m) of the folding roller from the end channel's exit."""
COLLAPSE_TIME = 0.05
"""'fold': the run ends (:class:`~.fold_watch.FoldCollapsed`) once the folding roller
has rolled backwards for this long (s). In the shipped fold presets it never does (it rolls
forward at about ``v/2`` throughout); without a forward push it falls behind at once
and rolls back within about 1 s (``apparatus_limit``, docs/apparatus.md)."""
FOLD_RELEASE = 0.5
"""'fold' with grooves: a lower-plate link leaves its groove (and gets its collision shape
back) once its centre is this many link lengths before the folding roller's top."""
FOLD_DT_MIN = 3.5e-4
"""'fold': smallest solver step (s) at which this model's fold was measured to hold.
The fold is not converged in the step: ``apparatus_fold`` and ``apparatus_special``
hold for 3 s at dt 0.35-0.5 ms, lose their folding roller at about 2.1 s at 0.25 ms
(``apparatus_special`` with its joint guide: at 0.65 s) and within 0.2 s at 0.1 ms
(docs/apparatus.md); the put-down rig alone is converged down to 0.03 ms. With
``fold_clearance = 0`` only: the cause is the folding roller locking between the plate
grooves and the table."""
HELD = 0.1
"""'fold': the folding roller counts as holding the chain while ``|v_R/v - 1/2|`` is at
most this (the collapse message tells a fold that never held from one that held and was
then lost)."""
SWING_EVERY, SWING_SAMPLES = 0.05, 100
"""'fold': sampling interval (s) and count of the speed history the collapse message
reads the speed swing from (the last 5 s in which the fold held)."""
LATE_COLLAPSE = 2.0
"""'fold': a collapse after the folding roller has held the chain this long (s) is
reported as the landing swing's, not as a missing push (docs/apparatus.md)."""
CATCH_LOST = 0.1
"""'fold': a collapse this long (s) or longer after the last link entered the end guide
through its mouth (normally one does every ``L/v``, about 7 ms) was preceded by a lost
catch, and the collapse message says so (docs/apparatus.md)."""
CATCH_STOP = 0.5
"""'fold' with the gripped folding roller: the run ends once no link has entered the end
guide through its mouth for this long (s; normally one does every ``L/v``, about 7 ms).
The gripped roller cannot slip, so after a lost catch a heavy lower cart (a braked fold's,
``apparatus.fold_brake``) keeps pulling the chain on and runs it away instead of letting
the roller roll back; measured on ``apparatus_special`` with a brake and a 325 g lower
cart, which lost its catch at 13.9 s and ran the chain up to 13 m/s by 16.9 s."""
RUNAWAY = 1.5
"""'fold' with the gripped folding roller: the run ends once the chain runs faster than this
times ``apparatus.speed``. A following end guide's wide mouth takes links landing beside
it too, so a lost fountain can run away while links still enter; no fountain this machine
catches is that fast (the landing moves about 1.5 cm per 1 % of speed, the guide at most
:data:`FOLLOW_TRAVEL`)."""
UP_RELEASE = 0.5
"""Upper joint guide: a link leaves the guide's straight once its centre is this many
link lengths short of the fountain start, i.e. once its front joint has left the guide,
so the free fountain starts at ``(0, 0)`` as with the channel's walls. Measured
(``apparatus_floor``, 2-6 s; docs/apparatus.md): the vertex is
+5.4 % off the catenary through the ends when links leave at their centre (0), +0.1 %
at 0.5, -1.6 % at 0.6, -6.0 % at 1 (the walls: +1.7 %)."""
CLEAR = 0.0008
"""Clearance between a link capsule and each channel wall (m)."""


@dataclass(frozen=True)
class Tuning:
    """The apparatus model's choices a study may vary (``Apparatus(..., tuning=...)``);
    the defaults are the shipped model's."""

    fold_capture: tuple[float, float] | None = None
    """'fold' joint guide: capture band (m) and angular margin (rad) of the first turn;
    ``None``: :data:`FOLD_CAPTURE`, or :data:`FOLLOW_CAPTURE` with a following end guide."""
    fold_close_rate: float | None = None
    """Joint guides: speed (m/s) at which the limits of a link captured off a turn's
    radius close in; ``None``: :data:`FOLD_CLOSE_RATE`, or :data:`FOLLOW_CLOSE_RATE`
    with a following end guide."""
    lay_at_rest: bool = False
    """Lay the chain at rest along its path even where the level lays it moving (a
    study's start, ``research/hanging_start.py``)."""

    def capture(self, following: bool) -> tuple[float, float]:
        """The first turn's capture band and margin, with or without a following end
        guide."""
        if self.fold_capture is not None:
            return self.fold_capture
        return FOLLOW_CAPTURE if following else FOLD_CAPTURE

    def close_rate(self, following: bool) -> float:
        """The joint guides' close rate (m/s), with or without a following end guide."""
        if self.fold_close_rate is not None:
            return self.fold_close_rate
        return FOLLOW_CLOSE_RATE if following else FOLD_CLOSE_RATE
