"""The two-step design procedure (theory part)."""

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from chainfountain.theory import Fountain, special_case_k
from chainfountain.theory.design import DesignError, design, xi_limits

PAPER = Fountain.from_geometry(0.33, 0.28, 2.0, k=0.377)


def test_paper_k_0377_is_the_special_case():
    # The paper's k = 0.377 is (to its 3 digits) the k of the case xi2 = xi3 = 1/2, Tbar_lc = 0.
    assert special_case_k(PAPER.q, PAPER.h, PAPER.H) == pytest.approx(0.377, abs=5e-4)
    d = design(PAPER, lam=0.05)
    assert d.label.startswith("special case")
    assert d.settings.T_lc == pytest.approx(0.0, abs=1e-3)


def test_kmax_default_is_the_limit_case():
    f = PAPER.with_k(PAPER.k_max)
    d = design(f, lam=0.05)
    assert d.settings.xi3 == pytest.approx(1 / (2 * f.k * f.H))
    assert d.settings.T_lc == pytest.approx(0.0, abs=1e-12)
    assert d.settings.TE_bar == pytest.approx(0.0, abs=1e-12)
    assert d.settings.T0_bar == pytest.approx(f.k * f.H)


@settings(max_examples=200, deadline=None)
@given(l=st.floats(0.05, 3), h=st.floats(0, 1.5), H=st.floats(0.2, 3), u=st.floats(0.01, 0.99),
       x2=st.one_of(st.none(), st.floats(0, 1)), x3=st.one_of(st.none(), st.floats(0, 2)))
def test_every_design_supplies_the_fountain(l, h, H, u, x2, x3):  # noqa: E741
    base = Fountain(l=l, h=h, H=H, k=1.0)
    lo, hi = base.k_range()
    assume(lo < hi and base.xi < 1)
    f = base.with_k(lo + u * (hi - lo))
    xi2_max, xi3_min = xi_limits(f)
    if (x2 is not None and x2 > xi2_max) or (x3 is not None and x3 < xi3_min):
        with pytest.raises(DesignError, match="nearest admissible"):
            design(f, lam=0.1, xi2=x2, xi3=x3)
        return
    d = design(f, lam=0.1, xi2=x2, xi3=x3)
    s = d.settings
    assert s.feasible
    assert s.balanced
    assert s.T0_bar == pytest.approx(f.T0_bar, abs=1e-9)
    assert s.TE_bar == pytest.approx(f.TE_bar, abs=1e-9)
    assert d.m_uc >= 0 and d.m_lc >= 0


def test_rejects_ruled_out_targets():
    with pytest.raises(DesignError, match=r"v\(k_max\).*nearest admissible: --v 4.77"):
        design(PAPER.with_k(0.5), lam=0.05)
    with pytest.raises(DesignError, match="energy bound"):
        design(PAPER.with_k(0.2), lam=0.05)


def test_cart_mass_from_force():
    d = design(PAPER, lam=0.05, xi2=0.2, slope=math.radians(30))
    force = d.settings.T_uc * 0.05 * PAPER.v**2
    # the cart passes on MEASURED_CART_GAIN = 1/2 of its force: twice the paper's mass
    assert d.m_uc == pytest.approx(force / (0.5 * 9.81 * 0.5))
    paper = design(PAPER, lam=0.05, xi2=0.2, slope=math.radians(30), cart_gain=1.0)
    assert paper.m_uc == pytest.approx(force / (9.81 * 0.5))


def test_design_cli(capsys):
    import json

    from chainfountain.cli import main

    assert main(["design", "--l", "0.33", "--h", "0.28", "--H", "2", "--k", "0.377",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["xi2"] == 0.5 and out["xi3"] == 0.5
    assert out["T0_bar"] == pytest.approx(0.8774, abs=1e-4)
    assert main(["design", "--l", "0.33", "--h", "0.28", "--H", "2", "--k", "0.5"]) == 2
    err = capsys.readouterr().err
    assert "v(k_max)" in err and "nearest admissible" in err and err.count("\n") == 1
