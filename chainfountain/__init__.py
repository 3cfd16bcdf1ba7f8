"""chainfountain: a 2D physics simulator of the chain fountain.

Implements J. Mayet and F. Pfeiffer, "Generating Steady-State Chain Fountains":
``chainfountain.theory`` holds the paper's analytic results, ``chainfountain.sim``
the pymunk model, ``chainfountain.app`` the pygame-ce front end.
"""

__version__ = "0.1.0"
