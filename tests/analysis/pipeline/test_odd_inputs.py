"""Odd inputs get a message that names the problem and what to do, and exit code 2: never a traceback, never an
empty success (docs/analysis.md, "Odd inputs")."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from steakhouse_store_study import Participant, play_participant

from server.cli import main
from server.flow import service
from server.flow.progress import Move

ARGS = ["--dv", "ticks", "--within", "robot,kitchen", "--subject", "participant", "--no-plots"]


def analyze_csv(tmp_path: Path, table, capsys, out: Path | None = None) -> tuple[int, str]:
    path = tmp_path / "cells.csv"
    table.to_csv(path, index=False)
    code = main(["analyze", "--csv", str(path), *ARGS, "--out", str(out or tmp_path / "out")])
    return code, capsys.readouterr().err


def test_an_infinite_cell_is_named_by_its_row(tmp_path, capsys, cells) -> None:
    cells = cells(8)
    cells.loc[5, "ticks"] = -np.inf
    code, err = analyze_csv(tmp_path, cells, capsys)
    assert code == 2 and "1 value(s) of ticks are not finite: row 6 (participant P02, robot=baseline, " \
                          "kitchen=mid_2): -inf" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists(), "nothing written"


def test_a_header_only_table_says_it_has_no_rows(tmp_path, capsys, cells) -> None:
    code, err = analyze_csv(tmp_path, cells(4).head(0), capsys)
    assert code == 2 and "the table has no rows (a header only)" in err and "not numeric" not in err


def test_a_table_whose_every_row_is_excluded_says_so_and_how_to_keep_them(tmp_path, capsys, cells) -> None:
    cells = cells(4).assign(invalid_reason="robot decisions missed their deadline", missed_decisions_pct=40.0)
    code, err = analyze_csv(tmp_path, cells, capsys)
    assert code == 2 and "all 16 row(s) were left out by the exclusion rules: 16 by rule invalid" in err
    assert "--include-invalid" in err and "0 level" not in err
    assert main(["analyze", "--csv", str(tmp_path / "cells.csv"), *ARGS, "--include-invalid",
                 "--out", str(tmp_path / "kept")]) == 0


def test_out_naming_a_file_is_refused_before_anything_is_read(tmp_path, capsys, cells) -> None:
    taken = tmp_path / "results.txt"
    taken.write_text("keep me")
    code, err = analyze_csv(tmp_path, cells(4), capsys, out=taken)
    assert code == 2 and f"--out {taken} is a file, not a folder" in err and "Traceback" not in err
    code, err = analyze_csv(tmp_path, cells(4), capsys, out=taken / "inside")
    assert code == 2 and f"{taken} is a file, not a folder" in err
    for command in (["export", "--study", "any"], ["analyze", "--study", "any"],
                    ["power", "--study", "any", "--n", "8"]):
        assert main([*command, "--out", str(taken), "--database-url", f"sqlite:///{tmp_path / 'none.db'}"]) == 2
        assert f"--out {taken} is a file" in capsys.readouterr().err, command
    assert taken.read_text() == "keep me"
    (tmp_path / "study").mkdir()
    (tmp_path / "study" / "data").write_text("a file where the export goes")
    assert main(["analyze", "--study", "any", "--out", str(tmp_path / "study")]) == 2
    assert "holds data, which is a file" in capsys.readouterr().err


def join_pilot(store, loaded, name: str) -> int:
    """A simulated pilot participant (joined as steakhouse pilot joins them) who consented and read on."""
    names = loaded.study.recruiting.url_parameters
    joined = service.join(store, loaded, {names[0]: name}, False, pilot_pace="fast")
    service.move(store, joined.participant.id, Move.ACCEPT_CONSENT)
    service.move(store, joined.participant.id, Move.FINISH_INSTRUCTIONS)
    return joined.participant.id


@pytest.mark.store_agnostic
def test_a_store_with_only_pilots_hints_include_pilot_and_power_wants_more_of_them(loaded_2x2, store, db_url,
                                                                                   tmp_path, capsys) -> None:
    play_participant(store, loaded_2x2, join_pilot(store, loaded_2x2, "pilot-a"), Participant(seed=1))
    url = ["--database-url", db_url]
    assert main(["analyze", "--study", "two_by_two", "--out", str(tmp_path / "a"), "--no-plots", *url]) == 2
    err = capsys.readouterr().err
    assert "1 simulated pilot participant(s)" in err and "add --include-pilot to analyse them" in err
    assert main(["export", "--study", "two_by_two", "--out", str(tmp_path / "e"), *url]) == 0
    assert "1 simulated pilot participant(s) of this study were left out; --include-pilot exports them" in \
        capsys.readouterr().err
    power = tmp_path / "power"
    assert main(["power", "--study", "two_by_two", "--n", "4,8", "--simulations", "20", "--dv", "ticks",
                 "--out", str(power), *url]) == 2
    err = capsys.readouterr().err
    assert "too few pilot participants to simulate: ticks: 1 complete pilot participant(s); at least 2" in err
    assert not (power / "power.csv").exists(), "no empty table"
    play_participant(store, loaded_2x2, join_pilot(store, loaded_2x2, "pilot-b"), Participant(seed=2))
    assert main(["power", "--study", "two_by_two", "--n", "4,8", "--simulations", "20", "--dv", "ticks",
                 "--no-plots", "--out", str(power), *url]) == 0
    report = (power / "power.md").read_text(encoding="utf-8")
    assert "power.png" not in report and not (power / "power.png").exists(), "no plot promised when none is drawn"
