"""The view factor end to end: each trial is played in the view of its condition, the participant is told
that view (in the session and in ``hello``) and nothing else about the condition, the trial row records it,
and the export carries it."""

from __future__ import annotations

import asyncio

from steakhouse_testing import Player, condition_order, play_every_trial

from analysis.exports.study_export import read_dataset
from store.tables import TrialRow


def test_each_trial_is_played_recorded_and_exported_in_its_view(live_server, study_file):
    server = live_server([study_file(
        robots=["stay"], kitchens=["practice"], views=["top_down", "first_person"], factors=["view"],
        practice=[{"kitchen": "practice", "robot": "stay", "view": "first_person"}],
        world={"orders": 1, "horizon": 6, "kb_delay": 1})])

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        played = await play_every_trial(player)
        await player.close()
        return joined, [trial["view"] for trial, _ in played], [hello for _, hello in played]

    joined, told, hellos = asyncio.run(scenario())
    order = condition_order(server.services, joined["participant_id"])
    assert sorted(order) == ["stay@practice@first_person", "stay@practice@top_down"]
    expected = ["first_person", *(cid.rsplit("@", 1)[1] for cid in order)]
    assert told == expected
    assert [h["view"] for h in hellos] == expected
    # The view is the one fact about the condition the participant's hello carries.
    assert all(set(h) == set(hellos[0]) and "robot" not in h and "kitchen" not in h for h in hellos)
    with server.services.store.transaction() as s:
        rows = sorted(s.query(TrialRow).all(), key=lambda r: r.id)
        assert [(r.kind, r.condition_id, r.view) for r in rows] == [
            ("practice", "stay@practice", "first_person"),
            *(("main", cid, cid.rsplit("@", 1)[1]) for cid in order)]
    dataset = read_dataset(server.services.store.engine, "tiny")
    trials = dataset.tables["trials.csv"]
    assert list(trials["view"]) == expected
    cells = dataset.tables["cells.csv"]
    assert sorted(zip(cells["condition"], cells["view"], strict=True)) == [
        ("stay@practice@first_person", "first_person"), ("stay@practice@top_down", "top_down")]
    assert set(dataset.tables["ticks.csv"]["view"]) == {"top_down", "first_person"}
