"""Room 4, the table made ready for the statistics: any long table, from an export or not.

``levels`` (the study's level order), ``exclusions`` (rows left out by rule), ``cells`` (complete cases),
``measure_info`` (what a measure is: its label, bounds, rating or not) and ``options`` (an analysis run's choices).
Imports only earlier rooms.
"""
