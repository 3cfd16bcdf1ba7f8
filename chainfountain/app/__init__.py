"""The interactive front end (pygame-ce + pygame_gui).

``session`` is the model side (no pygame): the running level and the commands the window
sends it. ``window`` is the window (``layout`` places its parts, ``input`` turns events
into commands, ``draw`` paints); ``scene_view`` draws the scene from the model's state
(``machine_view`` the machine, ``chain_view`` the chain, ``labels`` lays out the names),
``panel``, ``timebar``, ``tools``, ``picker`` and ``plots`` the controls around it, and
``capture`` writes pictures and clips. ``launch`` opens the window, or falls back to a
headless run when there is no display.
"""

from chainfountain.app.launch import display_available, open_app, run_default

__all__ = ["display_available", "open_app", "run_default"]
