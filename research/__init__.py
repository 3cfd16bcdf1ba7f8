"""Research scripts: studies of the model against the paper, run by hand from the repository
root as ``python -m research.SCRIPT`` (``research/README.md``). Not part of the installed
package; ``chainfountain`` never imports it (an import-linter contract)."""
