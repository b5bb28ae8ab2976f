"""Reconnecting: the same trial continues where it stopped (the world is paused while nobody is connected);
the stored ticks stay gap-free and unduplicated; after the grace window the study's policy applies."""

from __future__ import annotations

import asyncio

import pytest
from steakhouse_testing import Player, play_to_end, play_until, until_unloaded

from store import trials
from store.tables import EventRow, ParticipantRow, TrialRow


def trial_rows(server, participant_token_owner: str) -> list[TrialRow]:
    with server.services.store.transaction() as session:
        pid = session.query(ParticipantRow).filter_by(public_id=participant_token_owner).one().id
        return trials.list_trials(session, participant_id=pid)


def test_reconnect_continues_the_same_trial_at_the_same_tick(live_server, study_file):
    server = live_server([study_file()])

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        first = await player.socket()
        hello1 = await first.recv()
        last = await play_until(first, 12)
        await first.close()
        await asyncio.sleep(0.6)  # 18 ticks at 30 Hz if the world did not pause
        second = await player.socket()
        hello2 = await second.recv()
        state2 = await second.recv()
        end = await play_to_end(second)
        await second.close()
        await player.close()
        return joined, hello1, last, hello2, state2, end

    joined, hello1, last, hello2, state2, end = asyncio.run(scenario())
    assert hello2["trial"]["id"] == hello1["trial"]["id"]
    assert hello2["resumed"] is True and hello2["seq"] == 1
    assert last["tick"] <= hello2["tick"] <= last["tick"] + 5, "the world must pause while disconnected"
    assert state2["tick"] == hello2["tick"]
    assert end["status"] == "finished"
    trial_id = hello1["trial"]["id"]
    with server.services.store.transaction() as session:
        ticks = [t.tick for t in trials.ticks(session, trial_id)]
        kinds = [e.kind for e in session.query(EventRow).filter_by(trial_id=trial_id).order_by(EventRow.id)]
    assert ticks == list(range(1, end["ticks"] + 1))
    assert kinds.count("connect") == 2 and kinds.count("disconnect") >= 1
    assert len(trial_rows(server, joined["participant_id"])) == 1


def test_a_second_window_replaces_the_first(live_server, study_file):
    server = live_server([study_file()])

    async def scenario():
        player = Player(server.url)
        await player.ready()
        first = await player.socket()
        await first.recv()
        await play_until(first, 3)
        second = await player.socket()
        replaced = await first.until(lambda m: m["type"] == "error")
        await asyncio.wait_for(first.ws.wait_closed(), 5)
        hello = await second.recv()
        end = await play_to_end(second)
        await second.close()
        await player.close()
        return replaced, first.ws.close_code, hello, end

    replaced, code, hello, end = asyncio.run(scenario())
    assert replaced["code"] == "replaced" and code == 4000
    assert hello["resumed"] is True and end["status"] == "finished"


@pytest.mark.parametrize("policy", ["abandon", "restart", "resume"])
def test_after_the_grace_window_the_study_policy_applies(live_server, study_file, policy):
    server = live_server([study_file(reconnect={"grace_seconds": 0.3, "after_grace": policy})])

    async def scenario():
        player = Player(server.url)
        joined = await player.join()
        await player.post("/api/session/consent", {"accept": True})
        await player.post("/api/session/instructions_done")
        first = await player.socket()
        hello1 = await first.recv()
        last = await play_until(first, 8)
        await first.close()
        await until_unloaded(server.services, timeout=5)
        session = await player.session()
        second = await player.socket()
        reply = await second.recv()
        follow = None if reply["type"] != "hello" else await second.recv()
        await second.close()
        await player.close()
        return joined, hello1, last, session, reply, follow

    joined, hello1, last, session, reply, follow = asyncio.run(scenario())
    rows = {r.id: r for r in trial_rows(server, joined["participant_id"])}
    first_row = rows[hello1["trial"]["id"]]
    if policy == "abandon":
        assert (first_row.status, first_row.end_reason) == ("abandoned", "grace_expired")
        # The only main round was abandoned: the study's screen-out outcome, never a questionnaire about it.
        assert session["state"] == "screened_out" and session["completion"]["reason"] == "abandoned_rounds"
        assert reply["type"] == "error" and reply["code"] == "no_trial"
    elif policy == "restart":
        assert reply["type"] == "hello" and reply["tick"] == 0 and reply["trial"]["id"] != first_row.id
        assert (first_row.status, first_row.end_reason) == ("abandoned", "restarted")
        assert rows[reply["trial"]["id"]].attempt == 2
    else:
        assert reply["type"] == "hello" and reply["trial"]["id"] == first_row.id and reply["resumed"] is True
        assert last["tick"] <= reply["tick"] <= last["tick"] + 5
        assert follow["tick"] == reply["tick"]
        # Every tick stored once, none skipped: up to the resumed one, and on from it while the second socket stayed
        # open (on a busy machine the world steps on at 30 Hz before the close is handled).
        with server.services.store.transaction() as s:
            stored = [t.tick for t in trials.ticks(s, first_row.id)]
        assert stored == list(range(1, len(stored) + 1)) and len(stored) >= reply["tick"]
