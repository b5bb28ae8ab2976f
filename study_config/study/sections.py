"""The smaller sections of a study: world numbers, timing, practice, recruiting, reconnects, assignment."""

from __future__ import annotations

import re
from typing import Literal

from pydantic import Field, field_validator, model_validator

from planner.perception import FOV_ANGLE, KB_DELAY
from planner.rules import Rules
from study_config.study.base import Loc, RobotName, StudyModel, duplicate_problems, raise_problems
from study_config.study.kitchens import KitchenEntry
from study_config.study.views import ViewName

CODE_PLACEHOLDER = "{code}"
_URL_PARAMETER = re.compile(r"^[A-Za-z0-9_.-]+$")
_RULES = Rules()


class World(StudyModel):
    """The game's numbers (docs/domain.md §1–§3); the defaults are the paper's, read from their one home in
    ``planner`` (:mod:`planner.perception`, :class:`planner.rules.Rules`)."""

    fov_angle: float = Field(default=FOV_ANGLE, gt=0, le=360)
    """Field-of-view angle in degrees; cells outside it are black for the participant. 360 sees all."""
    kb_delay: int = Field(default=KB_DELAY, ge=0)
    """Consecutive ticks something must stay in view before it enters the human's knowledge base."""
    orders: int = Field(default=_RULES.orders, ge=1)
    """Dishes to deliver; a trial ends when all are delivered (or at the horizon)."""
    horizon: int = Field(default=_RULES.horizon, ge=1)
    """Maximum ticks per trial."""
    cook_time: int = Field(default=_RULES.cook_time, ge=1)
    """Ticks a steak needs on the grill."""
    chop_time: int = Field(default=_RULES.chop_time, ge=1)
    """Interact presses to chop an onion."""
    wash_time: int = Field(default=_RULES.wash_time, ge=1)
    """Interact presses to wash a plate."""
    delivery_reward: int = Field(default=_RULES.delivery_reward, ge=0)
    """Score for each delivered dish."""


class Timing(StudyModel):
    """How the world's clock advances during a trial."""

    mode: Literal["fixed_rate", "wait_for_participant"] = "fixed_rate"
    """``fixed_rate``: the world steps every tick whatever the participant does (the reference app);
    ``wait_for_participant``: a step happens only when the participant has an action queued
    (the reference study), and never faster than ``tick_rate_hz``."""
    tick_rate_hz: float = Field(default=5.0, gt=0, le=30)
    """World steps per second (5 Hz = one tick every 200 ms)."""
    blocked_subtask_seconds: float = Field(default=3.0, gt=0, le=600)
    """A subtask that makes no progress this long ends itself and says why (docs/client.md)."""
    max_round_seconds: float | None = Field(default=None, gt=0, le=86_400)
    """``wait_for_participant`` only: the wall-clock limit of a round (seconds while the participant is
    connected); past it the round ends with reason ``time_limit``. Default: the horizon at the tick rate × 3
    (:data:`ROUND_LIMIT_FACTOR`), so a person who reads as they play never meets it (docs/protocol.md §3)."""
    idle_nudge_seconds: float = Field(default=10.0, gt=0, le=3_600)
    """Seconds the cook may stand with nothing to do (no task, no key waiting) before the page shows
    "Choose your next task" (a nudge naming nothing of the condition)."""

    stall_hint_seconds: float = Field(default=8.0, gt=0, le=600)
    """The team's potential unchanged this long gives the participant a hint (docs/client.md, "Stall hints")."""

    def blocked_ticks(self) -> int:
        """``blocked_subtask_seconds`` in ticks at the tick rate (at least one)."""
        return max(1, round(self.blocked_subtask_seconds * self.tick_rate_hz))

    def round_seconds(self, horizon: int) -> float:
        """The longest a round lasts on the wall clock (while connected): the horizon at the tick rate
        (``fixed_rate``), or the wall-clock limit (``wait_for_participant``)."""
        played = horizon / self.tick_rate_hz
        if self.mode == "fixed_rate":
            return played
        return self.max_round_seconds if self.max_round_seconds is not None else played * ROUND_LIMIT_FACTOR

    def round_limit_seconds(self, horizon: int) -> float | None:
        """The wall-clock limit the server enforces (``None`` in ``fixed_rate``: the horizon ends a round)."""
        return self.round_seconds(horizon) if self.mode == "wait_for_participant" else None

    def stall_hint_ticks(self) -> int:
        """``stall_hint_seconds`` in ticks at the tick rate (at least one)."""
        return max(1, round(self.stall_hint_seconds * self.tick_rate_hz))

    @model_validator(mode="after")
    def _limit_needs_waiting(self) -> Timing:
        if self.mode == "fixed_rate" and self.max_round_seconds is not None:
            raise_problems([(("max_round_seconds",), "only a wait_for_participant round has a wall-clock "
                                                     "limit; a fixed_rate round ends at the horizon")], self)
        return self


ROUND_LIMIT_FACTOR = 3.0
"""The default wall-clock limit of a ``wait_for_participant`` round: this many times the horizon at the tick
rate (a reader's pace: the paper's participants took their time between choices)."""


