"""Room 2, the measures: values computed from one stored trial or response.

``trial_measures`` (per-trial measures from the stored ticks and events), ``work`` (who did which work),
``participation`` (the participant's part in each trial) and ``scale_scores`` (questionnaire scales scored after
reverse coding). Imports only the source.
"""
