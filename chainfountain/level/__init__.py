"""Level files (TOML): schema declarations (``fields``) and reading/writing (``io``).

Import ``chainfountain.level.io`` for :func:`load`, :func:`save` and friends;
this package itself stays import-light because the simulation's config
dataclasses import :mod:`chainfountain.level.fields`.
"""