class Counterbalancing(StudyModel):
    """How condition orders are formed (see ``study_config.study.counterbalance``).

    Written either as a bare scheme (``counterbalancing: latin_square``) or as a mapping
    (``{scheme: fixed, order: [...]}``).
    """

    scheme: Literal["latin_square", "full", "fixed"] = "latin_square"
    """``latin_square``: balanced Latin square (Williams design); ``full``: every permutation;
    ``fixed``: everyone gets ``order``."""
    order: tuple[str, ...] | None = None
    """For ``fixed`` only: every condition id exactly once (``fov_aware@none_3``, ...)."""

    @model_validator(mode="before")
    @classmethod
    def _from_scheme_name(cls, value: object) -> object:
        return {"scheme": value} if isinstance(value, str) else value

    @model_validator(mode="after")
    def _order_matches_scheme(self) -> Counterbalancing:
        if self.scheme == "fixed" and self.order is None:
            raise_problems([(("order",), "scheme 'fixed' needs an order listing every condition id")], self)
        if self.scheme != "fixed" and self.order is not None:
            reason = f"an order is only used with scheme 'fixed', not {self.scheme!r}"
            raise_problems([(("order",), reason)], self)
        return self


class Practice(StudyModel):
    """Practice trials played before the experimental conditions; never analysed."""

    kitchen: KitchenEntry
    """Shipped kitchen name or layout path (need not be one of the study's kitchens)."""
    robot: RobotName
    """Robot partner for practice, e.g. ``stay`` (a robot that does not move)."""
    count: int = Field(default=1, ge=1)
    """How many practice trials of this kind."""
    view: ViewName | None = None
    """How the participant sees this practice round; default: their group's view when ``view`` is between
    participants, else the study's first view (``views[0]``)."""


class Recruiting(StudyModel):
    """Recruiting-platform settings (e.g. Prolific): parameters to capture and where participants end."""

    completion_code: str | None = None
    """Code shown on the end page to participants who finished (quote it in YAML if it is all digits)."""
    completion_redirect_url: str | None = None
    """Where finished participants are sent; ``{code}`` is replaced by ``completion_code``."""
    screen_out_code: str | None = None
    """Code for participants who end early (declined consent, too many abandoned trials)."""
    screen_out_redirect_url: str | None = None
    """Where screened-out participants are sent; ``{code}`` is replaced by ``screen_out_code``."""
    url_parameters: tuple[str, ...] = ("PROLIFIC_PID", "STUDY_ID", "SESSION_ID")
    """Query parameters of the landing URL stored with the participant; the first identifies them."""
    require_id: bool = False
    """Refuse a join whose link lacks the first URL parameter (a participant who typed the address by hand, or
    came back without their id, could otherwise start again as someone new); test runs may join without it."""

    @field_validator("completion_redirect_url", "screen_out_redirect_url")
    @classmethod
    def _check_redirect(cls, url: str | None) -> str | None:
        if url is None:
            return url
        if not re.match(r"^https?://\S+$", url):
            raise ValueError("must be an http:// or https:// address without spaces")
        if "{" in url.replace(CODE_PLACEHOLDER, "") or "}" in url.replace(CODE_PLACEHOLDER, ""):
            raise ValueError(f"the only placeholder allowed is {CODE_PLACEHOLDER}")
        return url

    @field_validator("url_parameters")
    @classmethod
    def _check_parameters(cls, names: tuple[str, ...]) -> tuple[str, ...]:
        problems: list[tuple[Loc, str]] = [
            ((index,), f"{name!r} is not a URL parameter name (letters, digits, '_', '.', '-')")
            for index, name in enumerate(names)
            if not _URL_PARAMETER.match(name)
        ]
        raise_problems(problems + duplicate_problems(names, "parameter"), names)
        return names

    @model_validator(mode="after")
    def _codes_for_placeholders(self) -> Recruiting:
        problems: list[tuple[Loc, str]] = []
        if self.require_id and not self.url_parameters:
            problems.append((("require_id",), "needs a URL parameter to require: url_parameters is empty"))
        for kind in ("completion", "screen_out"):
            url = getattr(self, f"{kind}_redirect_url")
            if url and CODE_PLACEHOLDER in url and getattr(self, f"{kind}_code") is None:
                reason = f"{kind}_redirect_url uses {CODE_PLACEHOLDER} but no code is set"
                problems.append(((f"{kind}_code",), reason))
        raise_problems(problems, self)
        return self

    def redirect(self, kind: Literal["completion", "screen_out"]) -> str | None:
        """The redirect URL for ``kind`` with ``{code}`` filled in (plain replacement, no formatting)."""
        url: str | None = getattr(self, f"{kind}_redirect_url")
        code: str = getattr(self, f"{kind}_code") or ""
        return None if url is None else url.replace(CODE_PLACEHOLDER, code)


class Reconnect(StudyModel):
    """What happens when a participant's connection drops during a trial."""

    grace_seconds: float = Field(default=60.0, ge=0)
    """Within this many seconds the participant's token resumes the same trial, nothing lost."""
    after_grace: Literal["resume", "restart", "abandon"] = "abandon"
    """When they return later: ``resume`` the trial where it stopped, ``restart`` it from its first tick,
    or ``abandon`` it (marked abandoned) and continue with the next trial."""


class Assignment(StudyModel):
    """How a new participant gets a condition order: the least-filled order wins."""

    in_progress_window_minutes: float = Field(default=30.0, gt=0)
    """Participants who started within this many minutes and have not finished count toward their order."""
