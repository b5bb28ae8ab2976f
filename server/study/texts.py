"""Default participant-facing texts (Markdown). Studies should replace the consent text with their own."""

from __future__ import annotations

DEFAULT_CONSENT = """\
# Consent to take part

You are invited to take part in a research study about how people work together with a robot partner.
You will play a short cooking game in your browser with a simulated robot, and answer a few questions
after each round. It takes about 15 minutes.

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
garnish and a clean plate, brought together and delivered at the serving counter.

- **You only see what is in front of you.** Black cells are outside your field of view: anything
  there, including the robot, is hidden until you turn toward it.
- **Choose a task** with the buttons (for example *pick up meat* or *wash plate*): your cook walks
  there by the shortest path and does it.
- **Interrupt** at any time with the keys shown under the kitchen: move one step, stay, interact
  with what you face, or stop the current task. Choosing a new task replaces the current one.
- The robot works on its own. Deliver all orders as quickly as you can.

The first round is practice and is not scored.
"""
