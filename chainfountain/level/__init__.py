"""Level files (TOML): reading, checking and writing them (``io``) and the level library.

Import ``chainfountain.level.io`` for :func:`load`, :func:`save` and friends. The
fields a level declares (unit, description, allowed range) are
:mod:`chainfountain.fields`, a layer below the simulation's config dataclasses.
"""
