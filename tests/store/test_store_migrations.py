"""The Alembic migrations build exactly the tables the models declare, on SQLite and PostgreSQL."""

from __future__ import annotations

import threading

from alembic.autogenerate import compare_metadata
from alembic.runtime.migration import MigrationContext
from sqlalchemy import inspect

from store.engine import Store
from store.migrate import current_revision
from store.tables import Base


def test_migrations_match_the_models(empty_db_url):
    store = Store(empty_db_url)
    try:
        store.migrate()
        assert current_revision(store.engine) == "0010"
        with store.engine.connect() as conn:
            context = MigrationContext.configure(conn, opts={"compare_type": True})
            diff = compare_metadata(context, Base.metadata)
        assert diff == []
        tables = set(inspect(store.engine).get_table_names())
        assert tables >= {"studies", "participants", "assignments", "trials", "ticks", "events",
                          "questionnaire_answers", "quiz_attempts", "alembic_version"}
    finally:
        store.dispose()


def test_migrating_again_and_concurrently_is_harmless(empty_db_url):
    stores = [Store(empty_db_url) for _ in range(6)]
    errors: list[BaseException] = []

    def run(store: Store) -> None:
        try:
            store.migrate()
        except BaseException as exc:
            errors.append(exc)

    try:
        threads = [threading.Thread(target=run, args=(s,)) for s in stores]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        stores[0].migrate()
        assert errors == []
        assert current_revision(stores[0].engine) == "0010"
    finally:
        for store in stores:
            store.dispose()


def test_the_sqlite_store_creates_its_folder_and_uses_wal(tmp_path):
    store = Store(f"sqlite:///{tmp_path / 'new' / 'dir' / 's.sqlite3'}")
    try:
        store.migrate()
        with store.engine.connect() as conn:
            assert conn.exec_driver_sql("PRAGMA journal_mode").scalar() == "wal"
            assert conn.exec_driver_sql("PRAGMA foreign_keys").scalar() == 1
            conn.rollback()
        assert (tmp_path / "new" / "dir" / "s.sqlite3").exists()
        assert store.ping()
    finally:
        store.dispose()


def test_revision_0008_gives_older_trials_their_studys_angle_where_the_config_is_the_one_they_played(
        db_url, study_file):
    """Trials stored before the angle was recorded get the study's ``world.fov_angle`` when the study's stored
    configuration is the one they were played with (same hash); a trial of an older configuration stays unknown."""
    from alembic import command

    from server.flow import service
    from store import trials
    from store.migrate import alembic_config
    from store.studies import sync_study
    from store.tables import TrialRow
    from study_config.catalog import load_one

    loaded = load_one(study_file(world={"fov_angle": 100}))
    store = Store(db_url)
    try:
        store.migrate()
        with store.transaction() as session:
            sync_study(session, loaded.study)
        pid = service.join(store, loaded, {}, False).participant.id
        with store.transaction() as session:
            ids = [trials.create(session, study_id=loaded.id, participant_id=pid, kind="main", index=i,
                                 condition_id="stay@practice", kitchen="practice", robot="stay", seed=1,
                                 config_hash=config_hash, initial_state={}, fov_angle=55.0).id
                   for i, config_hash in enumerate((loaded.study.config_hash(), "an-older-configuration"))]
        config = alembic_config()
        for step, revision in ((command.downgrade, "0007"), (command.upgrade, "head")):
            with store.engine.begin() as conn:
                config.attributes["connection"] = conn
                step(config, revision)
        with store.transaction() as session:
            assert [session.get(TrialRow, i).fov_angle for i in ids] == [100.0, None]  # type: ignore[union-attr]
    finally:
        store.dispose()
