"""The readout in plain words for a class, and in the paper's symbols for an expert (E)."""

from __future__ import annotations

import math

from chainfountain.app.readout import Readout
from chainfountain.app.readout_text import readout_rows


def _ro(**kw) -> Readout:
    base = dict(v=4.0, k=9.81 / 16, q=2.0, h=1.2, l=2.5, H=3.0, T0_bar=0.6, TE_bar=0.05,
                T0_theory=0.55, TE_theory=0.0, measured=True, paper_h=1.25)
    base.update(kw)
    return Readout(**base)


def test_plain_words_give_forces_in_newtons_with_the_symbols_beside() -> None:
    rows = readout_rows(_ro(), lam=0.05, expert=False)
    text = {r.symbol: r.text for r in rows if r.symbol}
    assert "chain speed  4.00 m/s" in text["v"]
    assert "1.20 m above the launch" in text["h"]
    # T = Tbar * lambda * v^2 = 0.6 * 0.05 * 16 = 0.48 N; the paper's 0.55 -> 0.44 N
    assert "0.48 N" in text["Tbar_0"] and "paper 0.44" in text["Tbar_0"]
    assert "0.04 N" in text["Tbar_E"] and "paper 0.00" in text["Tbar_E"]
    assert any("the paper predicts 1.25 m" in r.text for r in rows)
    assert not any("k = g/v^2" in r.text for r in rows)


def test_expert_rows_use_the_papers_symbols() -> None:
    rows = readout_rows(_ro(), lam=0.05, expert=True)
    joined = "\n".join(r.text for r in rows)
    assert "k = g/v^2" in joined and "Tbar_0  0.600  (theory 0.550)" in joined


def test_nothing_measured_reads_as_dashes_not_nan() -> None:
    ro = _ro(v=math.nan, h=math.nan, l=math.nan, T0_bar=math.nan, TE_bar=math.nan,
             T0_theory=math.nan, TE_theory=math.nan, measured=False, paper_h=math.nan)
    for expert in (False, True):
        joined = "\n".join(r.text for r in readout_rows(ro, 0.05, expert))
        assert "nan" not in joined.lower() and "--" in joined
