"""Room 3, the export files: a study's tidy CSV files, ``wide.sav`` and their data dictionary.

``dictionary`` and ``dictionary_items`` (every column and questionnaire item, with its meaning), ``export_design``
(the design as the export needs it), ``roster`` (who is in and why not), ``dataset`` (the tables), ``spss``
(``wide.sav``) and ``study_export`` (writes them to one folder). Imports only earlier rooms.
"""
