"""The strokes' direction on a line, a planned choice (docs/model.md §24.2): strokes
``across`` the travel stepping from the part's ``leading`` (or ``trailing``) end, or
``along`` the travel stepping across it. ``auto`` plans both and keeps, of those that pass
every check (reach and motors as planned, then the gun's clearance), the shortest cycle; a
forced strategy that cannot paint is refused naming it.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from ...errors import PollardError, say_less, without_asides
from ..errors import LineSpeedError, PlanError
from ..policy import DEFAULT_POLICY, PlannerPolicy


@dataclass(frozen=True)
class Strokes:
    """A plan's strokes on the line: ``direction`` ("across" or "along" the travel), the end
    they step ``start`` from ("leading", "trailing"; None for strokes along the travel, which
    step across it), the ``dwell`` [s] waited in all at the turnarounds (a slow line,
    :mod:`.line.dwell`) and ``why`` it was chosen (forced, or auto's comparison)."""

    direction: str = "across"
    start: str | None = "leading"
    dwell: float = 0.0
    why: str = ""

    def to_dict(self) -> dict:
        return {"direction": self.direction, "step_from": self.start, "dwell_s": self.dwell,
                "why": self.why}

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


def shortest(plan_with, policy: PlannerPolicy = DEFAULT_POLICY, check=None,
             always: bool = False, source: str = ""):
    """``plan_with(strokes)`` for each of the policy's :func:`candidates`, the shortest
    cycle of those that plan and pass ``check`` (plan ↦ the plan checked, or a
    :class:`PlanError`: the gun's clearance), tried in order of cycle; ``check`` is run on
    the one kept when ``always``, else only where two or more planned (the choice then
    depends on it). None: the first one's error (a forced one's named, the job's
    ``source`` that leads its words dropped). The plan's ``strokes.why`` says the choice."""
    found, first, said = [], None, []
    ways = candidates(policy)
    for s in ways:
        try:
            found.append(plan_with(s))
        except PollardError as exc:  # a later strategy's bad input is only not a candidate
            if not isinstance(exc, PlanError) and s == ways[0]:
                raise
            first = exc if first is None else first
            said.append(f"{_short(s)}: {_reason(exc)}")
    found.sort(key=lambda p: p.times.cycle)
    refused = None
    for k, plan in enumerate(found):
        if check is not None and (always or len(found) > 1):
            try:
                plan = check(plan)
            except PlanError as exc:
                refused = exc if refused is None else refused
                said.append(f"{_short(plan.strokes)}: {_reason(exc)}")
                continue
        others = [f"{_short(p.strokes)}: cycle {p.times.cycle:.2f} s" for p in found[k + 1:]]
        why = "forced" if policy.strokes != "auto" else (
            f"auto: the shortest cycle that paints, {plan.times.cycle:.2f} s"
            + "".join(f"; {w}" for w in said + others))
        return replace(plan, strokes=replace(plan.strokes, why=why))
    if refused is not None:
        raise refused
    if len(ways) == 1 and policy.strokes != "auto":
        raise named(first, ways[0], source)
    raise first


def _short(strokes: Strokes) -> str:
    return strokes.direction + (f" from the {strokes.start} end" if strokes.start else "")


def _reason(exc: Exception, room: int = 100) -> str:
    """A refusal's words, cut to ``room`` characters."""
    text = str(exc)
    return text if len(text) <= room else text[:room - 1] + "…"


def named(exc: PlanError, strokes: Strokes, source: str = "") -> PlanError:
    """``exc`` with the forced strategy said first, the job's ``source`` that may lead its
    words dropped (a :class:`LineSpeedError` keeps its sense, so the speed search still
    reads it)."""
    said = f"{strokes.said()} (forced)"
    words = str(exc).removeprefix(f"{source}: ") if source else str(exc)
    text = say_less(f"{said}: {words}", f"{said}: {without_asides(words)}",
                    f"{said}: {words.split(': ')[0]}", said)
    if isinstance(exc, LineSpeedError):
        return LineSpeedError(text, exc.too_fast, exc.why, exc.hint)
    try:
        return type(exc)(text)
    except TypeError:  # a subclass of its own signature
        return PlanError(text)


__all__ = ["Strokes", "across", "candidates", "named", "shortest"]
