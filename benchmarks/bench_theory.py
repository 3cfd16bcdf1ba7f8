"""Benchmark: the vectorised kinematic-constraint solver on a grid of 10^6 geometries.

Target (issue 2): under one second for 10^6 points. Prints the timing and the
worst relative residual of Eq. (kinemat_constraint).

    .venv/bin/python benchmarks/bench_theory.py
"""

from __future__ import annotations

import time

import numpy as np

from chainfountain.theory import solve_qH
from chainfountain.theory.kinematics import kinematic_residual


def main() -> None:
    xi = np.linspace(0.0, 0.99, 1000)
    kappa = np.geomspace(1e-2, 20.0, 1000)
    X, K = np.meshgrid(xi, kappa)
    solve_qH(X[:10], K[:10])  # warm-up
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        Q = solve_qH(X, K)
        best = min(best, time.perf_counter() - t0)
    resid = np.max(np.abs(kinematic_residual(Q, X, K)) / (Q * K))
    print(f"solve_qH on {X.size:,} points: {best:.3f} s (best of 3), "
          f"max relative residual {resid:.2e}")


if __name__ == "__main__":
    main()
