"""Every parameter of the robot planners in one typed config (docs/domain.md §5), with the paper's defaults."""

from __future__ import annotations

from dataclasses import dataclass, replace

from planner.perception import FOV_ANGLE, KB_DELAY


@dataclass(frozen=True, slots=True)
class PlannerConfig:
    """The robot's model of the person, what it values and how far it looks; every field is read by the default
    robot or by a shipped one (``planner.registry``).

    **The person** (every QMDP robot): ``human_angle`` / ``human_delay``, the robot's model of the person's FOV and
    KB delay (the study's; the baseline uses 360° and 0). ``belief_threshold``: person subtasks below it are not
    planned for, at most ``max_subtasks`` of them; ``progress_weight`` and ``belief_floor``: the belief's update
    (:mod:`planner.belief`).

    **The objective** (the reference's shaping rewards, docs/domain.md §5 step 3; :func:`planner.rollout.potential`):
    ``order_left_penalty`` per order left, ``all_done_reward`` when none is, ``steak_on_grill``, ``station_in_use``
    (+ the count) per board and sink in use, ``hold_clean_plate`` / ``hold_steak`` / ``hold_dish`` per clean plate,
    plated steak and dish anywhere. A subtask's value is the discounted sum of the potential's increments over a
    rollout of ``search_depth`` subtasks × 6 ticks (7: 42 ticks; it measured better than the paper's 5 and fits the
    one-tick budget), ``tick_discount`` per tick; ``gamma`` the QMDP discount. ``value_smoothing``: the weight of
    this tick's rollout value against its running average over the previous ticks (1 = no averaging; the average
    restarts when the robot's held object or the orders left change); ``commitment_bonus`` for keeping the current
    subtask.

    **Exploration** (the FOV-aware robots): ``exploration_depth`` (k), the most extra ticks of a first move's walk
    explored for how it changes the person's KB (docs/domain.md §5 step 2; 0 = the no-rollout robot).

    **The person in the way** (every QMDP robot; :mod:`planner.standoff`, :mod:`planner.cycle`, :mod:`planner.alone`):
    ``standoff_ticks`` without progress behind the person before the robot plans around them; ``stall_ticks``
    without team progress before it takes the person's stalled work over (above most quiet stretches of finished
    trials: p90 24 ticks, max 56, docs/changes.md, "Measurement history"); ``visit_ticks`` the person stands in one cell
    before the robot stands beside them once; ``cycle_returns`` returns to one of the last ``cycle_window`` joint
    situations without progress make a joint cycle, after which the robot holds still ``cycle_hold`` ticks;
    ``alone_ticks`` the person does nothing before the robot plans as if alone.

    **The showing robot only** (``fov_aware_showing``, docs/domain.md §5, "The showing robot"): ``shown_value``,
    added once when the modelled person's KB acknowledges what the robot holds now; ``view_detour``, the most extra
    ticks of a hands walk's leg (and of its show plan, less the ``human_delay − 1`` ticks in view); ``dish_detour``
    the same for a whole dish trip; ``walk_price``, the share of a dish trip in view an extra tick must buy;
    ``hands_price``, the expected ticks of the KB being wrong about the robot's hands an extra tick must save;
    ``hands_still``: a person who has stood in one cell ``n`` ticks keeps their pose with weight
    ``n / (n + hands_still)``. Tuned on generated kitchens of generator seeds 0–29 only (docs/changes.md)."""

    human_angle: float = FOV_ANGLE
    human_delay: int = KB_DELAY
    exploration_depth: int = 3
    search_depth: int = 7
    belief_threshold: float = 0.15
    max_subtasks: int = 3
    gamma: float = 0.9
    tick_discount: float = 0.97
    progress_weight: float = 0.7
    belief_floor: float = 0.01
    order_left_penalty: float = -40.0
    all_done_reward: float = 100.0
    steak_on_grill: float = 5.0
    station_in_use: float = 3.0
    hold_clean_plate: float = 12.0
    hold_steak: float = 20.0
    hold_dish: float = 30.0
    commitment_bonus: float = 1.0
    value_smoothing: float = 0.5
    standoff_ticks: int = 5
    stall_ticks: int = 30
    visit_ticks: int = 30
    cycle_returns: int = 8
    cycle_window: int = 16
    cycle_hold: int = 10
    alone_ticks: int = 20
    shown_value: float = 10.0
    view_detour: int = 4
    dish_detour: int = 6
    walk_price: float = 0.05
    hands_price: float = 0.5
    hands_still: float = 2.0

    def omniscient_human(self) -> PlannerConfig:
        return replace(self, human_angle=360.0, human_delay=0)

    @property
    def human_sees_everything(self) -> bool:
        """The modelled person sees every cell and acknowledges it at once (360°, delay 0): their KB is the
        world (docs/domain.md §3)."""
        return self.human_angle >= 360 and self.human_delay == 0


BASELINE = PlannerConfig().omniscient_human()
