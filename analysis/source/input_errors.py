"""Errors raised by the analysis package at its input boundary."""

from __future__ import annotations


class AnalysisInputError(ValueError):
    """The table handed to an analysis does not fit the requested design (a column, level or value).

    The message names the offending column, subject or cell and says what would fit, so that the
    command line can print it as is.
    """
