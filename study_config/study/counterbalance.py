"""Condition orders: which sequence of conditions each participant plays.

- ``latin_square``: a balanced Latin square (Williams 1949). Row ``r`` is the sequence
  ``0, 1, n-1, 2, n-2, 3, ...`` shifted by ``r`` (mod n). For even n these n rows put each condition once
  in every position and make each condition immediately follow every other exactly once, which balances
  first-order carry-over effects. For odd n no such square exists; the n rows and their n mirror images
  (2n orders) put each condition twice in every position and each ordered pair next to each other
  exactly twice.
- ``full``: all n! permutations, in lexicographic order of the condition list.
- ``fixed``: the single given order.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Literal

Scheme = Literal["latin_square", "full", "fixed"]

MAX_FULL_CONDITIONS = 8
"""``full`` counterbalancing is refused above this many conditions (8! = 40 320 orders)."""


def williams_rows(n: int) -> list[tuple[int, ...]]:
    """Rows of a Williams design over condition indices ``0..n-1`` (2n rows when n is odd and > 1)."""
    if n < 1:
        raise ValueError("a Latin square needs at least one condition")
    first = [0]
    low, high = 1, n - 1
    while len(first) < n:
        first.append(low)
        low += 1
        if len(first) < n:
            first.append(high)
            high -= 1
    rows = [tuple((c + r) % n for c in first) for r in range(n)]
    if n % 2 == 1 and n > 1:
        rows += [tuple(reversed(row)) for row in rows]
    return rows


def condition_orders(
    conditions: Sequence[str], scheme: str, fixed: Sequence[str] | None = None
) -> list[tuple[str, ...]]:
    """The condition orders of ``scheme`` over ``conditions`` (condition ids, in study order)."""
    if len(set(conditions)) != len(conditions):
        raise ValueError("condition ids must be unique")
    if scheme == "latin_square":
        return [tuple(conditions[i] for i in row) for row in williams_rows(len(conditions))]
    if scheme == "full":
        if len(conditions) > MAX_FULL_CONDITIONS:
            raise ValueError(
                f"full counterbalancing of {len(conditions)} conditions is too many orders; use latin_square"
            )
        return list(itertools.permutations(conditions))
    if scheme == "fixed":
        if fixed is None or sorted(fixed) != sorted(conditions):
            raise ValueError("a fixed order must list every condition exactly once")
        return [tuple(fixed)]
    raise ValueError(f"unknown counterbalancing scheme {scheme!r}; use latin_square, full or fixed")
