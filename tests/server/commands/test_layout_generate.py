"""``steakhouse layout generate``: kitchens a researcher can check, reproduce and study with."""

from __future__ import annotations

import pytest

from server.cli import main


def test_generated_kitchens_pass_layout_check(tmp_path, capsys):
    assert main(["layout", "generate", "--seed", "40", "--count", "4", "--out", str(tmp_path)]) == 0
    files = sorted(tmp_path.glob("*.layout"))
    assert [f.name.split("_")[1] for f in files] == ["40", "41", "42", "43"]
    capsys.readouterr()
    assert main(["layout", "check", *map(str, files)]) == 0
    assert capsys.readouterr().out.count("ok: ") == 4


def test_same_seed_same_files(tmp_path):
    for folder in ("a", "b"):
        main(["layout", "generate", "--seed", "7", "--count", "3", "--out", str(tmp_path / folder)])
    a = {f.name: f.read_text() for f in (tmp_path / "a").iterdir()}
    assert a == {f.name: f.read_text() for f in (tmp_path / "b").iterdir()} and len(a) == 3


def test_style_and_size_are_honoured(tmp_path):
    assert main(["layout", "generate", "--seed", "1", "--count", "2", "--style", "split", "--size", "13x9",
                 "--out", str(tmp_path)]) == 0
    for path in tmp_path.iterdir():
        assert path.stem.endswith("_split")
        rows = path.read_text().splitlines()
        assert (len(rows[0]), len(rows)) == (13, 9)


@pytest.mark.parametrize("extra, reason", [
    (["--style", "galley"], "unknown style 'galley'"),
    (["--size", "big"], "not WIDTHxHEIGHT"),
    (["--size", "5x5"], "too small"),
    (["--count", "0"], "--count must be at least 1"),
])
def test_bad_arguments_get_a_usage_message(tmp_path, capsys, extra, reason):
    assert main(["layout", "generate", "--seed", "1", "--out", str(tmp_path), *extra]) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: steakhouse layout generate") and reason in err
    assert not list(tmp_path.iterdir())
