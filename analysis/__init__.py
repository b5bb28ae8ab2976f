"""Analysis of Steakhouse studies: from a long table of participant × condition values to a report.

The statistics half works from any long-format table (one row per subject and within-cell):
``cells`` (complete cases), ``anova`` (two-way repeated-measures ANOVA and simple main effects),
``descriptives`` (cell means with within-subject CIs), ``plots``, ``apa`` (formatting), ``report``
and ``run.analyze_long``, which ties them together. Submodules are imported on demand so that the
command line stays fast.
"""
