"""Analysis of Steakhouse studies: from a long table of participant × condition values to a report.

The statistics half works from any long-format table (one row per subject and within-cell):
``cells`` (complete cases), ``anova`` (two-way repeated-measures ANOVA and simple main effects),
``descriptives`` (cell means with within-subject CIs), ``plots``, ``apa`` (formatting), ``report``
and ``run.analyze_long``, which ties them together.

The store half reads a study from the SQL store (``store_reader``: queries of the tables in
``server.store.tables``, never the running server), computes per-trial measures (``measures``, ``work``),
builds the tidy tables (``design``, ``roster``, ``dataset``, ``dictionary``), writes them (``export``) and
hands the cells to the statistics (``study.analyze_study``). Submodules are imported on demand so that the
command line stays fast.
"""
