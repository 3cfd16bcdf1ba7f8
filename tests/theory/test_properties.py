"""Property tests over random admissible geometry (hypothesis)."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from chainfountain.theory import Fountain, catenary

lengths = st.floats(min_value=0.05, max_value=5.0)
overshoot = st.floats(min_value=0.0, max_value=3.0)


@settings(max_examples=200, deadline=None)
@given(l=lengths, h=overshoot, H=lengths)
def test_curve_passes_through_start_vertex_end(l, h, H):  # noqa: E741
    f = Fountain(l=l, h=h, H=H, k=1.0)
    sx, sy = f.start
    ex, ey = f.end
    scale = h + H
    assert math.isclose(float(f.y_of_x(sx)), -h, abs_tol=1e-9 * scale)
    assert math.isclose(float(f.y_of_x(ex)), -(h + H), rel_tol=1e-9)
    assert math.isclose(ex - sx, l, rel_tol=1e-9)
    assert float(f.y_of_x(0.0)) == 0.0
    x, y = f.curve(101)
    assert math.isclose(x[0], sx, rel_tol=1e-9, abs_tol=1e-12)
    assert math.isclose(x[-1], ex, rel_tol=1e-9)
    assert np.max(y) <= 1e-12


@settings(max_examples=200, deadline=None)
@given(l=lengths, h=overshoot, H=lengths)
def test_curvature_at_vertex_equals_q(l, h, H):  # noqa: E741
    f = Fountain(l=l, h=h, H=H, k=1.0)
    # Finite-difference curvature of the sampled curve at the vertex.
    d = 1e-4 / f.q
    y0, yp, ym = (float(f.y_of_x(x)) for x in (0.0, d, -d))
    kappa_fd = (yp - 2 * y0 + ym) / d**2
    assert math.isclose(-kappa_fd, f.q, rel_tol=1e-5)
    assert math.isclose(float(-catenary.curvature_of_x(0.0, f.q)), f.q)


@settings(max_examples=200, deadline=None)
@given(l=lengths, h=overshoot, H=lengths, k=st.floats(min_value=0.01, max_value=10.0))
def test_tension_linear_in_y_with_slope_k(l, h, H, k):  # noqa: E741
    f = Fountain(l=l, h=h, H=H, k=k)
    y = np.linspace(-(h + H), 0, 7)
    T = f.tension_bar(y)
    assert np.allclose(np.diff(T) / np.diff(y), k, rtol=1e-9)
    assert math.isclose(float(f.tension_bar(-h)), f.T0_bar, rel_tol=1e-12, abs_tol=1e-12)
    assert math.isclose(f.T0_bar - f.TE_bar, k * H, rel_tol=1e-9)
    # Same tension from the angle form Tbar = 1 - k/(q cos(alpha)).
    x = np.linspace(f.start[0], f.end[0], 9)
    alpha = catenary.alpha_of_x(x, f.q)
    assert np.allclose(1 - k / (f.q * np.cos(alpha)), f.tension_bar(f.y_of_x(x)), atol=1e-9)


@settings(max_examples=300, deadline=None)
@given(l=lengths, h=overshoot, H=lengths, u=st.floats(min_value=1e-6, max_value=1 - 1e-6))
def test_ranges_hold_whenever_velocity_bounds_hold(l, h, H, u):  # noqa: E741
    base = Fountain(l=l, h=h, H=H, k=1.0)
    k_lo, k_hi = base.k_range()
    assume(k_lo < k_hi)
    f = base.with_k(k_lo + u * (k_hi - k_lo))
    assert f.bounds().ok
    assert 0.0 <= f.TE_bar < 0.5
    assert 0.5 < f.T0_bar < 1.0
    r = f.force_ranges()
    assert r.TE[0] - 1e-12 <= f.TE_bar < r.TE[1] + 1e-12
    assert r.T0[0] - 1e-12 <= f.T0_bar < r.T0[1] + 1e-12


@settings(max_examples=300, deadline=None)
@given(
    v=st.floats(min_value=1.0, max_value=20.0),
    alpha0=st.floats(min_value=math.radians(5), max_value=math.radians(89)),
    H=lengths,
    TE=st.floats(min_value=0.0, max_value=0.5),
)
def test_launch_inverse_round_trips(v, alpha0, H, TE):
    k = 9.81 / v**2
    assume(TE + k * H < 0.98)
    f = Fountain.from_launch(v, alpha0, H, TE_bar=TE)
    assert math.isclose(f.alpha0, alpha0, rel_tol=1e-9)
    assert math.isclose(f.TE_bar, TE, abs_tol=1e-9)
    assert math.isclose(f.v, v, rel_tol=1e-12)
    # Rebuilding from the geometry alone gives back the same q.
    g = Fountain(l=f.l, h=f.h, H=f.H, k=f.k)
    assert math.isclose(g.q, f.q, rel_tol=1e-9)
    # And from the forces, one of the solutions is the original.
    sols = Fountain.from_forces(f.T0_bar, f.k, f.l, f.H)
    assert any(math.isclose(s.q, f.q, rel_tol=1e-6) for s in sols)
