"""Request and response bodies of the participant API (Create / Public schemas)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

ParamValue = Annotated[str, StringConstraints(max_length=200)]


class PilotRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    pace: Literal["fast", "realtime"] = "fast"
    """``fast``: each step as soon as the robot decided and the simulated participant answered the last state;
    ``realtime``: the study's tick rate."""


class JoinRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    recruiting: dict[Annotated[str, StringConstraints(max_length=64)], ParamValue] = Field(
        default_factory=dict, max_length=20)
    """The landing URL's query parameters; only the study's ``recruiting.url_parameters`` are kept."""
    test_run: bool = False
    """Ignored: a participant's own request never makes a test run (kept so that a client sending it still joins,
    as a real participant). Test runs come from the admin's signed test links: ``test_link``."""
    test_link: Annotated[str, StringConstraints(max_length=200)] | None = None
    """The code of an experimenter's test-run link (``/?study=<id>#test=<code>``, ``server.admin.test_links``):
    join as a test run (not counted for assignment, excluded from exports, no real completion code)."""
    handoff: Annotated[str, StringConstraints(max_length=40)] | None = None
    """The hand-off code a device-refused session's first device shows (``server.flow.handoff``): continue that
    session in this browser."""
    pilot: PilotRequest | None = None
    """Join as a simulated pilot participant (``steakhouse pilot``); only with the admin token as the bearer."""


class JoinResponse(BaseModel):
    """What the participant's browser learns on joining: never the condition order (the participant is blind
    to their conditions, ``docs/protocol.md`` §1); experimenters see it in the admin."""

    token: str
    """Send as ``Authorization: Bearer <token>`` (or ``?token=`` on the websocket). Shown once."""
    participant_id: str
    study_id: str
    state: str
    rejoined: bool


class ResumeRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    code: Annotated[str, StringConstraints(max_length=200)]
    """The code from the resume link's fragment (``#resume=<code>``)."""


class ConsentRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    accept: bool


class QuestionnaireRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    questionnaire_id: Annotated[str, StringConstraints(max_length=64)]
    answers: dict[Annotated[str, StringConstraints(max_length=64)], Any] = Field(max_length=100)
    """Item id → a rating (integer on the item's scale), a choice (the option's 0-based index) or a text
    (``null`` or absent for an unanswered optional item)."""


class QuizRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")

    answers: dict[Annotated[str, StringConstraints(max_length=64)], Any] = Field(max_length=100)
    """Question id → the chosen option's 0-based index."""


class StudyPublic(BaseModel):
    """The public facts of a study: no title (it may name the conditions), only what the landing page needs."""

    id: str
    url_parameters: list[str]
