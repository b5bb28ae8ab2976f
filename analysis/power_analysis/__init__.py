"""Room 7, simulation power from pilot data.

``within_power`` (designs within participants, vectorised over resamples), ``mixed_power`` (one factor between
participants) and ``chosen_effect`` (power for a chosen effect size). Imports only earlier rooms.
"""
