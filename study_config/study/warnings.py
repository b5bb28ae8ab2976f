"""Study-file warnings: settings that are valid but probably not what a real online study wants.

``steakhouse study validate`` prints them (the file still passes) and the admin dashboard shows them beside
the study. Each names the field it is about.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass

from study_config.study.counterbalance import williams_rows
from study_config.study.duration import study_length, unknown_placeholders
from study_config.study.models import Study

PLACEHOLDER_PREFIX = "REPLACE-WITH-YOUR-"
"""How the codes shipped in ``study_config/paper_study.yaml`` begin (``REPLACE-WITH-YOUR-COMPLETION-CODE``): a
study still using one is warned about."""

EVERYDAY_WORDS = frozenset({"stay", "practice"})
"""Robot or kitchen names that are ordinary words of the instructions ("stay", "practice"): not warned about."""

FULL_ORDERS_WARNING = 24
"""``full`` counterbalancing beyond this many orders gets a warning (4 conditions give 24 orders)."""


@dataclass(frozen=True, slots=True)
class StudyWarning:
    path: str
    """The field the warning is about (``recruiting.completion_code``)."""
    reason: str
    code: str
    """A stable name for tools (``no_completion_code``, ``placeholder_code``, ``no_screen_out_code``,
    ``many_orders``, ``clock_not_chosen``, ``unknown_placeholder``, ``names_condition``, ``unused_variant``)."""

    def __str__(self) -> str:
        return f"{self.path}: warning: {self.reason}"

    def to_dict(self) -> dict[str, str]:
        return {"path": self.path, "reason": self.reason, "code": self.code}


def study_warnings(study: Study) -> list[StudyWarning]:
    """Every warning about ``study``, in the order of the fields in the file."""
    out: list[StudyWarning] = []
    recruiting = study.recruiting
    captured = ", ".join(recruiting.url_parameters)
    if recruiting.url_parameters and not (recruiting.completion_code or recruiting.completion_redirect_url):
        out.append(StudyWarning(
            "recruiting.completion_code", f"recruiting ids are captured ({captured}) but no completion code or "
            "redirect is set: participants who finish cannot prove it to the recruiting platform",
            "no_completion_code"))
    for kind in ("completion_code", "screen_out_code"):
        if (getattr(recruiting, kind) or "").startswith(PLACEHOLDER_PREFIX):
            out.append(StudyWarning(
                f"recruiting.{kind}", "still the placeholder shipped with the example: replace it with the code "
                "your recruiting platform gives you", "placeholder_code"))
    if (study.quiz is not None and recruiting.url_parameters
            and not (recruiting.screen_out_code or recruiting.screen_out_redirect_url)):
        out.append(StudyWarning(
            "recruiting.screen_out_code", "the quiz can screen participants out but no screen-out code or redirect "
            "is set: they cannot be paid or returned to the recruiting platform", "no_screen_out_code"))
    if study.counterbalancing.scheme == "full":
        orders = math.factorial(len(study.conditions))
        if orders > FULL_ORDERS_WARNING:
            out.append(StudyWarning(
                "counterbalancing", f"full counterbalancing of {len(study.conditions)} conditions gives {orders} "
                f"orders: a complete design needs a multiple of {orders} participants ({orders}, {2 * orders}, …); "
                f"latin_square needs {len(williams_rows(len(study.conditions)))}", "many_orders"))
    if "mode" not in study.timing.model_fields_set:
        out.append(StudyWarning(
            "timing.mode", "not written, so fixed_rate: the world goes on while the participant thinks, and the "
            "robot does the work meanwhile; the paper's clock is wait_for_participant (docs/protocol.md, \"The two "
            "clocks\"). Write the clock you mean", "clock_not_chosen"))
    names = study_length(study).placeholders()
    for field in ("consent", "instructions"):
        for token in unknown_placeholders(getattr(study, field), names):
            out.append(StudyWarning(field, f"{token} is not a placeholder and is shown as written; placeholders: "
                                           f"{', '.join('{' + n + '}' for n in names)}", "unknown_placeholder"))
    out += condition_name_warnings(study)
    for name in study.robot_variants:
        if name not in study.robots:
            out.append(StudyWarning(f"robot_variants.{name}", "defined but not one of robots: no trial plays it",
                                    "unused_variant"))
    return out


def condition_name_warnings(study: Study) -> list[StudyWarning]:
    """Texts shown to participants that name a condition, a robot or a kitchen: participants must stay blind
    to their conditions (``docs/protocol.md`` §1), and the platform sends these texts as written."""
    names = {c.id for c in study.conditions} | set(study.robots) | {k.name for k in study.kitchens}
    names |= {p.robot for p in study.practice} | {p.kitchen.name for p in study.practice}
    pattern = re.compile(r"(?<![A-Za-z0-9_])(" + "|".join(
        re.escape(n) for n in sorted(names - EVERYDAY_WORDS, key=len, reverse=True)) + r")(?![A-Za-z0-9_@])")
    out = []
    for path, text in participant_texts(study):
        found = sorted(set(pattern.findall(text)))
        if found:
            out.append(StudyWarning(path, f"shown to participants but names {', '.join(map(repr, found))}: "
                                          "participants must not learn their conditions", "names_condition"))
    return out


def participant_texts(study: Study) -> Iterator[tuple[str, str]]:
    """``(field path, text)`` of everything the study file writes for participants to read."""
    yield "consent", study.consent
    yield "instructions", study.instructions
    if study.quiz is not None:
        for i, question in enumerate(study.quiz.questions):
            where = f"quiz.questions[{i}]"
            yield f"{where}.text", question.text
            yield f"{where}.explanation", question.explanation
            yield from ((f"{where}.options[{j}]", option) for j, option in enumerate(question.options))
    for i, questionnaire in enumerate(study.questionnaires):
        yield f"questionnaires[{i}].title", questionnaire.title
        for j, item in enumerate(questionnaire.items):
            where = f"questionnaires[{i}].items[{j}]"
            yield f"{where}.text", item.text
            yield from ((f"{where}.options[{k}]", option) for k, option in enumerate(item.options))
            if item.scale is not None:
                yield from ((f"{where}.scale.labels[{value}]", label) for value, label in item.scale.labels.items())
