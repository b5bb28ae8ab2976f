"""One instance per equal value of a kitchen or its rules, so the planner's caches find their keys by identity.

The planner caches paths, views and choices in ``lru_cache`` tables keyed by the :class:`~planner.layout.Layout`
and :class:`~planner.rules.Rules` (among other things). A lookup whose layout is the very object the entry was
stored with costs a pointer comparison; an equal but different object costs a field-by-field comparison of two
kitchens on every hit. A robot worker unpickles a new layout for every trial it opens, so without this every
trial after the first paid that on every cache hit (measured: +65 % CPU per decision). :func:`interned` hands
back the first equal instance this process has seen.
"""

from __future__ import annotations

from typing import TypeVar

T = TypeVar("T")
LIMIT = 1024
"""Distinct values kept (a process sees a handful of kitchens; generated ones in benchmarks, some hundreds)."""

_SEEN: dict[object, object] = {}


def interned(value: T) -> T:
    """The first instance equal to ``value`` this process has seen (``value`` itself the first time)."""
    found = _SEEN.get(value)
    if found is None:
        if len(_SEEN) >= LIMIT:
            _SEEN.clear()
        _SEEN[value] = found = value
    return found  # type: ignore[return-value]
