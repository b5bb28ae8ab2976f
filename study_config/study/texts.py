"""Default participant-facing texts (Markdown). Studies should replace the consent text with their own.

``{minutes}``, ``{rounds}``, ``{round_time}``, ``{practice_note}`` and the other placeholders of
:mod:`study_config.study.duration` are filled in from the study when the page is shown, so the times promised
always match the study's rounds, horizon and tick rate.
"""

from __future__ import annotations

DEFAULT_CONSENT = """\
# Consent to take part

You are invited to take part in a research study about how people work together with a robot partner.
You will play {rounds} short rounds of a cooking game in your browser with a simulated robot (each lasts
at most {round_time}) and answer a few questions after each of the {main_rounds} rounds that count. It takes up
to about {minutes} minutes.

- Taking part is voluntary. You may stop at any time by closing this page.
- We record your actions in the game and your answers. We do not record your name; your data are
  stored under a random id.
- There are no known risks beyond those of everyday computer use.

**Researchers: replace this text with the consent form approved by your ethics board.**

By clicking *I agree* you confirm that you are 18 or older and agree to take part.
"""

DEFAULT_INSTRUCTIONS = """\
# How to play

You and a robot run a small steakhouse kitchen. Each dish needs a grilled steak, a chopped onion
garnish and a clean plate, brought together and delivered at the serving counter. The recipe below
shows the order; during a round it stays in sight above the kitchen.

- **You only see what is in front of you.** Black cells are outside your field of view: anything
  there, including the robot, is hidden until you turn toward it.
- **Choose a task** with the buttons (for example *pick up meat* or *wash plate*): your cook walks
  there by the shortest path and does it. A task that cannot work with what you hold is greyed out,
  with the reason.
- **Interrupt** at any time with the keys shown under the kitchen: move one cell, stay, interact
  with what you face, or stop the current task. Choosing a new task replaces the current one.
- {clock_note} Deliver all orders as quickly as you can: a round lasts at most {round_time}.

{practice_note}
"""
