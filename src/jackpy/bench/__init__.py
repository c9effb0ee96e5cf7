"""The project's benchmark runner (``jackpy bench``).

Cases live one module per area in :mod:`jackpy.bench` (``cases_*.py``); each module defines
``CASES``, a list of :class:`~jackpy.bench.runner.Case`. A case times a callable and, where it has
one, a baseline measured in the same process, and reports medians and the ratio baseline/median.
"""
