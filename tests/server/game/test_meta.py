"""The fixed facts of a live trial (``server.game.meta``) as the admin receives them: the seed as text, since a
62-bit seed does not survive a JavaScript number."""

from __future__ import annotations

import json

from steakhouse_live_parts import meta


def test_the_admin_gets_the_seed_as_text_and_every_other_fact_as_is() -> None:
    seed = 2**62 - 1
    facts = json.loads(json.dumps(meta(seed=seed, pilot_pace="fast", epoch=3).to_dict()))
    assert facts["seed"] == str(seed) and int(facts["seed"]) == seed
    assert (facts["trial_id"], facts["pilot_pace"], facts["epoch"], facts["view"]) == (7, "fast", 3, "top_down")
