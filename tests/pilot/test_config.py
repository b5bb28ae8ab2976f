"""The simulated participant's parameters: defaults, a YAML file, ``--set``; bad values name file, field, reason."""

from __future__ import annotations

from pathlib import Path

import pytest

from pilot.config import ParticipantConfig, PilotConfigError, load_config, parse_setting
from server.cli import main
from study_config import STUDY_DIR


def test_a_file_and_settings_override_the_defaults(tmp_path: Path) -> None:
    path = tmp_path / "pilot.yaml"
    path.write_text("error_rate: 0.2\nnotice_probability: 0.9\n", encoding="utf-8")
    config = load_config(path, dict([parse_setting("notice_probability=0.1")]))
    assert (config.error_rate, config.notice_probability) == (0.2, 0.1)
    assert config.decision_latency_ticks == ParticipantConfig().decision_latency_ticks


def test_a_bad_value_names_the_file_and_the_field(tmp_path: Path) -> None:
    path = tmp_path / "pilot.yaml"
    path.write_text("error_rate: 2\n", encoding="utf-8")
    with pytest.raises(PilotConfigError, match=r"pilot.yaml: error_rate: .*less than or equal to 1"):
        load_config(path)
    with pytest.raises(PilotConfigError, match="unknown parameter 'speed'"):
        parse_setting("speed=3")


def test_the_command_reports_usage_problems(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    study = str(STUDY_DIR / "paper_study.yaml")
    assert main(["pilot", "--study", study, "--participants", "0"]) == 2
    assert main(["pilot", "--study", study, "--participants", "1", "--set", "nonsense"]) == 2
    assert main(["pilot", "--study", str(tmp_path / "none.yaml"), "--participants", "1"]) == 2
    assert main(["power", "--study", "paper_study", "--n", "8,x", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "--participants must be at least 1" in err and "expected name=value" in err
    assert "no such file" in err and "expected whole numbers" in err
