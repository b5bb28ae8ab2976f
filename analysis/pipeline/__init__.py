"""Room 9, the pipelines the command line and the admin's download call: they tie the rooms together.

``measure_run`` and ``mixed_run`` (the statistics of one measure), ``analyze_long`` (a long table to a report),
``analyze_study`` (export a stored study, then analyse it), ``study_power`` (the power analysis of a stored
study's pilots) and ``simulation`` (the paper's tests on ``steakhouse simulate``). Imports only earlier rooms.
"""
