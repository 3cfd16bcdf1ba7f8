"""``python -m chainfountain`` runs the same command line as ``chainfountain``."""

from chainfountain.cli import console_main

console_main()
