"""``steakhouse study validate FILE...``: exit codes, a summary per valid file, every problem otherwise."""

from __future__ import annotations

from pathlib import Path

import pytest

from server.cli import main

STUDY_CONFIG = Path(__file__).resolve().parents[3] / "study_config"
PAPER = str(STUDY_CONFIG / "paper_study.yaml")
DEMO = str(STUDY_CONFIG / "demo.yaml")


def test_valid_files_exit_0_with_one_summary_line_each(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["study", "validate", PAPER, DEMO]) == 0
    out, err = capsys.readouterr()
    paper, demo = out.splitlines()
    assert paper.startswith(f"{PAPER}: ok: paper_study: 4 conditions (fov_aware@none_3, fov_aware@mid_2, ")
    assert "4 condition orders (latin_square)" in paper
    assert demo.startswith(f"{DEMO}: ok: demo: 2 conditions (fov_aware@none_3, baseline@none_3)")
    assert "2 condition orders" in demo
    assert err.splitlines() == [  # the shipped example's placeholder codes are warnings, not errors
        f"{PAPER}: recruiting.{kind}: warning: still the placeholder shipped with the example: replace it with "
        "the code your recruiting platform gives you" for kind in ("completion_code", "screen_out_code")]


def test_invalid_file_exits_1_listing_every_problem(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text(
        "id: bad\ntitle: Bad\nkitchens: [none_3, atlantis]\nrobots: [fov_aware, terminator]\n"
        "questionnaires:\n  - id: q\n    items:\n      - {id: a, text: Hello.}\n",
        encoding="utf-8",
    )
    assert main(["study", "validate", str(bad)]) == 1
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    assert lines[0].startswith(f"{bad}: kitchens[1]: unknown kitchen 'atlantis'")
    assert lines[1].startswith(f"{bad}: robots[1]: unknown robot 'terminator'")
    assert lines[2].startswith(f"{bad}: questionnaires[0].items[0].scale: required field is missing")
    assert lines[3] == "1 of 1 study file(s) invalid"


def test_one_invalid_file_fails_the_run_but_all_are_checked(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    broken = tmp_path / "broken.yaml"
    broken.write_text("id: x\ntitle: [unclosed\n", encoding="utf-8")
    assert main(["study", "validate", str(broken), PAPER]) == 1
    out, err = capsys.readouterr()
    assert out.startswith(f"{PAPER}: ok: paper_study")
    assert err.startswith(f"{broken}: invalid YAML at line 3, column 1")


def test_validate_needs_a_file(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(["study", "validate"])
    assert info.value.code == 2
    assert "FILE" in capsys.readouterr().err


def test_kitchen_files_are_checked_as_serve_would_and_every_problem_is_listed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "my").mkdir()
    grid = (STUDY_CONFIG / "layouts" / "none_3.layout").read_text(encoding="utf-8").splitlines()
    (tmp_path / "my" / "open.layout").write_text("\n".join([grid[0][:7] + " " + grid[0][8:], *grid[1:]]) + "\n",
                                                 encoding="utf-8")
    # Three different problems in one file: every one is listed, in reading order.
    grid[2] = grid[2][:6] + "Q" + grid[2][7:]
    grid[4] = grid[4][:4] + "2" + grid[4][5:]
    grid[6] = " " + grid[6][1:]
    (tmp_path / "my" / "kitchen.layout").write_text("\n".join(grid) + "\n", encoding="utf-8")
    study = tmp_path / "study.yaml"
    study.write_text(
        "id: kitchens\ntitle: Kitchens\n"
        "kitchens: [none_3, my/kitchen.layout, my/missing.layout, none_3, my/open.layout]\n"
        "robots: [fov_aware, terminator, fov_aware]\nfactors: [robot, kitchen]\n"
        "practice:\n  - {kitchen: my/kitchen.layout, robot: stay}\n",
        encoding="utf-8",
    )
    assert main(["study", "validate", str(study)]) == 1
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    problems = [line.split(" (line ")[0] for line in lines[:-1]]
    kitchen_problems = [
        "(my/kitchen.layout:3:7): unknown character 'Q'; allowed: X, space, O, M, D, P, B, W, S, 1, 2",
        "(my/kitchen.layout:5:5): a second human start ('2'); the first is at line 4, column 6",
        "(my/kitchen.layout:7:1): the kitchen is not closed: floor on the border",
    ]
    assert problems == [
        *(f"{study}: kitchens[1] {problem}" for problem in kitchen_problems),
        f"{study}: kitchens[2]: no kitchen file at {(tmp_path / 'my' / 'missing.layout').resolve()}",
        f"{study}: kitchens[3]: duplicate kitchen 'none_3' (already at [0])",
        f"{study}: kitchens[4] (my/open.layout:1:8): the kitchen is not closed: floor on the border",
        f"{study}: robots[1]: unknown robot 'terminator'; choose one of: fov_aware, fov_aware_showing, baseline, "
        "no_rollout, stay",
        f"{study}: robots[2]: duplicate robot 'fov_aware' (already at [0])",
        *(f"{study}: practice[0].kitchen {problem}" for problem in kitchen_problems),
    ], "\n".join(lines)
    assert lines[-1] == "1 of 1 study file(s) invalid"


def test_a_bad_kitchen_or_robot_does_not_hide_the_checks_of_factors_and_counterbalancing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    study = tmp_path / "study.yaml"
    study.write_text(
        "id: masks\ntitle: Masks\nkitchens: [none_3, missing.layout]\nrobots: [fov_aware, terminator]\n"
        "factors: [robot, kitchen]\ncounterbalancing: {scheme: fixed, order: [nope@none_3]}\n",
        encoding="utf-8",
    )
    assert main(["study", "validate", str(study)]) == 1
    problems = [line.split(" (line ")[0].split(": ", 1)[1] for line in capsys.readouterr()[1].splitlines()[:-1]]
    assert problems == [
        f"kitchens[1]: no kitchen file at {(tmp_path / 'missing.layout').resolve()}",
        "robots[1]: unknown robot 'terminator'; choose one of: fov_aware, fov_aware_showing, baseline, no_rollout, "
        "stay",
        "counterbalancing.order[0]: unknown condition 'nope@none_3'; conditions are: fov_aware@none_3, "
        "fov_aware@missing, terminator@none_3, terminator@missing",
        "counterbalancing.order: missing conditions: fov_aware@none_3, fov_aware@missing, terminator@none_3, "
        "terminator@missing",
    ], problems
    study.write_text(study.read_text(encoding="utf-8").replace("factors: [robot, kitchen]", "factors: [robot]"),
                     encoding="utf-8")
    assert main(["study", "validate", str(study)]) == 1
    assert ("factors: kitchens has 2 entries but 'kitchen' is not a factor; add it to factors or keep one entry"
            in capsys.readouterr()[1])
