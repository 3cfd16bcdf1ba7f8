"""Direct chipmunk reads and writes of a body's position and velocity, for the
per-step loops over held links (:func:`chainfountain.sim.apparatus.joints.keep_on_arcs`,
:func:`chainfountain.sim.apparatus.starter.run_along`).

pymunk 7's :attr:`pymunk.Body.position` builds a :class:`pymunk.Vec2d` on every
read: 1.8 us per read or write of a position or velocity on this machine
(``timeit``), against 0.4-0.7 us for the chipmunk call itself. A link projected
back onto a guide arc needs four of them per step. These functions are the
chipmunk calls pymunk itself makes, without the wrapper; they take the body's
chipmunk handle (:func:`handle`), return structs with ``.x`` and ``.y``, and
take ``(x, y)`` tuples. ``tests/sim/test_fastbody.py`` checks them against pymunk's
properties; the apparatus gives the same numbers to the last digit with them.
Measured with callgrind on ``apparatus_special`` (t = 0.5-0.6 s): 2.17 million
instructions per step with these calls against 2.60 with pymunk's properties
(docs/apparatus.md).

:mod:`pymunk.batch` (one read and one write of all bodies) was measured as
well and is slower here: numpy's per-call cost on a few dozen links is more
than the loop's.

They use pymunk's private ``pymunk._chipmunk_cffi`` and ``Body._body`` (stable
through pymunk 7; ``pyproject.toml`` pins ``pymunk>=7,<8``), kept in this one
module so that a pymunk change breaks one place and ``tests/sim/test_fastbody.py``.
"""

from __future__ import annotations

import pymunk
from pymunk._chipmunk_cffi import ffi, lib

get_position = lib.cpBodyGetPosition
"""``get_position(h)``: the position (struct with ``.x``, ``.y``) of handle ``h``."""
set_position = lib.cpBodySetPosition
"""``set_position(h, (x, y))``."""
get_velocity = lib.cpBodyGetVelocity
"""``get_velocity(h)``: the velocity (struct with ``.x``, ``.y``) of handle ``h``."""
set_velocity = lib.cpBodySetVelocity
"""``set_velocity(h, (vx, vy))``."""
apply_force_at_local_point = lib.cpBodyApplyForceAtLocalPoint
"""``apply_force_at_local_point(h, (fx, fy), (x, y))``."""


def handle(body: pymunk.Body) -> object:
    """The chipmunk handle of ``body`` (valid while the body lives)."""
    return body._body


def pos(body: pymunk.Body):  # noqa: ANN201 (a chipmunk struct)
    """``body``'s position as a chipmunk struct (``.x``, ``.y``): the same numbers as
    :attr:`pymunk.Body.position` without building a :class:`pymunk.Vec2d`."""
    return get_position(body._body)


PIVOT_JACC = 25
"""Where chipmunk's ``cpPivotJoint`` keeps its accumulated impulse ``jAcc``: at this many
doubles from the start of the struct (the ``cpConstraint`` header of 13 words, the two
anchors, ``r1``, ``r2`` and the 2x2 mass matrix ``k`` come first). pymunk 7 exposes only
its length (:attr:`pymunk.Constraint.impulse`); ``tests/sim/test_fastbody.py`` checks
that the two agree and that the vector points the right way."""


def _pivot_layout_ok() -> bool:
    """Whether this pymunk build lays out ``cpPivotJoint`` as :data:`PIVOT_JACC` assumes:
    64-bit words, and the anchors (which pymunk does expose) at doubles 13-16."""
    if ffi.sizeof("void *") != 8:
        return False
    a, b = pymunk.Body(1.0, 1.0), pymunk.Body(1.0, 1.0)
    j = pymunk.PivotJoint(a, b, (0.125, -0.25), (0.375, -0.5))
    p = ffi.cast("double *", j._constraint)
    return (p[13], p[14], p[15], p[16]) == (0.125, -0.25, 0.375, -0.5)


PIVOT_LAYOUT_OK = _pivot_layout_ok()
"""Checked once at import: :func:`pivot_impulse` and :func:`set_pivot_impulse` refuse
otherwise."""


def _check_layout() -> None:
    """Refuse to touch a pivot joint's impulse unless :data:`PIVOT_LAYOUT_OK`."""
    if not PIVOT_LAYOUT_OK:
        raise RuntimeError(
            f"this pymunk build ({pymunk.version}) does not lay out its pivot joints as "
            "chainfountain reads them (chainfountain.sim.fastbody.PIVOT_JACC), so the "
            "apparatus's treadmills and gripped folding roller cannot run; use pymunk 7 "
            "on a 64-bit Python")


def pivot_impulse(joint: pymunk.PivotJoint) -> tuple[float, float]:
    """The impulse (N s) ``joint`` applied to its second body in the last pymunk step, as
    a vector (its opposite went to the first body). A chain joint ``PivotJoint(down, up)``
    under tension pulls ``up`` towards ``down``: the vector points downstream.

    The size alone (:attr:`pymunk.Constraint.impulse`) is no tension reading where the
    joint force rings: at the folding roller it rings at the laying rate ``v/(2L)`` and its
    harmonics, more at smaller steps and more solver iterations, and the ringing's size
    outgrows the mean (docs/apparatus.md, "The gripped folding roller")."""
    _check_layout()
    p = ffi.cast("double *", joint._constraint)
    return float(p[PIVOT_JACC]), float(p[PIVOT_JACC + 1])


def set_pivot_impulse(joint: pymunk.PivotJoint, impulse: tuple[float, float]) -> None:
    """Start ``joint`` warm: its accumulated impulse (as :func:`pivot_impulse` reads it),
    which pymunk's next step applies as the joint's warm start before it iterates. A new
    joint put into a chain under tension, given its predecessor's impulse, starts where
    the predecessor would have."""
    _check_layout()
    p = ffi.cast("double *", joint._constraint)
    p[PIVOT_JACC], p[PIVOT_JACC + 1] = impulse
