"""Room 5, the statistics on the prepared table: the omnibus tests and what stands beside them.

``sphericity``, ``anova`` and ``mixed_anova`` (repeated-measures and split-plot ANOVA), ``effect_sizes``,
``nonparametric`` (rank tests for ratings), ``normality``, ``descriptives``, ``order_check``, ``lmm_count_models``
(the LMM and the count model), ``censoring``, ``reliability`` (Cronbach's α), ``end_of_study`` (the end-of-study
questionnaire), ``apa`` (APA-style numbers) and ``results`` (the records of a run). Imports only earlier rooms.
"""
