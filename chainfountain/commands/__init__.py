"""Sub-commands of the ``chainfountain`` command line."""
