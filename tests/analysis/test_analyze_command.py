"""``steakhouse analyze`` (server/commands/analyze.py) end to end on a small CSV."""

from __future__ import annotations

import pytest

from server.cli import main

HEADERS = {
    "anova.csv": "measure,effect,df1,df2,SS,F,p,ges,partial_eta2",
    "simple_effects.csv": "measure,level,effect,df1,df2,F,p,p_holm,ges",
    "descriptives.csv": "measure,robot,kitchen,n,mean,sd,se_ws,ci95_low,ci95_high",
    "excluded.csv": "measure,subject,reason",
}


@pytest.fixture
def csv_file(cells, tmp_path):
    df = cells(n_subjects=8, seed=5)
    gone = (df["participant"] == "P02") & (df["robot"] == "fov_aware") & (df["kitchen"] == "none_3")
    path = tmp_path / "cells.csv"
    df[~gone].to_csv(path, index=False)
    return path


def run(csv_file, out, *extra: str) -> int:
    argv = ["analyze", "--csv", str(csv_file), "--dv", "ticks,interrupts"]
    argv += ["--within", "robot,kitchen", "--subject", "participant", "--out", str(out)]
    return main([*argv, *extra])


def test_end_to_end_writes_all_files_with_exact_headers(csv_file, tmp_path, capsys) -> None:
    out = tmp_path / "results"
    assert run(csv_file, out) == 0
    for name, first_line in HEADERS.items():
        assert (out / name).read_text().splitlines()[0] == first_line
    for measure in ("ticks", "interrupts"):
        for kind in ("interaction", "paired"):
            for ext in ("png", "svg"):
                assert (out / "plots" / f"{measure}_{kind}.{ext}").is_file()
    assert (out / "report.md").is_file() and (out / "report.html").is_file()
    excluded = (out / "excluded.csv").read_text()
    assert "ticks,P02,\"missing cell robot=fov_aware, kitchen=none_3\"" in excluded
    assert "subject P02: missing cell robot=fov_aware, kitchen=none_3" in (
        out / "report.md"
    ).read_text()
    stdout = capsys.readouterr().out
    assert "ticks: n = 7 of 8 subjects, 1 excluded" in stdout


def test_wrong_column_exits_2_naming_it(csv_file, tmp_path, capsys) -> None:
    argv = ["analyze", "--csv", str(csv_file), "--dv", "tickz", "--within", "robot,kitchen"]
    code = main([*argv, "--subject", "participant", "--out", str(tmp_path / "o")])
    assert code == 2
    err = capsys.readouterr().err
    assert "column 'tickz' not found" in err
    assert "'ticks'" in err  # the available columns are listed
    assert not (tmp_path / "o").exists()


def test_wrong_subject_column_exits_2(csv_file, tmp_path, capsys) -> None:
    argv = ["analyze", "--csv", str(csv_file), "--dv", "ticks", "--within", "robot,kitchen"]
    assert main([*argv, "--subject", "pid", "--out", str(tmp_path / "o")]) == 2
    assert "column 'pid' not found" in capsys.readouterr().err


def test_missing_file_exits_2(tmp_path, capsys) -> None:
    assert run(tmp_path / "nope.csv", tmp_path / "o") == 2
    assert "nope.csv: no such file" in capsys.readouterr().err


def test_within_needs_two_factors(csv_file, tmp_path, capsys) -> None:
    argv = ["analyze", "--csv", str(csv_file), "--dv", "ticks", "--within", "robot"]
    assert main([*argv, "--subject", "participant", "--out", str(tmp_path / "o")]) == 2
    assert "--within needs exactly two factors" in capsys.readouterr().err


def test_csv_needs_the_role_flags(csv_file, capsys) -> None:
    assert main(["analyze", "--csv", str(csv_file), "--dv", "ticks"]) == 2
    assert "--csv needs --within, --subject, --out" in capsys.readouterr().err


def test_study_needs_out_and_takes_no_design_flags(capsys) -> None:
    assert main(["analyze", "--study", "steakhouse-2024"]) == 2
    assert "--study needs --out" in capsys.readouterr().err
    assert main(["analyze", "--study", "s", "--out", "o", "--within", "a,b"]) == 2
    assert "--study uses within = robot,kitchen and subject = participant; drop --within" in capsys.readouterr().err


def test_csv_and_study_are_mutually_exclusive(csv_file, capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(["analyze", "--csv", str(csv_file), "--study", "x"])
    assert info.value.code == 2
    assert "not allowed with argument" in capsys.readouterr().err
