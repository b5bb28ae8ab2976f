"""Server → client messages (protocol v1). Every message carries ``v`` and a per-connection ``seq``
(1, 2, 3, … in sending order).

``state`` is the only per-tick message and holds **only what is in the participant's field of view** at that
tick: the visible cells (terrain, the object on a visible counter, the status of a visible station) and the
robot if its cell is visible. Cells out of view are simply absent; ``hello`` gives the kitchen's size but no
terrain. A client may remember terrain it has seen; the server never sends what is not in view now.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

from planner.vocabulary import StationState as StationState
from planner.vocabulary import TerrainName as TerrainName
from study_config.study.views import ViewName

BlockedReason = Literal[
    "hands_full", "hands_empty", "needs_item", "nothing_there", "counter_empty", "grill_busy", "steak_cooking",
    "board_busy", "nothing_to_chop", "no_garnish", "not_chopped", "already_chopped", "sink_busy", "nothing_to_wash",
    "already_washed", "no_clean_plate", "robot_in_way", "no_way", "unknown_place", "stuck", "no_steak",
    "taken_by_robot", "filled_by_robot", "done_by_robot"]
"""Why a subtask is not getting anywhere (``blocked`` messages; docs/protocol.md lists each with its words)."""


class ServerMessage(BaseModel):
    model_config = ConfigDict(extra="forbid")

    v: Literal[1] = 1
    seq: int = 0


class TrialInfo(BaseModel):
    id: int
    kind: Literal["practice", "main"]
    index: int
    """Index within its kind (practice 0, 1, …; main 0, 1, …)."""
    number: int
    """1-based position among all trials of the participant (practice and main together)."""
    total: int
    """All trials of the participant (practice and main together)."""
    kind_number: int
    """1-based position among the trials of its kind ("Practice 1 of 1", "Round 2 of 4")."""
    kind_total: int
    """Trials of its kind."""
    scored: bool
    """Whether the round's score counts (practice rounds are not scored: no score is shown)."""


class Bounds(BaseModel):
    """The part of the grid worth drawing: every floor cell and station plus one ring of cells around them
    (the kitchen's extent, the same for every trial in it; nothing about what is on a cell)."""

    left: int
    top: int
    width: int
    height: int


class Hello(ServerMessage):
    """First message of every connection: the trial and the fixed facts the client needs to draw it."""

    type: Literal["hello"] = "hello"
    protocol: int = 1
    trial: TrialInfo
    width: int
    height: int
    subtasks: list[str]
    interrupts: list[str]
    mode: Literal["fixed_rate", "wait_for_participant"]
    tick_rate_hz: float
    fov_angle: float
    horizon: int
    orders: int
    tick: int
    resumed: bool
    max_message_bytes: int
    bounds: Bounds
    """Draw only these cells, scaled to the space (the rest of the grid is counters nobody can reach)."""
    needs: dict[str, str]
    """Subtask → what must be in hand for it: ``nothing``, ``something`` or an object name (the task buttons
    are disabled from this and what the cook holds)."""
    view: ViewName
    """How to draw the kitchen: from above, or through the cook's eyes (camera field of view ``fov_angle``).
    The only fact about the trial's condition a participant may be told: they see it anyway."""


class StationView(BaseModel):
    state: StationState
    progress: int
    """Cook ticks, chop or wash presses so far."""
    total: int
    """Needed for ready / chopped / clean."""


class CellView(BaseModel):
    x: int
    y: int
    terrain: TerrainName
    object: str | None = None
    station: StationView | None = None


class AgentView(BaseModel):
    x: int
    y: int
    facing: Literal["north", "south", "east", "west"]
    held: str | None


class Hud(BaseModel):
    tick: int
    horizon: int
    ticks_left: int
    seconds_left: float | None
    """``ticks_left`` at the tick rate; ``None`` in wait-for-participant mode."""
    orders_left: int
    score: int
    round_seconds_left: float | None = None
    """Wait-for-participant mode: wall-clock seconds left before the round's ``timing.max_round_seconds`` (counted
    while connected); ``None`` in ``fixed_rate``."""


class State(ServerMessage):
    type: Literal["state"] = "state"
    tick: int
    you: AgentView
    robot: AgentView | None
    cells: list[CellView]
    hud: Hud
    subtask: str | None
    available: list[str]
    queued: int
    ack: int
    """The highest client ``seq`` accepted so far on this connection (0 if none)."""


class Ack(ServerMessage):
    """The reply to an accepted ``select_subtask``, ``interrupt``, ``focus``, ``blur`` or ``idle``."""

    type: Literal["ack"] = "ack"
    ack: int
    subtask: str | None
    queued: int


