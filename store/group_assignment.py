"""Assignment in a study with between-participants groups, layered on the order counts of
:mod:`store.assignment`.

Each order belongs to one group (``Study.order_groups``). A joining participant goes to the group with the fewest
counting participants (the sum of its orders' counts; ties to the lowest group), then to the least-filled order of
that group (ties to the lowest index), so groups stay within one participant of each other and, inside each group,
the within factors' orders do too. It runs inside the joining transaction, after the study's row is locked, on the
counts :func:`store.assignment.order_counts` read there: atomic like the order choice itself.
"""

from __future__ import annotations

from collections.abc import Sequence

from store.assignment import least_filled


def least_filled_grouped(counts: Sequence[int], groups: Sequence[int]) -> int:
    """The order index to assign: the least-filled order of the least-filled group (``groups[i]``: the group of
    order i; without groups, the least-filled order)."""
    if not groups or len(set(groups)) < 2:
        return least_filled(list(counts))
    totals: dict[int, int] = {}
    for group, count in zip(groups, counts, strict=True):
        totals[group] = totals.get(group, 0) + count
    chosen = min(totals, key=lambda g: (totals[g], g))
    members = [i for i, g in enumerate(groups) if g == chosen]
    return members[least_filled([counts[i] for i in members])]
