"""The live view of a running trial: the spectator view of the game (``LiveGame.spectator``) plus the scene
the dashboard draws — the whole kitchen, the participant's field of view and the modelled KB's kitchen
(:mod:`server.admin.scenes`). Trials another server process runs are rebuilt from the store
(:mod:`server.admin.stored_live`) into the same shape."""

from __future__ import annotations

from typing import Any

from server.admin.scenes import frame, grid, kb_frame
from server.game.engine import TrialEngine
from server.game.live import LiveGame
from server.game.ownership import process_name


def scene_view(spectator: dict[str, Any], engine: TrialEngine) -> dict[str, Any]:
    layout, rules = engine.layout, engine.rules
    return {**spectator, "grid": grid(layout),
            "frame": {**frame(layout, engine.world, rules, engine.angle), "kb": kb_frame(layout, engine.kb, rules)}}


def live_view(game: LiveGame) -> dict[str, Any]:
    return scene_view({**game.spectator(), "process": process_name(), "source": "process"}, game.engine)
