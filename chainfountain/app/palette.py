"""The window's colours: light lines and bold parts on a dark blue-grey background, chosen
to read on a projector (a bright chain with white markers, the theory a thin dashed
line, parts in distinct hues)."""

from __future__ import annotations

BG = (22, 27, 36)
SCENE_BG = (16, 20, 28)
GRID = (30, 37, 49)
TEXT = (226, 231, 240)
DIM = (150, 160, 176)
PANEL = (30, 36, 48)
"""Panel backgrounds."""
CARD = (10, 12, 18)
"""The card's, the messages' and the big readout's backing over the scene."""
LABEL_BG = (6, 8, 12)
"""A label's backing."""
CHAIN = (255, 168, 52)
CHAIN_DARK = (150, 86, 18)
"""The joints between links and the chain's shading."""
MARK = (250, 250, 250)
"""Every n-th link: the marks that travel with the chain."""
HALO = (6, 8, 12)
"""The dark edge around the chain that keeps it clear of lines behind it."""
THEORY = (96, 206, 255)
"""The paper's curve (a thin dashed line behind the chain)."""
ROPE = (206, 190, 160)
LABEL = (214, 220, 232)
"""Names of the machine's parts."""
VERTEX = (255, 96, 200)
FLOOR = (150, 160, 175)
ABSORB = (70, 130, 90)
GUIDE = (186, 194, 210)
GLASS = (170, 210, 230)
ROLLER = (176, 188, 255)
ROLLER_FILL = (48, 56, 92)
CART = (96, 208, 150)
CART_DARK = (28, 78, 54)
TRACK = (128, 136, 152)
TABLE = (132, 112, 88)
TABLE_DARK = (82, 68, 52)
T0_COL = (255, 120, 90)
TE_COL = (120, 200, 255)
SPEED_COL = (255, 210, 90)
WARN = (255, 110, 90)
OK = (120, 220, 140)
BUTTON = (52, 62, 82)
BUTTON_HOVER = (70, 84, 110)
PLAY = (255, 196, 64)
"""The big play/pause button (PhET's orange-yellow)."""
RESET_ALL = (240, 128, 40)
"""Reset All (PhET's orange)."""
RULER = (250, 226, 120)
