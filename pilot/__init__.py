"""Simulated pilot participants: rehearse a study through the real server before recruiting anyone.

- :mod:`pilot.config` — every parameter of the simulated participant in one typed config (YAML or flags).
- :mod:`pilot.perception` — what the simulated participant knows: its own KB, built only from the masked
  ``state`` frames with the study's FOV and KB rules (``planner.kb``).
- :mod:`pilot.mind` — its choices each tick: subtasks by the simulated human's rule, decision latency, errors,
  interrupts (stop, replace, one-step corrections, side-steps) when what it sees makes its subtask pointless.
- :mod:`pilot.answers` — its simulated questionnaire answers.
- :mod:`pilot.client` — one simulated participant over the participant REST flow and the game websocket.
- :mod:`pilot.run` — N of them against a server (started here, or a running one), with a progress display.

The package lives at the top level, beside ``planner`` and ``analysis``: it is a client of the server (it
imports only the study loader and the planner's pure rules from it), not part of the server.
"""
