"""The live view of a running trial: the spectator view of the game (``LiveGame.spectator``) plus the scene
the dashboard draws — the whole kitchen, the participant's field of view and the modelled KB's kitchen
(:mod:`server.admin.scenes`)."""

from __future__ import annotations

from typing import Any

from server.admin.scenes import frame, grid, kb_frame
from server.game.live import LiveGame


def live_view(game: LiveGame) -> dict[str, Any]:
    engine = game.engine
    layout, rules = engine.layout, engine.rules
    return {**game.spectator(), "grid": grid(layout),
            "frame": {**frame(layout, engine.world, rules, engine.angle), "kb": kb_frame(layout, engine.kb, rules)}}
