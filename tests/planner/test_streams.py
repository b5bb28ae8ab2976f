"""A trial's random streams (``planner.streams``): each draw is a function of the seed and the tick alone, so a
trial resumed at tick t draws what it would have drawn, and the avatar's draws never shift the robot's."""

from __future__ import annotations

from planner.streams import avatar_rng, robot_rng


def draws(rng_at, seed: int, tick: int) -> list[float]:
    return list(rng_at(seed, tick).random(5))


def test_a_resumed_trial_draws_what_it_would_have_drawn() -> None:
    straight_through = [draws(robot_rng, 123, tick) for tick in range(10)]
    resumed = [draws(robot_rng, 123, tick) for tick in range(5, 10)]
    assert resumed == straight_through[5:]


def test_the_avatars_draws_do_not_shift_the_robots() -> None:
    alone = draws(robot_rng, 7, 3)
    avatar = avatar_rng(7, 3)
    avatar.random(100)  # the avatar breaks many ties at this tick
    assert draws(robot_rng, 7, 3) == alone
    assert draws(avatar_rng, 7, 3) != alone, "two streams, not one"


def test_each_tick_and_each_seed_has_its_own_draws() -> None:
    assert draws(avatar_rng, 7, 3) != draws(avatar_rng, 7, 4)
    assert draws(avatar_rng, 7, 3) != draws(avatar_rng, 8, 3)
    assert draws(avatar_rng, 2**61 + 5, 3) == draws(avatar_rng, 2**61 + 5, 3), "62-bit seeds"
