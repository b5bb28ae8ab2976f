"""The kitchen's numbers (docs/domain.md §1). Defaults are those every run of the reference study used."""

from __future__ import annotations

from dataclasses import asdict, dataclass


@dataclass(frozen=True, slots=True)
class Rules:
    """Cook time in ticks, chop and wash presses, orders per trial, horizon in ticks, reward per delivery."""

    cook_time: int = 10
    chop_time: int = 2
    wash_time: int = 2
    orders: int = 2
    horizon: int = 400
    delivery_reward: int = 20

    def __post_init__(self) -> None:
        for name in ("cook_time", "chop_time", "wash_time", "orders", "horizon"):
            if getattr(self, name) < 1:
                raise ValueError(f"{name} must be at least 1, got {getattr(self, name)}")

    def chopped(self, board: int | None) -> bool:
        """A board's status (``None``: empty, else its chop count) holds a chopped garnish."""
        return board is not None and board >= self.chop_time

    def chopping(self, board: int | None) -> bool:
        """A board holds an onion not yet chopped."""
        return board is not None and board < self.chop_time

    def clean(self, sink: int | None) -> bool:
        """A sink's status (``None``: empty, else its wash count) holds a clean plate."""
        return sink is not None and sink >= self.wash_time

    def washing(self, sink: int | None) -> bool:
        """A sink holds a plate not yet clean."""
        return sink is not None and sink < self.wash_time

    def to_dict(self) -> dict[str, int]:
        return asdict(self)
