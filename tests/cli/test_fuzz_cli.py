"""Every flag of every command, given a bad value, exits 2 with one line naming it.

``chainfountain.cli.main`` runs in-process. A value a flag does accept gives its
documented success (status 0, and for ``--json`` only finite numbers); any other value
gives status 2 and exactly one line on stderr that names the flag, never a traceback.
"""

from __future__ import annotations

import json
import math
import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pytest  # noqa: E402

from chainfountain import cli  # noqa: E402
from chainfountain.level import io  # noqa: E402

BAD = ["abc", "nan", "NaN", "inf", "-inf", "+inf", "-1", "-0.0", "0", "1e308", "-1e308",
       "1e999", "1e-320", "", " ", "1,5", "--1", "0x10", "1_0", " 5\n", "9" * 5000]
"""Values tried on every flag (plus the flag with no value at all)."""

FOUNTAIN = ["--l", "0.33", "--h", "0.28", "--H", "2"]


@pytest.fixture(autouse=True)
def _home(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.chdir(tmp_path)


@pytest.fixture
def level_file(tmp_path):
    return str(io.save(io.make_level("quick", "short in-process CLI run"), tmp_path / "q.toml"))


@pytest.fixture
def blocked(tmp_path):
    """A path no file can be written to: it lies under a regular file."""
    (tmp_path / "a-file").write_text("not a folder")
    return str(tmp_path / "a-file" / "sub" / "out")


def call(argv: list[str], capsys) -> tuple[int, str, str]:
    """Status, stdout and stderr of ``chainfountain ARGV`` (argparse's exits included)."""
    try:
        status = cli.main(argv)
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else 1
    out, err = capsys.readouterr()
    return status, out, err


def assert_refused(status: int, err: str, names: str | tuple[str, ...], argv) -> None:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert status == 2, (argv, status, err)
    assert "Traceback" not in err, (argv, err)
    assert len(lines) == 1 and err.count("\n") == 1, (argv, err)
    names = (names,) if isinstance(names, str) else names
    assert any(n in lines[0] for n in names), (argv, err)


def assert_finite_json(out: str) -> None:
    def walk(x):
        if isinstance(x, float):
            assert math.isfinite(x), out
        elif isinstance(x, dict):
            for v in x.values():
                walk(v)
        elif isinstance(x, list):
            for v in x:
                walk(v)

    walk(json.loads(out))


FOUNTAIN_FLAGS = ("--l", "--h", "--H", "--k", "--v", "--g")
"""A geometry and speed that do not fit together are refused naming the flags that
decide it (a speed too low for the geometry names ``--v``, whichever flag was extreme)."""


def check_flag(base: list[str], flag: str, capsys, *, json_out: bool = False,
               related: tuple[str, ...] = ()) -> None:
    """Every value of :data:`BAD` for ``flag`` after ``base``, and ``flag`` with no value;
    a refusal names ``flag`` or, for a combination, one of ``related``."""
    status, _, err = call([*base, flag], capsys)
    assert_refused(status, err, flag, [*base, flag])
    for bad in BAD:
        argv = [*base, flag, bad]
        status, out, err = call(argv, capsys)
        assert "Traceback" not in err, (argv, err)
        if status == 0:
            if json_out:
                assert_finite_json(out)
            continue
        assert_refused(status, err, (flag, *related), argv)


@pytest.mark.parametrize("flag", ["--l", "--h", "--H", "--g", "--k", "--v"])
def test_theory_flags(flag, capsys):
    check_flag(["theory", "--json", *[a for a in FOUNTAIN if a != flag]]
               if flag not in FOUNTAIN else
               ["theory", "--json", *FOUNTAIN[:FOUNTAIN.index(flag)],
                *FOUNTAIN[FOUNTAIN.index(flag) + 2:]], flag, capsys, json_out=True,
               related=FOUNTAIN_FLAGS)


def _without(args: list[str], flag: str) -> list[str]:
    if flag not in args:
        return list(args)
    i = args.index(flag)
    return args[:i] + args[i + 2:]


@pytest.mark.parametrize("flag", ["--l", "--h", "--H", "--g", "--k", "--v", "--xi2", "--xi3",
                                  "--lambda", "--slope"])
def test_design_flags(flag, capsys):
    base = ["design", "--json", *FOUNTAIN, "--v", "5"]
    if flag == "--k":
        base = _without(base, "--v")
    check_flag(_without(base, flag), flag, capsys, json_out=True, related=FOUNTAIN_FLAGS)


def test_design_out(tmp_path, blocked, capsys):
    base = ["design", *FOUNTAIN, "--v", "5", "--out"]
    status, _, err = call([*base, blocked], capsys)
    assert_refused(status, err, "--out", base)
    status, _, err = call([*base, str(tmp_path)], capsys)  # a folder, not a file
    assert_refused(status, err, "--out", base)
    status, _, err = call([*base, ""], capsys)
    assert_refused(status, err, "--out", base)
    status, _, err = call([*base], capsys)
    assert_refused(status, err, "--out", base)
    status, out, _ = call([*base, str(tmp_path / "d.toml")], capsys)
    assert status == 0 and io.load(tmp_path / "d.toml").sim.feed.speed == pytest.approx(5.0)


@pytest.mark.parametrize("flag", [pytest.param("--duration", marks=pytest.mark.slow), "--seed"])
def test_run_flags(flag, level_file, tmp_path, capsys):
    base = ["run", level_file, "--quiet", "--out", str(tmp_path / "o")]
    if flag != "--duration":
        base += ["--duration", "0.05"]
    check_flag(base, flag, capsys)


def test_run_out_and_level(level_file, tmp_path, blocked, capsys):
    base = ["run", level_file, "--quiet", "--duration", "0.05", "--out"]
    for bad in (blocked, level_file, ""):
        status, _, err = call([*base, bad], capsys)
        assert_refused(status, err, "--out", [*base, bad])
    status, _, err = call(base, capsys)
    assert_refused(status, err, "--out", base)
    (tmp_path / "binary.toml").write_bytes(b"\x00\xff\xfe")
    for bad in ("", "nan", "no_such_level", "a\nb", str(tmp_path), str(tmp_path / "binary.toml"),
                "x" * 300, "x" * 300 + ".toml"):
        argv = ["run", bad, "--quiet", "--duration", "0.05", "--out", str(tmp_path / "o")]
        status, _, err = call(argv, capsys)
        assert_refused(status, err, ("no such", "not a", "is a directory", "cannot read"), argv)


@pytest.mark.parametrize("flag", ["--frames", "--size"])
def test_play_flags(flag, capsys):
    base = ["play", "--paused"] + (["--frames", "2"] if flag != "--frames" else [])
    check_flag(base, flag, capsys)


def test_play_paths(tmp_path, blocked, capsys):
    base = ["play", "--frames", "2", "--paused"]
    for flag, bad in (("--screenshot", blocked + ".png"), ("--screenshot", str(tmp_path / "x.jpg")),
                      ("--screenshot", ""), ("--screenshot", str(tmp_path) + "/"),
                      ("--out", str(tmp_path / "o")), ("--out", blocked)):
        argv = [*base, flag, bad]
        status, _, err = call(argv, capsys)
        assert_refused(status, err, flag, argv)
    for bad in ("", "nan", "no_such_level", str(tmp_path)):
        argv = [*base, bad]
        status, _, err = call(argv, capsys)
        assert_refused(status, err, ("no such", "is a directory"), argv)
    status, _, err = call([*base, "--screenshot", str(tmp_path / "s.png")], capsys)
    assert status == 0 and (tmp_path / "s.png").exists(), err


def test_check_schema_figures(tmp_path, blocked, level_file, capsys):
    (tmp_path / "binary.toml").write_bytes(bytes(range(256)))
    for bad in ("", "nan", str(tmp_path), str(tmp_path / "binary.toml"), "a\nb.toml"):
        argv = ["check", level_file, bad]
        status, out, err = call(argv, capsys)
        assert_refused(status, err, ("no such", "not a", "is a directory"), argv)
    status, _, err = call(["check"], capsys)
    assert_refused(status, err, "LEVEL", ["check"])
    for flag, argv in (("--out", ["schema", "--out", blocked]),
                       ("--out", ["schema", "--out", str(tmp_path)]),
                       ("--out", ["schema", "--out", ""]), ("--out", ["schema", "--out"]),
                       ("--out", ["figures", "--out", blocked, "--only", "sol"]),
                       ("--out", ["figures", "--out", ""]), ("--out", ["figures", "--out"]),
                       ("--only", ["figures", "--only", "nope"]),
                       ("--only", ["figures", "--only", ""]), ("--only", ["figures", "--only"])):
        status, _, err = call(argv, capsys)
        assert_refused(status, err, flag, argv)
    status, out, _ = call(["schema", "--out", str(tmp_path / "levels.md")], capsys)
    assert status == 0 and (tmp_path / "levels.md").read_text() == io.schema_markdown()


def test_unknown_commands_and_flags(capsys):
    for argv in (["nope"], ["theory", "--nope"], ["run"], ["--nope"], ["theory", *FOUNTAIN,
                                                                       "--k", "1", "--v", "2"]):
        status, _, err = call(argv, capsys)
        assert status == 2 and "Traceback" not in err and err.count("\n") == 1, (argv, err)
