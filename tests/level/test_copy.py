"""The shipped levels' cards: a short title, a description of at most three sentences that
a teacher can read aloud, and the few sliders that matter for what the level shows."""

import copy
import re

import pytest

from chainfountain.app import spans
from chainfountain.app.controls import control_fields
from chainfountain.level import io
from chainfountain.level.library import twin
from tests import shipped

LEVELS = shipped.PATHS
IDS = [p.stem for p in LEVELS]

MAX_TITLE = 40
MAX_DESCRIPTION = 320
MAX_SENTENCES = 3

_SENTENCE_END = re.compile(r"[.!?](?=\s|$)")


def sentences(text: str) -> int:
    """Sentences in ``text``: each ends with '.', '!' or '?' followed by a space or the end
    (so "0.3 m" does not end one); text after the last end counts as one more."""
    text = text.strip()
    ends = _SENTENCE_END.findall(text)
    tail = _SENTENCE_END.split(text)[-1].strip()
    return len(ends) + (1 if tail else 0)


def test_sentence_count_counts_what_a_reader_hears():
    assert sentences("One. Two! Three?") == 3
    assert sentences("The top rises 0.3 m above the rim.") == 1
    assert sentences("No full stop at the end") == 1
    assert sentences("One. Two. Three. Four.") == 4
    assert sentences("e.g. this counts. As two") == 3  # why the cards avoid such dots


@pytest.mark.parametrize("path", LEVELS, ids=IDS)
def test_every_shipped_level_has_a_short_plain_title(path):
    meta = io.load(path).meta
    title = meta.title.strip()
    assert title, f"{path.stem}: no title"
    assert len(title) <= MAX_TITLE, f"{path.stem}: title of {len(title)} characters"
    assert title != meta.name and "_" not in title and ".toml" not in title, \
        f"{path.stem}: the title names a file ({title!r})"


@pytest.mark.parametrize("path", LEVELS, ids=IDS)
def test_every_shipped_description_is_a_short_card(path):
    text = io.load(path).meta.description.strip()
    assert text, f"{path.stem}: no description"
    assert len(text) <= MAX_DESCRIPTION, f"{path.stem}: {len(text)} characters"
    n = sentences(text)
    assert 1 <= n <= MAX_SENTENCES, f"{path.stem}: {n} sentences"
    assert "docs/" not in text and ".md" not in text, f"{path.stem}: names a docs page"
    assert ".toml" not in text, f"{path.stem}: names a file"


@pytest.mark.parametrize("path", LEVELS, ids=IDS)
def test_the_card_says_m_only_where_there_is_a_twin(path):
    text = io.load(path).meta.description
    says_m = re.search(r"\bM\b", text) is not None
    assert says_m == (twin(path.stem) is not None), path.stem


@pytest.mark.parametrize("path", LEVELS, ids=IDS)
def test_the_card_says_how_the_level_starts(path):
    """A level laid on its path says so; a level that forms from rest never says it starts
    laid on its path (and the laid ones never claim to form from rest)."""
    from chainfountain.app import paths

    if io.load(path).sim.kind == "scene":
        return
    text = io.load(path).meta.description.lower()
    laid = "starts laid on its path" in text or "starts on the predicted curve" in text
    assert laid != paths.forms_from_rest(path), path.stem
    if laid:
        assert "from rest" not in text and "forms" not in text, path.stem


@pytest.mark.parametrize("path", LEVELS, ids=IDS)
def test_every_shipped_level_names_the_sliders_that_matter(path):
    """2-4 of the sliders the window offers for this level (scene levels: none); each one
    moves (a contact fold's offsets keep their built value, so they are not named)."""
    level = io.load(path)
    named = level.meta.control_paths()
    if level.sim.kind == "scene":
        assert named == [], path.stem
        return
    assert 2 <= len(named) <= 4, f"{path.stem}: {len(named)} controls"
    assert len(set(named)) == len(named), f"{path.stem}: a control named twice"
    offered = {s.path: s for s in control_fields(level.sim)}
    origin = copy.deepcopy(level.sim)
    for p in named:
        assert p in offered, f"{path.stem}: {p} is not one of the window's sliders here"
        span = spans.narrowed(level, offered[p], origin)
        assert span.slider_hi > span.slider_lo, f"{path.stem}: {p}'s slider cannot move"
