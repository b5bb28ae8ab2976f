"""Every parameter of the robot planners in one typed config (docs/domain.md §5), with the paper's defaults."""

from __future__ import annotations

from dataclasses import dataclass, replace

from planner.perception import FOV_ANGLE, KB_DELAY

LOOKAHEADS = ("rollout", "abstract")


@dataclass(frozen=True, slots=True)
class PlannerConfig:
    """``human_angle``/``human_delay``: the robot's model of the person's FOV and KB delay (the baseline
    uses 360° and 0). ``exploration_depth`` (k): ticks of robot motion explored for how they change the
    human's KB; 0 = the no-rollout robot. ``search_depth`` (n): subtasks looked ahead per agent
    (× 6 ticks of rollout; 7 measured better than the paper's 5 and fits the one-tick budget).
    ``belief_threshold``: human subtasks below it are not planned for. ``gamma``: the QMDP discount;
    ``tick_discount``: the per-tick discount of progress inside a lookahead (paper: 0.8 per abstract depth).
    ``rollout_samples``: simulated futures averaged per hypothesis (the human's choices are random).
    ``value_smoothing``: weight of this tick's rollout value of a robot subtask against its running average
    over the previous ticks (1 = no averaging); the average restarts when the robot's held object or the
    orders left change. Averaging over ticks lowers the noise of one-sample rollouts at no extra cost.
    ``lookahead``: ``"rollout"`` (default): each robot subtask is valued by simulating the joint system
    tick by tick for ``search_depth`` × 6 ticks with the human model. ``"abstract"``: docs/domain.md §5 as the
    reference did it (:mod:`planner.reference`): Q per low-level action from ``exploration_samples``
    motion sequences of depth ``exploration_depth`` and a heuristic search over abstract states
    (:mod:`planner.abstract`) ``abstract_depth`` transitions deep, discounted ``abstract_discount`` per
    transition. Rewards are the reference implementation's shaping (docs/domain.md §5, step 4).
    ``standoff_ticks``: ticks without progress while the person blocks the robot's target before the robot
    re-plans around them (:mod:`planner.standoff`). ``stall_ticks``: ticks without team progress (the shaping
    potential unchanged) before the robot takes the person's stalled work over (:mod:`planner.standoff`, team
    stalls); above most quiet stretches of finished trials (a trial's longest: p90 24 ticks, max 56, on the
    shipped and generator-seed 0–9 kitchens; docs/domain.md §5, "Standoffs"). ``visit_ticks``: ticks the
    person stands in one cell before the robot goes to stand beside it for ``standoff_ticks`` ticks, once
    until the person moves (:mod:`planner.standoff`, still person). ``cycle_returns``, ``cycle_window``,
    ``cycle_hold``: returns to one of the last ``cycle_window`` joint situations without team progress that
    make a joint cycle, and the ticks the robot then holds still after stepping aside (:mod:`planner.cycle`).
    ``alone_ticks``: ticks the person has not moved, turned or interacted before the robot plans as if it were
    alone (:mod:`planner.alone`). ``reuse_rollouts``: keep a
    rollout whose first tick came true for the next tick's decision (:mod:`planner.reuse`; only with
    ``rollout_samples`` 1).
    ``rollout_budget``: simulated ticks one decision may spend on new rollouts (0: no limit; 336 is eight
    rollouts of the full 42 ticks). A decision that would need more (the person just chose anew, so three
    hypotheses × every robot option × the exploration's candidates) shortens the lookahead of all its
    rollouts alike, to ``budget / rollouts`` ticks but never below one subtask (6 ticks). Both are off by
    default: they cut the decision time but also the FOV-aware robot's effect (docs/domain.md §5).
    The person's knowing (docs/domain.md §5; only the FOV-aware robot's exploration, whose candidate first moves
    are valued with it): ``shown_value`` once, when the modelled person's KB acknowledges what the robot holds
    now while it still holds it; ``shown_empty`` the same for empty hands (a put-down the person did not see;
    also, with nothing to do, the robot then walks into view; off by default: it cost ticks for little less KB
    gap); ``wrong_hands`` (off by default: it cost ticks) is lost per tick the modelled KB is wrong about
    what the robot holds (stale or unknown), in the exploration only. ``view_detour``: the most extra ticks of a
    hands walk's leg, and of a showing walk less its ``human_delay − 1`` ticks in view (at most ``view_detour +
    human_delay − 1``); ``dish_detour`` the same for a whole dish trip (6: at 4, behaviour 2 was 3.7 points lower
    on the tuning kitchens, docs/domain.md §5). ``walk_price``: behaviour 2's dish walk (:mod:`planner.dish_walk`)
    takes an extra tick only for at least this much more of the dish trip's share in the person's view (0.05: five
    points; at 0.02 the team was 1.4 points of ticks slower on the tuning kitchens, docs/domain.md §5). Tuned
    on generated kitchens of generator seeds 0–29 only. (With ``reuse_rollouts`` the kept rollouts carry no
    knowing value, so the direct move is scored without it: not measured.)
    ``hands_walk``: while the modelled KB is wrong about what the robot holds, the robot walks to its station by
    the hands walk (:mod:`planner.hands_walk`), planned on the person's predicted views, instead of the show plan
    scored by the rollouts; an extra tick must save at least ``hands_price`` expected ticks of that KB being
    wrong. Beside the predicted poses, a person who has stood in one cell ``n`` ticks keeps their pose with weight
    ``n / (n + hands_still)``: the robot's model of what they do next can be wrong, and standing is telling.
    ``walk_rollout`` (off by default): a hands walk that turns off the direct way is taken only when its rollouts
    (the walk as their prefix: the team's progress and what the person comes to know) score higher than the direct
    move's, as every other candidate of the exploration is (:meth:`planner.qmdp.QmdpRobot.walk_or_direct`). On the
    tuning kitchens it made the team 1.5 % faster but gave back 1.3 points of the robot gap's fall (docs/domain.md
    §5), the issue's target, while the team was already no slower there: so off; on the shipped kitchens it cut the
    FOV-aware team's extra ticks from +5.0 % to +2.1 % (docs/domain.md §6)."""

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
    rollout_samples: int = 1
    value_smoothing: float = 0.5
    lookahead: str = "rollout"
    abstract_depth: int = 5
    exploration_samples: int = 16
    abstract_discount: float = 0.8
    standoff_ticks: int = 5
    stall_ticks: int = 30
    visit_ticks: int = 30
    cycle_returns: int = 8
    cycle_window: int = 16
    cycle_hold: int = 10
    alone_ticks: int = 20
    reuse_rollouts: bool = False
    rollout_budget: int = 0
    shown_value: float = 10.0
    shown_empty: float = 0.0
    view_detour: int = 4
    dish_detour: int = 6
    wrong_hands: float = 0.0
    walk_price: float = 0.05
    hands_walk: bool = True
    hands_price: float = 0.5
    hands_still: float = 2.0
    walk_rollout: bool = False

    def __post_init__(self) -> None:
        if self.lookahead not in LOOKAHEADS:
            raise ValueError(f"lookahead must be one of {', '.join(LOOKAHEADS)}, got {self.lookahead!r}")

    @property
    def values_knowing(self) -> bool:
        """The exploration values the person's knowing (:meth:`planner.rollout.Rollout.knowing`)."""
        return bool(self.shown_value or self.shown_empty or self.wrong_hands)

    def omniscient_human(self) -> PlannerConfig:
        return replace(self, human_angle=360.0, human_delay=0)

    @property
    def human_sees_everything(self) -> bool:
        """The modelled person sees every cell and acknowledges it at once (360°, delay 0): their KB is the
        world (docs/domain.md §3)."""
        return self.human_angle >= 360 and self.human_delay == 0


BASELINE = PlannerConfig().omniscient_human()
