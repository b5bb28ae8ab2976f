"""The researcher-facing commands of the world: layout check, fov, play (stable output, clear errors)."""

from __future__ import annotations

import json

import pytest

from server.cli import main
from study_config import LAYOUT_DIR


def test_layout_check_accepts_names_and_paths(capsys):
    assert main(["layout", "check", "none_3", str(LAYOUT_DIR / "mid_2.layout")]) == 0
    assert "ok: none_3" in capsys.readouterr().out


def test_layout_check_names_file_line_column_and_reason(tmp_path, capsys):
    broken = tmp_path / "broken.layout"
    broken.write_text("XXXXX\nXO1QX\nXMDPX\nXBW2X\nXSXXX\n")
    assert main(["layout", "check", "none_3", str(broken)]) == 1
    err = capsys.readouterr().err
    assert f"{broken}:2:4: unknown character 'Q'" in err


def test_layout_check_lists_every_problem_of_a_file_one_per_line(tmp_path, capsys):
    broken = tmp_path / "broken.layout"
    broken.write_text("XXXXXXX\nXOMDPBX\nX1 Q 2X\n   2  X\nXXSWXXX\n")
    assert main(["layout", "check", str(broken), "none_3"]) == 1
    out, err = capsys.readouterr()
    assert out == "ok: none_3 (15x10)\n"
    assert err.splitlines() == [
        f"invalid: {broken}:3:4: unknown character 'Q'; allowed: X, space, O, M, D, P, B, W, S, 1, 2",
        f"invalid: {broken}:4:1: the kitchen is not closed: floor on the border",
        f"invalid: {broken}:4:4: a second human start ('2'); the first is at line 3, column 6",
    ]


def test_fov_json_lists_visible_cells(capsys):
    assert main(["fov", "--layout", "none_3", "--x", "5", "--y", "3", "--facing", "east", "--json"]) == 0
    visible = {tuple(c) for c in json.loads(capsys.readouterr().out)["visible"]}
    assert (5, 3) in visible and (5, 2) in visible and (5, 4) in visible
    assert (4, 3) not in visible and (6, 3) in visible


def test_fov_grid_masks_out_of_view_cells(capsys):
    assert main(["fov", "--layout", "none_3", "--x", "5", "--y", "3", "--facing", "east"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[3][5] == ">" and lines[3][4] == "#" and lines[3][6] == "."


def test_fov_360_masks_nothing(capsys):
    main(["fov", "--layout", "none_3", "--x", "5", "--y", "3", "--facing", "east", "--angle", "360"])
    assert "#" not in "".join(capsys.readouterr().out.splitlines()[:-1])


@pytest.mark.parametrize("argv", [
    ["fov", "--layout", "none_3", "--x", "0", "--y", "0", "--facing", "east"],
    ["fov", "--layout", "nowhere", "--x", "5", "--y", "3", "--facing", "east"],
    ["fov", "--layout", "none_3", "--x", "5", "--y", "3", "--facing", "east", "--angle", "0"],
    ["play", "--layout", "none_3", "--seed", "1", "--kb-delay", "-1"],
])
def test_bad_arguments_get_a_usage_message(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: steakhouse") and "error:" in err


def test_unknown_facing_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["fov", "--layout", "none_3", "--x", "5", "--y", "3", "--facing", "up"])
    assert exit_info.value.code == 2 and "invalid choice" in capsys.readouterr().err


def test_play_json_reports_the_trial(capsys):
    assert main(["play", "--layout", "none_3", "--seed", "4", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["finished"] is True and result["delivered"] == 2 and result["ticks"] < 400
    assert result["kb_gap_mean"] > 0


def test_play_is_reproducible(capsys):
    main(["play", "--layout", "mid_2", "--seed", "9", "--json"])
    first = capsys.readouterr().out
    main(["play", "--layout", "mid_2", "--seed", "9", "--json"])
    assert capsys.readouterr().out == first


def test_play_text_output(capsys):
    assert main(["play", "--layout", "practice", "--seed", "2"]) == 0
    out = capsys.readouterr().out
    assert "orders delivered" in out and "mean KB gap" in out
