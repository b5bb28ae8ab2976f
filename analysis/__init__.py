"""Analysis of Steakhouse studies: from a stored study, or any long table of participant × condition values, to a
report.

The package is laid out in rooms along its pipeline, each a sub-package that imports only the rooms before it
(``tests/test_layers.py`` holds this):

1. ``source``: reading the store (``store.tables``, never the running server), the design a study declares, and
   how cells, items and scales are named;
2. ``measures``: per-trial measures, who did which work, participation, scale scores;
3. ``exports``: the tidy CSV files, ``wide.sav`` and the data dictionary;
4. ``preparation``: any long table made ready (level order, exclusions by rule, complete cases, the run's options);
5. ``statistics``: the ANOVA (within and mixed) with sphericity and effect sizes, rank tests, models, normality,
   descriptives, the order check, censoring, reliability, the end-of-study questionnaire;
6. ``followups``: simple effects and pairwise comparisons, within and mixed designs;
7. ``power_analysis``: simulation power from pilot data;
8. ``reporting``: the report in Markdown and HTML, and its figures;
9. ``pipeline``: ``analyze_long``, ``analyze_study``, ``study_power`` and ``simulation``, which tie the rooms together
   for the command line and the admin's download.

Submodules are imported on demand so that the command line stays fast.
"""
