"""The interactive front end (pygame-ce + pygame_gui).

``session`` is the model side (no pygame): the running level and the commands
the window sends it. ``window``, ``render`` and ``capture`` make the pixels.
``launch`` opens the window, or falls back to a headless run when there is no
display.
"""

from chainfountain.app.launch import display_available, open_app, run_default

__all__ = ["display_available", "open_app", "run_default"]
