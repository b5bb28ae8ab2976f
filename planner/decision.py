"""What a robot planner answers each tick: the action and a record of how it chose (for logs and the admin view).

Every robot policy (:mod:`planner.robots`) offers ``reset(world)``, ``decide(world, events, rng, deadline)``
returning a :class:`Decision`, and ``act(world, events, rng)`` returning just the action. ``deadline`` is an
absolute ``time.perf_counter()`` value: past it the planner returns its best action so far and sets
``timed_out``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from planner.geometry import Action


@dataclass(frozen=True, slots=True)
class Decision:
    action: Action
    q_values: dict[str, float] = field(default_factory=dict)
    belief: dict[str, float] = field(default_factory=dict)
    explored_kbs: int = 0
    elapsed_ms: float = 0.0
    timed_out: bool = False

    def to_dict(self) -> dict[str, object]:
        return {
            "action": self.action.value,
            "q_values": {k: round(v, 3) for k, v in self.q_values.items()},
            "belief": {k: round(v, 4) for k, v in self.belief.items()},
            "explored_kbs": self.explored_kbs,
            "elapsed_ms": round(self.elapsed_ms, 3),
            "timed_out": self.timed_out,
        }
