"""Study definitions: the YAML an experimenter writes, validated into frozen models.

``load_study(path)`` gives a :class:`Study` (conditions, condition orders, every setting, and the config
hash stored with each trial); ``validate_study_file(path)`` lists every problem with file, field and reason;
``Design.from_config(config)`` reads a study's factors, levels and conditions from its configuration, also as an
older version stored it.
"""

from study_config.study.conditions import Condition, condition_id
from study_config.study.counterbalance import condition_orders
from study_config.study.design import Design
from study_config.study.kitchens import Kitchen
from study_config.study.loader import StudyConfigError, StudyProblem, load_study, validate_study_file
from study_config.study.models import Study

__all__ = [
    "Condition",
    "Design",
    "Kitchen",
    "Study",
    "StudyConfigError",
    "StudyProblem",
    "condition_id",
    "condition_orders",
    "load_study",
    "validate_study_file",
]
