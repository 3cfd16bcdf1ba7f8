"""The ``chainfountain theory`` command."""

import json
import subprocess
import sys

import pytest

from chainfountain.cli import main

EXAMPLE = ["theory", "--l", "0.33", "--h", "0.28", "--H", "2"]


def test_json_example(capsys):
    assert main(EXAMPLE + ["--k", "0.377", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("q", "qH", "k", "v", "k_max", "v_min", "v_max", "T0_bar", "TE_bar",
                "alpha0_deg", "alphaE_deg", "bounds_ok"):
        assert key in out
    assert round(out["qH"], 2) == 44.20
    assert out["v"] == pytest.approx(5.10, abs=5e-3)
    assert out["k_max"] == pytest.approx(0.4301, abs=1e-4)
    assert out["T0_bar"] == pytest.approx(0.8774, abs=1e-4)
    assert out["TE_bar"] == pytest.approx(0.1234, abs=1e-4)
    assert out["bounds_ok"] is True


def test_table_and_range(capsys):
    assert main(EXAMPLE + ["--v", "4.8"]) == 0
    out = capsys.readouterr().out
    assert "Tbar_0" in out and "holds" in out
    assert main(EXAMPLE) == 0
    out = capsys.readouterr().out
    assert "k range" in out and "0.4301" in out


def test_h_does_not_collide_with_help(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["theory", "--help"])
    assert exc.value.code == 0
    assert "OVERSHOOT" in capsys.readouterr().out


@pytest.mark.parametrize(
    "args, flag",
    [
        (["--l", "-1", "--h", "0.28", "--H", "2"], "--l"),
        (["--l", "0", "--h", "0.28", "--H", "2"], "--l"),
        (["--l", "0.33", "--h", "abc", "--H", "2"], "--h"),
        (["--l", "0.33", "--h", "0.28", "--H", "nan"], "--H"),
        (["--l", "0.33", "--h", "0.28", "--H", "2", "--k", "0.5"], "--k"),
        (["--l", "0.33", "--h", "0.28", "--H", "2", "--k", "-1"], "--k"),
        (["--l", "0.33", "--h", "0.28", "--H", "2", "--v", "4"], "--v"),
        (["--l", "0.33", "--h", "0.28", "--H", "2", "--k", "0.3", "--v", "5"], "--v"),
    ],
)
def test_bad_input_one_line_no_traceback(args, flag):
    proc = subprocess.run(
        [sys.executable, "-m", "chainfountain", "theory", *args],
        capture_output=True, text=True, timeout=60,
    )
    assert proc.returncode != 0
    err = proc.stderr.strip()
    assert "Traceback" not in err
    assert len(err.splitlines()) == 1, err
    assert flag in err and "allowed" in err or "not allowed" in err


def test_console_script_and_module_agree():
    a = subprocess.run([sys.executable, "-m", "chainfountain", *EXAMPLE, "--k", "0.377", "--json"],
                       capture_output=True, text=True, timeout=60)
    assert a.returncode == 0
    assert json.loads(a.stdout)["qH"] == pytest.approx(44.2012, abs=1e-4)
