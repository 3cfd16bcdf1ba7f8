"""chainfountain: a 2D physics simulator of the chain fountain.

Implements J. Mayet and F. Pfeiffer, "Generating Steady-State Chain Fountains":
``chainfountain.theory`` holds the paper's analytic results, ``chainfountain.sim``
the pymunk model, ``chainfountain.app`` the pygame-ce front end.
"""

__version__ = "0.1.0"


def __getattr__(name: str):  # noqa: ANN202 - lazy, so that `import chainfountain` stays light
    """``chainfountain.run``, ``chainfountain.start``, ``chainfountain.with_changes``:
    :mod:`chainfountain.study`'s Python API (imported on first use)."""
    if name in ("run", "start", "with_changes", "RunResult", "Stepper"):
        from chainfountain import study

        return getattr(study, name)
    raise AttributeError(f"module 'chainfountain' has no attribute {name!r}")
