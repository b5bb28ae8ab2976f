"""The device check on landing: the game needs a screen large enough for the kitchen and the task buttons,
and a keyboard for the interrupt keys (docs/client.md). A smaller screen or a touch-only device gets a clear
message to use a computer with a keyboard; what the browser reported is stored with the participant."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from study_config.study.base import StudyModel

DeviceProblem = Literal["small_screen", "touch_only"]


class DeviceRequirements(StudyModel):
    """The smallest device a participant may take part on."""

    min_width: int = Field(default=1024, ge=0)
    """Smallest screen width in CSS pixels (default 1024)."""
    min_height: int = Field(default=600, ge=0)
    """Smallest screen height in CSS pixels (default 600)."""
    allow_touch_only: bool = False
    """Let devices without a mouse or trackpad (phones, tablets) take part (default false)."""


class DeviceInfo(BaseModel):
    """What the participant's browser reports about its device (``POST /api/session/device``)."""

    model_config = ConfigDict(extra="forbid")

    screen_width: int = Field(ge=0, le=100_000)
    """``screen.width`` in CSS pixels."""
    screen_height: int = Field(ge=0, le=100_000)
    """``screen.height`` in CSS pixels."""
    viewport_width: int = Field(ge=0, le=100_000)
    """The window's inner width in CSS pixels."""
    viewport_height: int = Field(ge=0, le=100_000)
    """The window's inner height in CSS pixels."""
    pixel_ratio: float = Field(ge=0, le=100, allow_inf_nan=False)
    """``devicePixelRatio``."""
    fine_pointer: bool
    """A mouse or trackpad is present (``any-pointer: fine``)."""
    touch: bool
    """A touch screen is present (``maxTouchPoints > 0``)."""


def refused(report: dict[str, Any] | None) -> bool:
    """Whether a participant's stored device report (``ParticipantRow.device``) refused their device."""
    return bool(report and report.get("problems"))


def device_problems(required: DeviceRequirements, info: DeviceInfo) -> list[DeviceProblem]:
    """What stops ``info``'s device from taking part: a screen below the minimum (either orientation of the
    screen counts, so a rotated monitor passes), or no fine pointer at all."""
    problems: list[DeviceProblem] = []
    long_side, short_side = max(info.screen_width, info.screen_height), min(info.screen_width, info.screen_height)
    if long_side < max(required.min_width, required.min_height) or short_side < min(required.min_width,
                                                                                     required.min_height):
        problems.append("small_screen")
    if not info.fine_pointer and not required.allow_touch_only:
        problems.append("touch_only")
    return problems
