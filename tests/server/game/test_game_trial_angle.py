"""A stored trial is masked with its own field of view: in a study with ``fov_angles: [90, 150]`` between
participants, the participant of the 150° group sees cells at the start of their trial that the 90° participant,
in the same kitchen and pose, does not; a trial rebuilt from the store (a resume, the admin's view of another
process's trial) keeps the angle, and the admin's live view shows the same field of view."""

from __future__ import annotations

from steakhouse_testing import write_study

from server.admin.live import scene_view
from server.flow import service
from server.flow.progress import Move
from server.game.restore import trial_engine
from server.game.resume import prepare_trial
from server.game.snapshot import state
from store.engine import Store
from store.studies import sync_study
from store.tables import ParticipantRow
from study_config.catalog import load_one


def test_each_angle_level_masks_its_own_trials(db_url, tmp_path) -> None:
    loaded = load_one(write_study(tmp_path, fov_angles=[90, 150], between=["fov_angle"], kitchens=["none_3"]))
    store = Store(db_url)
    try:
        store.migrate()
        with store.transaction() as session:
            sync_study(session, loaded.study)
        seen: dict[float, set[tuple[int, int]]] = {}
        for _ in range(2):
            joined = service.join(store, loaded, {}, False)
            pid = joined.participant.id
            service.move(store, pid, Move.ACCEPT_CONSENT)
            service.move(store, pid, Move.FINISH_INSTRUCTIONS)
            with store.transaction() as session:
                row = session.get(ParticipantRow, pid)
                assert row is not None
                step = service.progress_of(row).current
            trial = prepare_trial(store, loaded, pid, step).trial
            assert trial.fov_angle is not None
            engine = trial_engine(loaded, trial, None)
            assert engine.angle == trial.fov_angle
            cells = state(engine, mode="wait_for_participant", rate=5.0, ack=0).cells
            seen[trial.fov_angle] = {(c.x, c.y) for c in cells}
            admin = scene_view({}, engine)["frame"]["fov"]
            assert {tuple(cell) for cell in admin} == seen[trial.fov_angle], "the admin's live view draws it too"
    finally:
        store.dispose()
    assert sorted(seen) == [90.0, 150.0], "one trial in each group"
    assert seen[90.0] < seen[150.0], "the wider view shows every cell of the narrower one, and more"