class Blocked(ServerMessage):
    """The current subtask is not getting anywhere, and why (judged from what the participant holds and the cell
    the cook faces, which is always in view). ``ended``: the subtask ended itself (or was refused when chosen);
    otherwise it goes on and this is a notice ("The steak is still cooking")."""

    type: Literal["blocked"] = "blocked"
    subtask: str | None
    """``null``: an ``interact`` key (an interrupt) that did nothing, for the reason given."""
    reason: BlockedReason
    item: str | None = None
    """The object the reason names: what is needed (``needs_item``), what is in hand (``hands_full``), or what the
    robot took, put or worked on (``taken_by_robot``, ``filled_by_robot``, ``done_by_robot``)."""
    place: str | None = None
    """Where the robot did it (``grill``, ``board``, ``sink``, ``counter``) for the ``…_by_robot`` reasons."""
    ended: bool


StallHintCode = Literal["standing_at_station", "onion_needs_chopping", "plate_needs_washing", "holding",
                        "look_around"]
"""Which hint a ``stall_hint`` gives (``server.game.stall_hint``)."""


class StallHint(ServerMessage):
    """The team has not got anything done for ``timing.stall_hint_seconds``: a hint phrased from what the
    participant knows (where they stand, what they hold, what they have seen); never the robot's planner or the
    condition."""

    type: Literal["stall_hint"] = "stall_hint"
    code: StallHintCode
    text: str


class Pong(ServerMessage):
    type: Literal["pong"] = "pong"
    ack: int
    client_time: float
    server_time: float
    """Server clock, ms since the Unix epoch."""


ErrorCode = Literal["bad_frame", "too_large", "bad_json", "invalid_message", "unknown_type",
                    "unsupported_version", "bad_seq", "queue_full", "not_playing", "replaced", "no_trial",
                    "unauthorized", "internal", "server_full", "moved", "rate_limited",
                    "device_refused"]


class Error(ServerMessage):
    """A rejected message (nothing changed) or a connection-level problem."""

    type: Literal["error"] = "error"
    code: ErrorCode
    message: str
    ref: int | None = None
    """The ``seq`` of the rejected message when it could be read."""


class Waiting(ServerMessage):
    """The server runs as many rounds as it can hold on time; this participant's round starts when a slot is
    free (sent before ``hello``, again whenever the line moves, and every 2 s). Nothing about the round."""

    type: Literal["waiting"] = "waiting"
    position: int
    """1 for the next to start."""
    eta_s: int
    """Expected wait in seconds (rounded up to 5 s)."""


class Nudge(ServerMessage):
    """The cook has had nothing to do for the study's ``timing.idle_nudge_seconds``: the page shows "Choose your
    next task" until the participant acts. Sent again every ``idle_nudge_seconds`` of the idle stretch (``repeat``
    counts them); it names nothing of the condition."""

    type: Literal["nudge"] = "nudge"
    text: Literal["Choose your next task"] = "Choose your next task"
    repeat: int = 1


class Countdown(ServerMessage):
    """Wait-for-participant mode: the last minute of the round's wall-clock limit has begun (or had, when the page
    reconnects): the page counts ``seconds_left`` down where the participant sees it."""

    type: Literal["countdown"] = "countdown"
    seconds_left: float


WarningRule = Literal["no_actions", "idle", "task_steps", "refused_tasks"]
"""Which engagement rule the round so far fails (``server.flow.engagement``)."""


class EngagementWarning(ServerMessage):
    """If the round ended now it would not count (``low_engagement``): told while the participant can still act,
    from the second nudge of an idle stretch on and when the countdown starts. ``rule`` names why (the page words
    it); ``seconds_left``: before the wall-clock limit (``None`` in ``fixed_rate``)."""

    type: Literal["warning"] = "warning"
    code: Literal["would_not_count"] = "would_not_count"
    rule: WarningRule
    seconds_left: float | None = None


class TrialEnd(ServerMessage):
    """The trial is over; the server closes the connection after this. ``next`` is the participant's state
    now (``GET /api/session`` tells what to show). ``reason``: ``delivered``, ``horizon``, ``time_limit`` (a
    ``wait_for_participant`` round reached ``timing.max_round_seconds``) or, when abandoned, ``grace_expired``."""

    type: Literal["trial_end"] = "trial_end"
    status: Literal["finished", "abandoned"]
    reason: str
    ticks: int
    delivered: int
    score: int
    next: str


AnyServerMessage = Annotated[Hello | State | Ack | Blocked | StallHint | Pong | Error | Waiting | Nudge | Countdown
                             | EngagementWarning | TrialEnd, Field(discriminator="type")]
server_adapter: TypeAdapter[AnyServerMessage] = TypeAdapter(AnyServerMessage)
