"""``steakhouse analyze`` (server/commands/analyze.py) end to end on small CSVs."""

from __future__ import annotations

import pandas as pd
import pingouin as pg
import pytest

from server.cli import main

HEADERS = {
    "anova.csv": "measure,effect,df1,df2,SS,SS_error,MS,MSE,F,p,ges,partial_eta2,",
    "simple_effects.csv": "measure,factor,at,df1,df2,MSE,F,p,ges,",
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


def run(csv_file, out, *extra: str, within: str = "robot,kitchen", dv: str = "ticks,interrupts") -> int:
    argv = ["analyze", "--csv", str(csv_file), "--dv", dv, "--within", within, "--subject", "participant",
            "--out", str(out)]
    return main([*argv, *extra])


def test_end_to_end_writes_all_files_with_exact_headers(csv_file, tmp_path, capsys) -> None:
    out = tmp_path / "results"
    assert run(csv_file, out) == 0
    for name, first_line in HEADERS.items():
        assert (out / name).read_text().splitlines()[0].startswith(first_line), name
    for measure in ("ticks", "interrupts"):
        for kind in ("interaction", "paired"):
            for ext in ("png", "svg"):
                assert (out / "plots" / f"{measure}_{kind}.{ext}").is_file()
    excluded = (out / "excluded.csv").read_text()
    assert "ticks,P02,\"missing cell robot=fov_aware, kitchen=none_3\"" in excluded
    assert "participant P02: missing cell robot fov_aware, kitchen none_3" in (out / "report.md").read_text(), \
        "levels in words in the report's prose"
    assert "ticks: n = 7 of 8 subjects, 1 excluded" in capsys.readouterr().out


def test_level_order_from_the_file_or_from_levels(csv_file, tmp_path) -> None:
    assert run(csv_file, tmp_path / "a", "--no-plots") == 0
    first = pd.read_csv(tmp_path / "a" / "descriptives.csv")
    assert first["robot"].drop_duplicates().tolist() == ["baseline", "fov_aware"]  # as they first appear
    assert run(csv_file, tmp_path / "b", "--no-plots", "--levels", "robot=fov_aware,baseline", "--levels",
               "kitchen=mid_2,none_3") == 0
    given = pd.read_csv(tmp_path / "b" / "descriptives.csv")
    assert given[["robot", "kitchen"]].drop_duplicates().values.tolist()[:2] == [["fov_aware", "mid_2"],
                                                                               ["fov_aware", "none_3"]]


def test_one_factor_and_three_factors(cells, tmp_path) -> None:
    base = cells(n_subjects=6, seed=1)
    base[base["kitchen"] == "none_3"].to_csv(tmp_path / "one.csv", index=False)
    assert run(tmp_path / "one.csv", tmp_path / "one", "--no-plots", within="robot", dv="ticks") == 0
    assert pd.read_csv(tmp_path / "one" / "anova.csv")["effect"].tolist() == ["robot"]
    three = pd.concat([base.assign(view=v) for v in ("top_down", "first_person")])
    three.to_csv(tmp_path / "three.csv", index=False)
    assert run(tmp_path / "three.csv", tmp_path / "three", within="robot,kitchen,view", dv="ticks") == 0
    assert len(pd.read_csv(tmp_path / "three" / "anova.csv")) == 7


def test_a_published_dataset_with_one_level_all_zero_exits_0_with_a_warning(tmp_path, capsys) -> None:
    # Issue 15: this stopped the analysis with KeyError: 'F' and wrote no report.
    df = pg.read_dataset("rm_anova2")
    df.loc[df["Metric"] == "Action", "Performance"] = 0
    df.to_csv(tmp_path / "rm.csv", index=False)
    argv = ["analyze", "--csv", str(tmp_path / "rm.csv"), "--dv", "Performance", "--within", "Time,Metric",
            "--subject", "Subject", "--out", str(tmp_path / "o")]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "warning: Performance: simple effect of Time at Metric=Action: not testable: no variance" in err
    assert (tmp_path / "o" / "report.md").is_file()


def test_ratings_get_rank_tests(cells, tmp_path) -> None:
    df = cells(n_subjects=8, seed=2)
    df["trust"] = (df["interrupts"] % 7 + 1).astype(int)
    df.to_csv(tmp_path / "r.csv", index=False)
    assert run(tmp_path / "r.csv", tmp_path / "o", "--no-plots", "--ratings", "trust=1..7", dv="ticks,trust") == 0
    ranks = pd.read_csv(tmp_path / "o" / "rank_tests.csv")
    assert set(ranks["measure"]) == {"trust"} and len(ranks) == 3


@pytest.mark.parametrize(("extra", "message"), [
    (("--levels", "robot"), "expected FACTOR=LEVEL"),
    (("--levels", "robot=baseline"), "does not list"),
    (("--ratings", "trust=7..1"), "MIN < MAX"),
    (("--ratings", "trust=a..b"), "expected COL or COL=MIN..MAX"),
])
def test_bad_options_exit_2_with_a_usage_message(csv_file, tmp_path, capsys, extra, message) -> None:
    assert run(csv_file, tmp_path / "o", *extra) == 2
    assert message in capsys.readouterr().err


def test_wrong_column_exits_2_naming_it(csv_file, tmp_path, capsys) -> None:
    assert run(csv_file, tmp_path / "o", dv="tickz") == 2
    err = capsys.readouterr().err
    assert "column 'tickz' not found" in err and "'ticks'" in err
    assert not (tmp_path / "o").exists()


def test_wrong_subject_column_exits_2(csv_file, tmp_path, capsys) -> None:
    argv = ["analyze", "--csv", str(csv_file), "--dv", "ticks", "--within", "robot,kitchen"]
    assert main([*argv, "--subject", "pid", "--out", str(tmp_path / "o")]) == 2
    assert "column 'pid' not found" in capsys.readouterr().err


def test_missing_file_exits_2(tmp_path, capsys) -> None:
    assert run(tmp_path / "nope.csv", tmp_path / "o") == 2
    assert "nope.csv: no such file" in capsys.readouterr().err


def test_within_takes_one_to_three_factors(csv_file, tmp_path, capsys) -> None:
    assert run(csv_file, tmp_path / "o", within="a,b,c,d") == 2
    assert "--within takes one to three factors" in capsys.readouterr().err


def test_csv_needs_the_role_flags(csv_file, capsys) -> None:
    assert main(["analyze", "--csv", str(csv_file), "--dv", "ticks"]) == 2
    assert "--csv needs --within, --subject, --out" in capsys.readouterr().err


def test_study_needs_out_and_takes_no_design_flags(capsys) -> None:
    assert main(["analyze", "--study", "steakhouse-2024"]) == 2
    assert "--study needs --out" in capsys.readouterr().err
    assert main(["analyze", "--study", "s", "--out", "o", "--within", "a,b"]) == 2
    assert "--study takes the design from the study; drop --within" in capsys.readouterr().err
    assert main(["analyze", "--study", "s", "--out", "o", "--levels", "robot=a,b"]) == 2
    assert "drop --levels" in capsys.readouterr().err


def test_csv_and_study_are_mutually_exclusive(csv_file, capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(["analyze", "--csv", str(csv_file), "--study", "x"])
    assert info.value.code == 2
    assert "not allowed with argument" in capsys.readouterr().err


def test_include_invalid_keeps_the_trials_the_server_marked(cells, tmp_path) -> None:
    df = cells(n_subjects=6, seed=3).assign(invalid_reason="")
    df.loc[0, "invalid_reason"] = "robot missed 30% of its decisions"
    df.to_csv(tmp_path / "c.csv", index=False)
    assert run(tmp_path / "c.csv", tmp_path / "a", "--no-plots", dv="ticks") == 0
    assert pd.read_csv(tmp_path / "a" / "anova.csv")["df2"].iloc[0] == 4
    assert run(tmp_path / "c.csv", tmp_path / "b", "--no-plots", "--include-invalid", dv="ticks") == 0
    assert pd.read_csv(tmp_path / "b" / "anova.csv")["df2"].iloc[0] == 5
    assert pd.read_csv(tmp_path / "b" / "exclusions.csv")["included"].tolist() == [1]
