"""Room 8, the report: Markdown and HTML, with its figures.

``document`` (the block model), ``typeset`` (its typography), ``report_tables``, ``quality_section``,
``measure_section`` and ``end_section`` (the report's parts), ``analysis_report`` (the whole report) and ``plots``.
Imports only earlier rooms.
"""
