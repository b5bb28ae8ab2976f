"""The studies this server runs, loaded and validated once at start-up (an invalid one stops the server).

For each study: the validated :class:`~study_config.study.Study`, its condition orders, the kitchens' layouts
(parsed by ``planner``) and the world's :class:`~planner.rules.Rules`. Immutable after start-up.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from planner.layout import Layout
from planner.robot_api import Person
from planner.robot_catalog import RobotSetup
from planner.rules import Rules
from study_config import load_layout
from study_config.study import Study, load_study


@dataclass(frozen=True)
class LoadedStudy:
    study: Study
    orders: tuple[tuple[str, ...], ...]
    layouts: dict[str, Layout]
    rules: Rules
    source: Path

    @property
    def id(self) -> str:
        return self.study.id

    def layout(self, kitchen: str) -> Layout:
        return self.layouts[kitchen]

    @cached_property
    def order_groups(self) -> tuple[int, ...]:
        """The between-participants group of each of ``orders`` (``study_config/study/groups.py``); computed once,
        like ``orders`` (read at every assignment; the study is immutable after start-up)."""
        return tuple(self.study.order_groups())

    def robot_setup(self, robot: str, angle: float) -> RobotSetup:
        """What the robot called ``robot`` is built with in a trial of this study: the person the trial shows, its
        FOV ``angle`` and the study's KB delay (docs/domain.md §5), and its variant's settings
        (``study_config/study/robots.py``); the kitchen's numbers reach the robot as :attr:`rules`."""
        return RobotSetup(Person(fov_angle=angle, kb_delay=self.study.world.kb_delay),
                          tuple(self.study.robot_settings(robot).items()))

    def planner(self, robot: str) -> str:
        """The installed robot (``planner.robot_catalog``) that plays the robot called ``robot``."""
        return self.study.planner(robot)


class DuplicateStudyError(ValueError):
    pass


@dataclass(frozen=True)
class Catalog:
    studies: dict[str, LoadedStudy]

    def get(self, study_id: str) -> LoadedStudy | None:
        return self.studies.get(study_id)

    def __iter__(self) -> Iterator[LoadedStudy]:
        return iter(self.studies.values())


def load_one(path: Path) -> LoadedStudy:
    """Load and validate one study file and its kitchens (``StudyConfigError`` / ``LayoutError``)."""
    study = load_study(path)
    kitchens = {k.name: k for k in study.kitchens}
    kitchens.update({p.kitchen.name: p.kitchen for p in study.practice})
    layouts = {name: load_layout(kitchen.path) for name, kitchen in kitchens.items()}
    w = study.world
    rules = Rules(cook_time=w.cook_time, chop_time=w.chop_time, wash_time=w.wash_time, orders=w.orders,
                  horizon=w.horizon, delivery_reward=w.delivery_reward)
    orders = tuple(tuple(order) for order in study.condition_orders())
    return LoadedStudy(study=study, orders=orders, layouts=layouts, rules=rules, source=Path(path))


def load_catalog(paths: Iterable[Path]) -> Catalog:
    studies: dict[str, LoadedStudy] = {}
    for path in paths:
        loaded = load_one(Path(path))
        if loaded.id in studies:
            raise DuplicateStudyError(
                f"{path}: study id {loaded.id!r} is already used by {studies[loaded.id].source}")
        studies[loaded.id] = loaded
    return Catalog(studies)
