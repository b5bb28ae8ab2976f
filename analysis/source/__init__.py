"""Room 1, the source: what the analysis reads and how it names it.

``store_reader`` (the store's rows, by SQLAlchemy Core queries of ``store.tables``, never the running server),
``study_design`` (the design a stored study declares), ``naming`` (how a cell, an item and a scale are named) and
``input_errors`` (the one error every room raises at its input boundary). Imports no other room.
"""
