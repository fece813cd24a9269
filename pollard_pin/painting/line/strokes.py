"""The strokes' direction on a line, a planned choice (docs/model.md §24.2): strokes
``across`` the travel stepping from the part's ``leading`` (or ``trailing``) end, or
``along`` the travel stepping across it. ``auto`` plans both and keeps, of those that paint,
the shortest cycle; a forced strategy that cannot paint is refused naming it.
"""
from __future__ import annotations

from dataclasses import dataclass

from ...errors import PollardError, say_less
from ..errors import LineSpeedError, PlanError
from ..policy import DEFAULT_POLICY, PlannerPolicy


@dataclass(frozen=True)
class Strokes:
    """A plan's strokes on the line: ``direction`` ("across" or "along" the travel), the end
    they step ``start`` from ("leading", "trailing"; None for strokes along the travel, which
    step across it) and the ``dwell`` [s] waited in all at the turnarounds (a slow line,
    :mod:`.line.dwell`)."""

    direction: str = "across"
    start: str | None = "leading"
    dwell: float = 0.0

    def to_dict(self) -> dict:
        return {"direction": self.direction, "step_from": self.start, "dwell_s": self.dwell}

    def said(self) -> str:
        """The strategy in words (the summary's line, a refusal's name)."""
        where = f", stepping from the {self.start} end" if self.start else ""
        return f"strokes {self.direction} the travel{where}"


def candidates(policy: PlannerPolicy = DEFAULT_POLICY) -> tuple[Strokes, ...]:
    """The strategies to plan: the forced one, or for ``auto`` across then along."""
    ways = ("across", "along") if policy.strokes == "auto" else (policy.strokes,)
    return tuple(Strokes(w, policy.step_from if w == "across" else None) for w in ways)


def across(strokes: Strokes, across_travel: bool) -> bool:
    """The layout's ``horizontal`` for ``strokes``, given whether horizontal passes run
    across the travel."""
    return across_travel if strokes.direction == "across" else not across_travel


def shortest(plan_with, policy: PlannerPolicy = DEFAULT_POLICY):
    """``plan_with(strokes)`` for each of the policy's :func:`candidates`, the shortest
    cycle of those that plan; none: the first one's error (a forced one's named)."""
    found, first = [], None
    ways = candidates(policy)
    for s in ways:
        try:
            found.append(plan_with(s))
        except PollardError as exc:  # a later strategy's bad input is only not a candidate
            if not isinstance(exc, PlanError) and s == ways[0]:
                raise
            first = exc if first is None else first
    if found:
        return min(found, key=lambda p: p.times.cycle)
    if len(ways) == 1 and policy.strokes != "auto":
        raise named(first, ways[0])
    raise first


def named(exc: PlanError, strokes: Strokes) -> PlanError:
    """``exc`` with the forced strategy said first (a :class:`LineSpeedError` keeps its
    sense, so the speed search still reads it)."""
    said = f"{strokes.said()} (forced)"
    text = say_less(f"{said}: {exc}", f"{said}: {str(exc).split(': ')[0]}", said)
    if isinstance(exc, LineSpeedError):
        return LineSpeedError(text, exc.too_fast, exc.why, exc.hint)
    try:
        return type(exc)(text)
    except TypeError:  # a subclass of its own signature
        return PlanError(text)


__all__ = ["Strokes", "across", "candidates", "named", "shortest"]
