"""The tests of the pick-up and cart-step study rigs (``sim/pickup.py``, ``sim/cart_step.py``)
that still live here: all of them are slow (``make check`` leaves them out, ``make test``
runs them), as a folder, until they move with their rigs."""

from pathlib import Path

import pytest

HERE = Path(__file__).parent


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if item.path.parent == HERE:
            item.add_marker(pytest.mark.slow)
