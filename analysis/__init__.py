"""Analysis of Steakhouse studies: from a long table of participant × condition values to a report.

The statistics half works from any long-format table (one row per subject and within-cell, one to three within
factors): ``levels`` (the study's level order), ``exclusions`` (rows left out by rule), ``cells`` (complete
cases), ``sphericity`` and ``anova`` (the repeated-measures ANOVA with Mauchly's test and the Greenhouse–Geisser
and Huynh–Feldt corrections), ``effect_sizes``, ``followups`` (simple main effects), ``pairwise``,
``nonparametric`` (rank tests for ratings), ``censoring`` (``ticks`` at the horizon, ``finished``),
``order_check``, ``normality``, ``scales`` (questionnaire scales), ``descriptives``, ``plots``, ``apa`` and the
``report*`` modules; ``measure_run`` analyses one measure and ``run.analyze_long`` ties them together.

The store half reads a study from the SQL store (``store_reader``: queries of the tables in
``store.tables``, never the running server), computes per-trial measures (``measures``, ``work``),
builds the tidy tables (``design``, ``roster``, ``dataset``, ``dictionary``), writes them (``export``) and
hands the cells to the statistics with the design the study declares (``study_design``, ``study``).
Submodules are imported on demand so that the command line stays fast.
"""
