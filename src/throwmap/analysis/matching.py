"""Attractors matched across neighbouring parameter values, and the changes between them.

Two attractors found at neighbouring values of a parameter are *the same attractor* when their sets lie close:
the distance (:func:`set_distance`) is the largest Hausdorff distance between their hulls on the sides both
rest on, in metres (infinite when they share no side). Matching is greedy by ascending distance, one to one,
up to a threshold — the matching by distance of Attractors.jl's global continuation, with sides kept apart
because a throw map's configurations on different sides are never near each other.

What is left unmatched is a change: an unmatched attractor whose set (its hull on every side, ± the threshold)
takes in unmatched ones of the other value continues the largest of them — a *jump* (the set grew or shrank at
once, a crisis) — and the others have *merged* into it (or *split* off it); an attractor of the earlier value within
the threshold of one already matched has merged into it, one of the later value near a matched one has split off
it; the rest have *vanished* or *appeared*. :func:`match` returns both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Change", "set_distance", "match"]


def _hulls(a) -> dict:
    """``{side: (lo, hi)}`` of an attractor (an :class:`~throwmap.analysis.attractors.Attractor`), m."""
    out: dict = {}
    for s, lo, hi in a.bands:
        l0, h0 = out.get(int(s), (math.inf, -math.inf))
        out[int(s)] = (min(l0, float(lo)), max(h0, float(hi)))
    return out


def set_distance(a, b) -> float:
    """Distance between two attractors' sets, m: over the sides both rest on, the largest Hausdorff distance
    between their hulls on that side (max(|lo_a − lo_b|, |hi_a − hi_b|)); ``inf`` when they share no side."""
    ha, hb = _hulls(a), _hulls(b)
    common = set(ha) & set(hb)
    if not common:
        return math.inf
    return max(max(abs(ha[s][0] - hb[s][0]), abs(ha[s][1] - hb[s][1])) for s in common)


@dataclass(frozen=True, slots=True)
class Change:
    """One change between two neighbouring values: ``kind`` (``"appear"``, ``"vanish"``, ``"merge"``,
    ``"split"``, ``"jump"``), ``before`` / ``after`` the indices of the attractors concerned at the earlier / later
    value (a merge: the vanished one and the one it merged into; a split: the one split from and the new one; a
    jump: one attractor whose set grew or shrank by more than the threshold at once)."""

    kind: str
    before: tuple
    after: tuple


def match(before, after, tol: float, forced=()) -> tuple[dict, list]:
    """Match the attractors ``after`` (a sequence) to those ``before``: ``({index after: index before}, [Change])``.

    ``forced`` pairs ``(index before, index after)`` are matched first, whatever their distance (a fixed point and
    the period-2 cycle it doubled into); then pairs closer than ``tol`` m (:func:`set_distance`) one to one,
    nearest first; an unmatched one within ``tol`` of a matched one is a merge (before) or a split (after); the
    others vanish or appear.
    """
    pairs = sorted((set_distance(a, b), i, j) for i, a in enumerate(before) for j, b in enumerate(after))
    pairs = [(-1.0, i, j) for i, j in forced] + [(d, i, j) for d, i, j in pairs if d <= tol]
    to_before: dict = {}
    used_before: set = set()
    for d, i, j in pairs:
        if i not in used_before and j not in to_before:
            to_before[j] = i
            used_before.add(i)
    changes = []
    fraction = [getattr(a, "fraction", 0.0) for a in before], [getattr(b, "fraction", 0.0) for b in after]
    # an attractor whose set takes in unmatched ones of the other value continues the largest of them: one taken
    # in is a jump (its hull grew or shrank by more than tol at once), more are a merge (or a split)
    for j in range(len(after)):
        if j in to_before:
            continue
        inner = [i for i in range(len(before)) if i not in used_before and _inside(before[i], after[j], tol)]
        if inner:
            keep = max(inner, key=lambda i: fraction[0][i])
            to_before[j] = keep
            used_before.add(keep)
            changes.append(Change("jump", (keep,), (j,)))
            changes += [Change("merge", (i, keep), (j,)) for i in inner if i != keep]
            used_before.update(inner)
    matched_after = {i: j for j, i in to_before.items()}
    for i in range(len(before)):
        if i in used_before:
            continue
        inner = [j for j in range(len(after)) if j not in to_before and _inside(after[j], before[i], tol)]
        if inner:
            keep = max(inner, key=lambda j: fraction[1][j])
            to_before[keep] = i
            used_before.add(i)
            matched_after[i] = keep
            changes.append(Change("jump", (i,), (keep,)))
            for j in inner:
                if j != keep:
                    to_before.setdefault(j, None)
                    changes.append(Change("split", (i,), (keep, j)))
    split_new = {j for j, i in to_before.items() if i is None}
    to_before = {j: i for j, i in to_before.items() if i is not None}
    for i in range(len(before)):
        if i in used_before:
            continue
        near = [j for d, k, j in pairs if k == i and j in to_before]
        changes.append(Change("merge", (i, to_before[near[0]]), (near[0],)) if near else Change("vanish", (i,), ()))
    for j in range(len(after)):
        if j in to_before or j in split_new:
            continue
        near = [i for d, i, k in pairs if k == j and i in matched_after]
        changes.append(Change("split", (near[0],), (matched_after[near[0]], j)) if near else Change("appear", (), (j,)))
    return to_before, changes


def _inside(small, big, tol: float) -> bool:
    """Whether every side's hull of ``small`` lies within ``big``'s hull on that side, ± ``tol`` m."""
    hs, hb = _hulls(small), _hulls(big)
    return bool(hs) and all(s in hb and hb[s][0] - tol <= lo and hi <= hb[s][1] + tol for s, (lo, hi) in hs.items())
