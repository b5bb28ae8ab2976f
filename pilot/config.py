"""The simulated participant's parameters: one frozen, typed config, from defaults, a small YAML file or flags.

Defaults and where they come from (docs/pilot.md):

- ``decision_latency_ticks`` (2): ticks between the end of a subtask and the next choice (at 5 Hz, 0.4 s: a
  glance at the kitchen and a key press).
- ``error_rate`` (0.05): the share of choices made at random among the subtasks that fit what the cook holds,
  instead of by the simulated human's rule (paper §IV-A; ``planner.human``).
- ``notice_probability`` (0.35): per tick, the chance of noticing that what is now seen makes the running
  subtask pointless or impossible (its believed targets are gone, or it is no longer available in the KB:
  the grill turned out busy, the plate was taken, the robot brings what it was getting).
- ``stop_weight`` / ``replace_weight`` / ``correct_weight`` (0.3 / 0.4 / 0.3): how a noticed pointless subtask
  is handled: ``stop`` (an interrupt, then a new choice after the latency), replace it with a new choice at
  once, or a one-step correction (``interact`` to put what is held on the counter faced, when one is free;
  else it falls back on stop or replace).
- ``stuck_ticks`` (3) and ``sidestep_probability`` (0.5): when the cook has not moved for ``stuck_ticks``
  ticks with the robot in view next to it, the chance per tick of stepping aside with a move interrupt.
- questionnaire model (``pilot.answers``): ``rating_mean`` (5.0) on a 1..7 scale, minus
  ``rating_gap_slope`` (1.0) per unit of the trial's mean KB gap as the simulated participant measured it,
  plus normal noise of ``rating_sd`` (1.0), rounded and clipped to the item's scale (reversed items mirrored).
- ``quiz_error_rate`` (0.0): the chance of answering a quiz question wrongly (answers otherwise come from
  the study file: a simulated participant has read the instructions).
- ``think_seconds_min`` / ``think_seconds_max`` (0.5 / 3.0): at the ``realtime`` pace only, the wall-clock
  seconds before each choice of a next task, drawn uniformly between the two (a glance at the kitchen, the
  recipe and the buttons, then a click; the range a person reading the screen needs). It replaces
  ``decision_latency_ticks`` there, so the pilot meets each clock as a person would: under ``fixed_rate`` the
  world goes on while it thinks, under ``wait_for_participant`` it waits.
- ``wait_tap_seconds`` (0.3) and ``wait_taps`` (20): ``--realtime`` on the paper's clock only: a task refused
  because its station is still at work (a steak cooking) is waited for with "." (stay) presses this far apart, while
  the faced station works, at most this many (a person tapping the key the page names; 20 covers a steak's 10
  cooking ticks twice), then it chooses again (``pilot.mind``).
- ``script_every_seconds`` (8.0) and ``script_tap_seconds`` (0.2): the gaming scripts' pace (``steakhouse pilot
  --script``; :mod:`pilot.scripts`): a random task every 8 s, a key tapped five times a second.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator


class PilotConfigError(ValueError):
    """A pilot config file or flag that cannot be used; the message names the file, field and reason."""


class ParticipantConfig(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    decision_latency_ticks: int = Field(default=2, ge=0, le=100)
    error_rate: float = Field(default=0.05, ge=0.0, le=1.0)
    notice_probability: float = Field(default=0.35, ge=0.0, le=1.0)
    stop_weight: float = Field(default=0.3, ge=0.0)
    replace_weight: float = Field(default=0.4, ge=0.0)
    correct_weight: float = Field(default=0.3, ge=0.0)
    stuck_ticks: int = Field(default=3, ge=1, le=100)
    sidestep_probability: float = Field(default=0.5, ge=0.0, le=1.0)
    rating_mean: float = Field(default=5.0)
    rating_gap_slope: float = Field(default=1.0)
    rating_sd: float = Field(default=1.0, ge=0.0)
    quiz_error_rate: float = Field(default=0.0, ge=0.0, le=1.0)
    think_seconds_min: float = Field(default=0.5, ge=0.0, le=60.0)
    think_seconds_max: float = Field(default=3.0, ge=0.0, le=60.0)
    wait_tap_seconds: float = Field(default=0.3, gt=0.0, le=10.0)
    wait_taps: int = Field(default=20, ge=0, le=1000)
    script_every_seconds: float = Field(default=8.0, gt=0.0, le=600.0)
    script_tap_seconds: float = Field(default=0.2, gt=0.0, le=60.0)

    @model_validator(mode="after")
    def _think_range(self) -> ParticipantConfig:
        if self.think_seconds_max < self.think_seconds_min:
            raise ValueError("think_seconds_max must be at least think_seconds_min")
        return self

    def reaction_weights(self) -> tuple[float, float, float]:
        """``(stop, replace, correct)`` normalised to sum 1 (all zero: never react)."""
        total = self.stop_weight + self.replace_weight + self.correct_weight
        if total <= 0:
            return (0.0, 0.0, 0.0)
        return (self.stop_weight / total, self.replace_weight / total, self.correct_weight / total)


FIELDS = tuple(ParticipantConfig.model_fields)


def load_config(path: Path | None = None, overrides: dict[str, Any] | None = None) -> ParticipantConfig:
    """Defaults, then the YAML mapping in ``path``, then ``overrides`` (from ``--set name=value``)."""
    values: dict[str, Any] = {}
    source = "defaults"
    if path is not None:
        source = str(path)
        try:
            loaded = yaml.safe_load(path.read_text(encoding="utf-8"))
        except OSError as exc:
            raise PilotConfigError(f"{path}: cannot read ({exc.strerror})") from exc
        except yaml.YAMLError as exc:
            raise PilotConfigError(f"{path}: not valid YAML ({exc})") from exc
        if loaded is not None and not isinstance(loaded, dict):
            raise PilotConfigError(f"{path}: expected a mapping of parameter: value")
        values.update(loaded or {})
    values.update(overrides or {})
    try:
        return ParticipantConfig(**values)
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(str(p) for p in e['loc']) or 'config'}: {e['msg']}" for e in exc.errors())
        raise PilotConfigError(f"{source}: {problems}") from None


def parse_setting(text: str) -> tuple[str, Any]:
    """``name=value`` (value read as YAML: numbers stay numbers) for ``--set``."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip():
        raise PilotConfigError(f"--set {text!r}: expected name=value (names: {', '.join(FIELDS)})")
    if name.strip() not in FIELDS:
        raise PilotConfigError(f"--set {text!r}: unknown parameter {name.strip()!r} (names: {', '.join(FIELDS)})")
    return name.strip(), yaml.safe_load(value)
