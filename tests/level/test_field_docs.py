"""Level field docs (the ``doc=`` of every :func:`chainfountain.fields.param`): one or two
short sentences saying what the field is, its meaning and units; run results and long
explanations live in the docs section a doc may point to ("see docs/PAGE.md#section")."""

import dataclasses
import re
import typing
from collections.abc import Iterator
from pathlib import Path

import pytest

from chainfountain.fields import tuple_item_type
from chainfountain.level.model import Meta
from chainfountain.sim.config import SimConfig

ROOT = Path(__file__).resolve().parents[2]
MAX_DOC = 300
_POINTER = re.compile(r"docs/([\w.]+\.md)(?:#([\w-]+))?")


def field_docs(cls: type, prefix: str = "") -> Iterator[tuple[str, str]]:
    """``(dotted path, doc)`` of every declared field under ``cls``, nested tables included."""
    hints = typing.get_type_hints(cls)
    for f in dataclasses.fields(cls):
        tp = hints[f.name]
        item = tuple_item_type(tp)
        if isinstance(tp, type) and dataclasses.is_dataclass(tp):
            yield from field_docs(tp, f"{prefix}{f.name}.")
        elif item is not None and dataclasses.is_dataclass(item):
            yield from field_docs(item, f"{prefix}{f.name}[].")
        elif "doc" in f.metadata:
            yield f"{prefix}{f.name}", f.metadata["doc"]


DOCS = dict(field_docs(Meta, "meta.")) | dict(field_docs(SimConfig))


def anchors(page: Path) -> set[str]:
    """GitHub's anchors of a Markdown page's headings."""
    out = set()
    for line in page.read_text().splitlines():
        if line.startswith("#"):
            title = line.lstrip("#").strip().lower()
            out.add(re.sub(r"[^\w\- ]", "", title).replace(" ", "-"))
    return out


def test_every_level_field_is_documented():
    assert len(DOCS) > 100
    assert all(doc.strip() for doc in DOCS.values()), [p for p, d in DOCS.items() if not d]


@pytest.mark.parametrize("path", sorted(DOCS))
def test_field_doc_is_short(path):
    doc = DOCS[path]
    assert len(doc) <= MAX_DOC, f"{path}: {len(doc)} characters; move the rest to the docs"


def test_field_doc_pointers_resolve():
    for path, doc in DOCS.items():
        for page, anchor in _POINTER.findall(doc):
            target = ROOT / "docs" / page
            assert target.is_file(), f"{path}: no docs/{page}"
            if anchor:
                assert anchor in anchors(target), f"{path}: no section #{anchor} in docs/{page}"
