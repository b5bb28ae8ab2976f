"""The robot's belief over the human's current subtask (paper §V-A; docs/domain.md §5).

Update, once per tick, from the human's pose, heading, held object and the robot's model of the human's KB:

1. Feasibility: the subtasks available to the human given the *modelled* KB (:func:`planner.subtasks.available`).
   A human holding something has exactly one (its forced continuation), so the belief is certain.
2. Reset: when the human's held object or the modelled KB's status summary changed since last tick (the
   high-level state changed), the prior is uniform over the feasible subtasks.
3. Progress: for each feasible subtask ``s``, ``progress(s) = 1`` if the human's last action moved it
   closer to (or interacted at) one of ``s``'s targets, else 0.
4. ``b'(s) ∝ feasible(s) · [(1 − w) · b(s) + w · progress(s) / Σ progress]`` with ``w`` the progress weight
   (0.7, as the reference), then a floor (0.01) on feasible subtasks and renormalisation, so the belief
   is always a proper distribution over feasible subtasks.
"""

from __future__ import annotations

from dataclasses import dataclass

from planner.geometry import Action
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.paths import UNREACHABLE, Pose, distances_to
from planner.rules import Rules
from planner.state import AgentState
from planner.subtasks import Believed, Subtask, available, targets
from planner.summary import Summary, summarize


@dataclass(frozen=True, slots=True)
class Belief:
    probs: tuple[tuple[Subtask, float], ...]
    held: str | None = None
    summary: Summary | None = None

    def as_dict(self) -> dict[str, float]:
        return {s.value: p for s, p in self.probs}

    def likely(self, threshold: float, limit: int) -> tuple[tuple[Subtask, float], ...]:
        """The subtasks at or above ``threshold`` (at least the most likely one), renormalised."""
        ranked = sorted(self.probs, key=lambda sp: (-sp[1], sp[0].value))
        kept = [sp for sp in ranked if sp[1] >= threshold][:limit] or ranked[:1]
        total = sum(p for _, p in kept)
        return tuple((s, p / total) for s, p in kept)


def uniform(options: tuple[Subtask, ...]) -> tuple[tuple[Subtask, float], ...]:
    return tuple((s, 1.0 / len(options)) for s in options)


def update_belief(belief: Belief | None, layout: Layout, rules: Rules, kb: KnowledgeBase,
                  human_before: AgentState | None, human_now: AgentState, human_action: Action | None,
                  partner_held: str | None, orders_left: int, *, weight: float = 0.7,
                  floor: float = 0.01) -> Belief:
    """The belief after observing one tick (see the module docstring)."""
    believed = Believed(kb=kb, held=human_now.held, partner_held=partner_held, orders_left=orders_left)
    current = None
    if belief is not None and belief.probs:
        current = max(belief.probs, key=lambda sp: sp[1])[0]
    options = available(believed, rules, current)
    summary = summarize(kb, rules)
    if (belief is None or belief.held != human_now.held or belief.summary != summary or len(options) == 1):
        prior = dict(uniform(options))
    else:
        old = dict(belief.probs)
        prior = {s: old.get(s, 0.0) for s in options}
        if sum(prior.values()) <= 0:
            prior = dict(uniform(options))
    progress = {s: _progress(layout, rules, kb, s, human_before, human_now, human_action) for s in options}
    total_progress = sum(progress.values())
    mixed = {}
    for s in options:
        moved = progress[s] / total_progress if total_progress else 1.0 / len(options)
        mixed[s] = (1 - weight) * prior[s] + weight * moved
    floored = {s: max(p, floor) for s, p in mixed.items()}
    norm = sum(floored.values())
    probs = tuple(sorted(((s, p / norm) for s, p in floored.items()), key=lambda sp: sp[0].value))
    return Belief(probs=probs, held=human_now.held, summary=summary)


def _progress(layout: Layout, rules: Rules, kb: KnowledgeBase, subtask: Subtask,
              before: AgentState | None, now: AgentState, action: Action | None) -> float:
    if before is None or action is None:
        return 0.0
    cells = targets(layout, subtask, kb, rules)
    if not cells:
        return 0.0
    pose_before: Pose = (before.pos, before.facing)
    pose_now: Pose = (now.pos, now.facing)
    d_before = min(distances_to(layout, c).get(pose_before, UNREACHABLE) for c in cells)
    d_now = min(distances_to(layout, c).get(pose_now, UNREACHABLE) for c in cells)
    if action is Action.INTERACT:
        return 1.0 if d_before == 0 else 0.0
    return 1.0 if d_now < d_before else 0.0
