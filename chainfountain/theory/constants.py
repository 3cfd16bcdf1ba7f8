"""Physical constants shared by theory and simulation."""

G0: float = 9.81
"""Standard gravitational acceleration used throughout the paper (m/s^2)."""
