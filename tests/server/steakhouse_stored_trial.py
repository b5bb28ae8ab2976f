"""A main trial row in the store, for tests of what is stored on it (``store.trials``, the writer, a live trial's
robot health)."""

from __future__ import annotations

from planner.state import initial_state
from server.flow import service
from store import trials
from store.engine import Store
from study_config.catalog import LoadedStudy


def new_trial(store: Store, loaded: LoadedStudy) -> tuple[int, int]:
    """A participant who joined ``loaded`` and their first main trial (``stay`` in ``practice``): their ids."""
    joined = service.join(store, loaded, {}, False)
    with store.transaction() as session:
        row = trials.create(session, study_id=loaded.id, participant_id=joined.participant.id, kind="main", index=0,
                            condition_id="stay@practice", kitchen="practice", robot="stay", seed=1,
                            config_hash="0" * 64,
                            initial_state=initial_state(loaded.layout("practice"), loaded.rules).to_dict())
        return joined.participant.id, row.id
