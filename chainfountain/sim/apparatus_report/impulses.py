"""The guides' impulses on the chain that the recorded contacts do not hold: the lower
joint guides hold their links with joints, not contacts. :func:`guided_impulses`
reconstructs the 'fold' guide's (shear neglected; :func:`pivot_offset` corrects what
that misses), :func:`open_guide_impulses` the 'open' turn's and tail grooves' exactly."""

from __future__ import annotations

import numpy as np

from chainfountain.sim.apparatus import Apparatus


def guided_impulses(app: Apparatus, pre_vel: np.ndarray, post, dt: float,
                     k: int, start: tuple[int, float]) -> np.ndarray:
    """'fold': 'contact' impulses for the first ``k`` links, which the lower guide joints
    hold (their impulses are not among the contacts), such that the momentum balance
    summed from the end gives, at joint ``k-1``, the tension of the guided chain.

    The guide forces are normal to the path (frictionless grooves, slide joints to
    the turns' centres), so each guided link's balance along its own axis ``u_i``
    gives the tension recursively (shear neglected):
    ``T_i (e_i.u_i) = T_{i-1} (e_{i-1}.u_i) - m (dv_i/dt + g y).u_i`` with ``e_j`` the
    joint direction as in ``signed_tension``, starting from a known tension
    ``start = (i, T_i)`` at joint ``i`` (on the lower plate, from the horizontal joint
    force). The returned rows make the summed force at joint ``k-1`` equal
    ``-T_{k-1} e_{k-1}``. (:func:`pivot_offset` corrects what the neglected shear
    misses; 'open' is read exactly, :func:`open_guide_impulses`.)
    """
    m, g = app.chain.mass, app.g
    ang = post.angle
    u = np.column_stack((np.cos(ang), np.sin(ang)))
    n = len(ang)
    kk = min(k, n - 1)
    e = u[:kk] + u[1:kk + 1]
    e /= np.linalg.norm(e, axis=1)[:, None]
    acc = (post.velocity[:kk] - pre_vel[:kk]) / dt
    acc[:, 1] += g
    i_first, T = start[0] + 1, start[1]
    # the recursion in plain floats: numpy's per-call cost on 2-vectors made this loop
    # 40 % of a sample's analysis (0.4 ms at 30 guided links)
    ul, el, al = u[:kk].tolist(), e.tolist(), acc.tolist()
    epx, epy = el[start[0]]
    for i in range(i_first, kk):
        ux, uy = ul[i]
        ax, ay = al[i]
        rhs = T * (epx * ux + epy * uy) - m * (ax * ux + ay * uy)
        ex, ey = el[i]
        T = rhs / (ex * ux + ey * uy)
        epx, epy = ex, ey
    raw = m * (post.velocity[:k] - pre_vel[:k])
    raw[:, 1] += m * g * dt
    target = np.zeros((k, 2))
    if kk:
        target[kk - 1] = -T * e[kk - 1] * dt
    return raw - target


def open_guide_impulses(app: Apparatus, pre_vel: np.ndarray, pre_w: np.ndarray, post,
                         dt: float, lower: tuple[int, int, float, float]
                         ) -> tuple[np.ndarray, float]:
    """'open' with the joint turn: the external impulses on the first ``k`` links (the
    tail's grooves, the turn's slide joints), exactly, as 'contact' rows for
    :func:`~chainfountain.sim.measure.joint_forces`.

    ``lower = (n_tail, n_turn, m_end, I_end)`` is the guide's state at the step (links
    ``0 .. n_tail-1`` in the lower plate's grooves, the next ``n_turn`` on the turn; the
    end link's mass and moment with the lumped tail). The energy budget's impulse sweep
    (:func:`chainfountain.sim.budget.sweep`) gives each joint's impulse along its known
    normal from the links' momentum and angular momentum changes, so nothing is
    neglected (the 'fold' guide's reconstruction, :func:`guided_impulses`, takes the
    guide forces normal to each link's axis and neglects the shear). Each row also
    carries what ``joint_forces`` does not know: the end pull and the lumped mass beyond
    one link's on the end link. Also returns the grooves' summed impulse on the tail (N
    s, upward)."""
    from chainfountain.sim.budget import lower_kinds, sweep

    n_tail, n_turn, m_end, I_end = lower
    k = min(n_tail + n_turn, len(post.angle))
    kinds = lower_kinds(app, n_tail, n_turn)[:k]
    m, g = app.chain.mass, app.g
    mass = np.full(k, m)
    moment = np.full(k, app.chain.moment)
    mass[0], moment[0] = m_end, I_end
    dv = post.velocity[:k] - pre_vel[:k]
    dv[:, 1] += g * dt  # momentum change and weight, per unit mass
    dp = mass[:, None] * dv
    dp[0, 0] -= app.end_pull * dt
    _, gn, nrm, _ = sweep(kinds, post.position[:k], post.angle[:k], dp,
                          moment * (post.angular_velocity[:k] - pre_w[:k]), 0.5 * app.L)
    rows = gn[:, None] * nrm  # the guides' impulses
    rows[0] += np.array([app.end_pull * dt, 0.0]) - (m_end - m) * dv[0]
    return rows, float(np.sum(gn[:n_tail] * nrm[:n_tail, 1]))


def pivot_offset(F: np.ndarray, pivots: np.ndarray, free: np.ndarray) -> np.ndarray | None:
    """'fold': the constant force ``c`` that the lower guide's reconstruction
    (:func:`guided_impulses`) misses, from the free flight's pivot joints.

    Summed from the downstream end, the joint forces of the free links are exact up
    to one constant vector: the error of the guide's reconstruction (its guide forces
    taken normal to each link's axis, shear neglected), which reaches every joint
    upstream of the mouth. The solver's own pivot impulses give each joint force's
    size, ``|F_j + c| = |J_j|/dt``; ``c`` is their least-squares fit (Gauss-Newton from
    0). Measured on ``apparatus_special`` over 1-4 s (docs/apparatus.md): the fit's rms
    residual is 1e-4 ``lambda v^2`` (the flight's joint forces are exact up to ``c``),
    ``|c|`` 0.05 ``lambda v^2`` in the median, and ``Tbar_0 - Tbar_E`` then equals ``k``
    times the height between the two joints within 0.01 with either upper guide. None if
    the fit does not hold (fewer than 5 free joints, or an rms residual above 2 % of the
    mean pivot force)."""
    if len(free) < 5:
        return None
    Ff, P = F[free], pivots[free]
    if not np.all(np.isfinite(P)):
        return None
    c = np.zeros(2)
    for _ in range(4):
        G = Ff + c
        Gn = np.linalg.norm(G, axis=1)
        if np.any(Gn == 0.0):
            return None
        c = c + np.linalg.lstsq(G / Gn[:, None], P - Gn, rcond=None)[0]
    rms = float(np.sqrt(np.mean((np.linalg.norm(Ff + c, axis=1) - P) ** 2)))
    return c if rms <= 0.02 * float(np.mean(P)) else None
