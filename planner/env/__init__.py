"""The kitchen as a standard multi-agent environment, for training robots against the FOV-limited person
(docs/robots.md, "The environment").

- :mod:`planner.env.observation`: the observation of a cook, numpy only: the person's masked by the same function
  as the participant's frames (:func:`planner.masking.masked`), the robot's full.
- :mod:`planner.env.kitchen`: :class:`~planner.env.kitchen.KitchenEnv`, a PettingZoo ``ParallelEnv`` over the world
  rules (:func:`planner.step.step`), agents ``human`` and ``robot``.
- :mod:`planner.env.single`: :class:`~planner.env.single.RobotEnv`, a Gymnasium ``Env`` for the robot alone, the
  person played by the simulated human (:mod:`planner.human`) with its KB, as in ``steakhouse simulate``.

It lives in ``planner/`` because it is the world's rules, the FOV and the simulated human and nothing else
(planner/ imports nothing of the platform's other layers). PettingZoo and Gymnasium are an optional extra of the
distribution (``pip install 'steakhouse-study[env]'``): only :mod:`~planner.env.kitchen` and
:mod:`~planner.env.single` import them, so nothing else of the platform needs them.
"""
