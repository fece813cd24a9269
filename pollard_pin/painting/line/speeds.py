"""The line speeds that paint a job (docs/model.md §24.3): the fastest (``--max-line-speed``),
the interval [v_min, v_max] around the job's speed, and the refusal of a speed that does not
paint naming them. Every search runs over ``plan_at(speed)``, the whole job's plan at one
speed (one robot, a cell, whichever stroke strategies it tries): only its
:class:`LineSpeedError` (and, on the slow side, the budget's :class:`BudgetError`) count as
a speed that does not paint; any other error is the job's and is raised.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ...errors import say_less
from ..errors import BudgetError, LineSpeedError, PlanError, kept, made_again
from ..progress import ticking
from .conveyor import MAX_LINE_SPEED

SPEED_RESOLUTION = 0.01  # relative: --max-line-speed's bisection stops at this bracket
SPEED_TRIES = 12  # doublings/halvings bracketing the fastest speed
INTERVAL_RESOLUTION = 0.05  # relative: the interval paint.json states (--speeds)
BUDGET_FLOOR = "budget floor"  # the slow end's bound when the path's sample budget binds
# the constraint a LineSpeedError's ``why`` names (plan_world's words), first match
_CONSTRAINTS = (("turnaround", "reach and motors"), ("motor", "motors"), ("reach", "reach"),
                ("workspace", "reach"), ("clearance", "clearance"), ("film", "film"))


@dataclass(frozen=True)
class SpeedInterval:
    """The line speeds that paint a job: the run [``low``, ``high``] m/s about the speed
    the search starts from, each end within ``resolution`` (relative) of the first speed
    beyond it that does not paint, both ends planned in full (docs/model.md §24.3).

    Attributes
    ----------
    low, high : float
        The slowest and the fastest speed found to paint [m/s].
    resolution : float
        The relative bracket each end was bisected to.
    low_bound, high_bound : str
        What stops the run there: ``"budget floor"`` (the path's sample budget, slower),
        ``"too slow: <why>"`` / ``"too fast: <why>"`` (the plan's failure beyond the end),
        or ``"searched no further"`` (every speed tried planned).
    low_plan, high_plan : object
        The plans at ``low`` and ``high``.
    """

    low: float
    high: float
    resolution: float
    low_bound: str
    high_bound: str
    low_plan: object = field(default=None, repr=False, compare=False)
    high_plan: object = field(default=None, repr=False, compare=False)

    def said(self) -> str:
        """The interval in words: ``"0.0031–0.0402 m/s"``."""
        return f"{self.low:.4g}–{self.high:.4g} m/s"

    def table(self) -> dict:
        """paint.json's ``line.speeds`` (:class:`pollard_pin.outputs.sections.LineSpeeds`)."""
        return {"min": self.low, "max": self.high, "resolution": self.resolution,
                "min_bound": self.low_bound, "max_bound": self.high_bound}


def constraint(why: str) -> str:
    """The constraint a :class:`LineSpeedError`'s ``why`` names: ``"reach"``, ``"motors"``,
    ``"reach and motors"`` (no turnaround keeps both), ``"clearance"``, ``"film"``, or
    ``""`` when its words name none."""
    low = why.lower()
    return next((name for word, name in _CONSTRAINTS if word in low), "")


def _bound(exc: LineSpeedError) -> str:
    side = "too fast" if exc.too_fast else "too slow"
    return f"{side}: {exc.why}" if exc.why else side


def fastest_line_speed(plan_at, start: float, source: str,
                       resolution: float = SPEED_RESOLUTION):
    """The fastest line speed [m/s] (within ``resolution``, relative) at which
    ``plan_at(speed)`` plans, and that plan (docs/model.md §24): from ``start`` (the job's
    speed), halved while too fast and doubled while too slow (or sent to the failure's
    ``hint``, the speed of no drift, if further) until one plans, then doubled until one
    fails, then bisected. Only :class:`LineSpeedError` counts as a failure."""
    with ticking("line speed search", "plan") as tick:  # a bar on a terminal, if asked
        return _fastest(lambda s: (tick(), plan_at(s))[1], start, source, resolution)


def _fastest(plan_at, start: float, source: str, resolution: float):
    lo, plan, _ = _find(plan_at, start, source, resolution)
    lo, plan, _ = _climb(plan_at, lo, plan, resolution)
    return lo, plan


def remembering(plan_at):
    """``plan_at`` (speed ↦ plan) with a memory of the speeds it refused: a speed refused
    once (a :class:`LineSpeedError`) is refused again in the same words without planning
    (the plan is the same every time)."""
    failed = {}  # speed → its refusal, kept (errors.kept: no frames held)

    def plan(speed):
        key = float(speed)
        if key in failed:
            raise made_again(failed[key])
        try:
            return plan_at(speed)
        except LineSpeedError as exc:
            failed[key] = kept(exc)
            raise

    return plan


def _find(plan_at, start: float, source: str, resolution: float):
    """(a speed that plans, its plan, the fastest too slow tried or 0 and its bound): from
    ``start``, halved while too fast, doubled (or sent to the hint) while too slow, bisected
    when both sides are known; none: the :class:`PlanError` naming both sides."""
    s = start
    best = None
    slow, fast = 0.0, math.inf  # the fastest too slow and the slowest too fast tried
    why = {True: "", False: ""}
    binds = {True: "", False: ""}
    slow_bound = ""
    for _ in range(2 * SPEED_TRIES):  # a speed that works: the drift ≈ the part's length
        try:
            best = (s, plan_at(s))
            break
        except LineSpeedError as exc:
            why[exc.too_fast] = f" ({exc.why})" if exc.why else ""
            binds[exc.too_fast] = constraint(exc.why)
            hint = exc.hint
            if exc.too_fast:
                fast = s
            else:
                slow, slow_bound = s, _bound(exc)
        if fast < math.inf and slow > 0:
            if fast - slow <= resolution * slow:
                break
            s = 0.5 * (slow + fast)
        elif fast == math.inf:  # too slow: on to the speed of no drift if it is further
            s = max(2 * s, hint if hint is not None and hint < MAX_LINE_SPEED else 0.0)
        else:
            s = 0.5 * s
    if best is None:
        said = f"{source}: no line speed paints the part: too slow at {slow:.4g} m/s" \
               f"{why[False]}, too fast at {fast:.4g} m/s{why[True]}"
        named = [f"{w} ({b})" for w, b in (("slow", binds[False]), ("fast", binds[True])) if b]
        if binds[False] and binds[False] == binds[True]:  # no speed moves it off: say so
            named = [f"{binds[False]} on both sides"]
        tail = f"; binding: {', '.join(named)}" if named else ""
        raise PlanError(say_less(said + tail, said, f"{source}: no line speed paints the part: "
                                 f"too slow at {slow:.4g} m/s, too fast at {fast:.4g} m/s"
                                 f"{tail}"))
    return best[0], best[1], (slow, slow_bound)


def _climb(plan_at, lo: float, plan, resolution: float):
    """From ``lo`` that plans: doubled until a speed fails, then bisected; (the fastest that
    plans, its plan, what fails beyond it)."""
    hi = None
    bound = "searched no further"
    for _ in range(SPEED_TRIES):
        try:
            s2 = 2 * lo if hi is None else hi
            plan = plan_at(s2)
            lo = s2
        except LineSpeedError as exc:
            hi, bound = s2, _bound(exc)
            break
    if hi is None:
        return lo, plan, bound
    while (hi - lo) > resolution * lo:
        mid = 0.5 * (lo + hi)
        try:
            plan = plan_at(mid)
            lo = mid
        except LineSpeedError as exc:
            hi, bound = mid, _bound(exc)
    if plan.speed != lo:
        plan = plan_at(lo)
    return lo, plan, bound


def waits_bound(floor: float) -> str:
    """The slow end's bound when its plan waits at the turnarounds (docs/model.md §24.3)."""
    return f"waits: slower lines wait longer, down to the budget's floor ≈ {floor:.2g} m/s"


def budget_floor(points, budget: float) -> float | None:
    """The line speed [m/s] at which a path's samples reach ``budget``, from the two slowest
    plans' (speed, samples) ``points``: samples ≈ a + b/s (the hold before the part
    arrives grows as 1/s, the program does not; docs/model.md §24.3); None with fewer
    points or samples that do not grow."""
    if len(points) < 2:
        return None
    (s1, n1), (s2, n2) = points[-2:]
    b = (n2 - n1) / (1 / s2 - 1 / s1) if s1 != s2 else 0.0
    a = n1 - b / s1
    return b / (budget - a) if b > 0 and budget > a else None


def _descend(plan_at, hi: float, plan, slow: float, slow_bound: str, resolution: float,
             floor=None, budget=None):
    """From ``hi`` that plans, down to the slowest that plans: halved until a speed fails
    (unless ``slow``, a speed known to fail, > 0), then bisected; a :class:`BudgetError`
    fails as the budget's floor. ``floor(plan)``: where a plan waits at its turnarounds,
    the budget's floor it paints down to (else None): the search stops at the first such
    plan, since a slower line only waits longer (§24.1). ``budget(plan)``: (its path's
    samples, the budget) or None: the halving jumps to just above the floor the last two
    plans put it at (:func:`budget_floor`), and the bisection first tries just above the
    failure found there (§24.3). (The slowest that plans, its plan, what fails below it.)"""
    if floor is not None and (f := floor(plan)) is not None:
        return hi, plan, waits_bound(f)
    bound = slow_bound if slow > 0 else "searched no further"

    def tried(s):
        nonlocal bound
        try:
            return plan_at(s)
        except LineSpeedError as exc:
            bound = _bound(exc)
        except BudgetError:
            bound = BUDGET_FLOOR
        return None

    def counted(p):
        return None if budget is None else budget(p)

    guided = False  # the last speed tried was the guide's, not a halving
    if slow <= 0:
        bottom = hi * 0.5**SPEED_TRIES  # 12 halvings at most, as without a guide
        points = [] if (n := counted(plan)) is None else [(hi, n[0])]
        for _ in range(SPEED_TRIES):
            est = budget_floor(points, n[1]) if n is not None else None
            s, guided = 0.5 * hi, est is not None
            if guided:  # just above the floor put, or just below hi if the floor is above
                target = est * (1 + 0.5 * resolution)
                s = max(target, bottom) if target < hi else hi / (1 + 0.99 * resolution)
            p = tried(s)
            if p is None:
                slow = s
                break
            if guided and floor is not None and floor(p) is not None:
                # waits begin above the jump: the first halving that waits, as unguided
                return _descend(plan_at, hi, plan, 0.0, "", resolution, floor)
            if guided and s >= 0.5 * hi and est * (1 + 0.5 * resolution) >= hi:
                n = None  # the floor was put too high: halve from here on
            hi, plan = s, p
            if n is not None and (m := counted(plan)) is not None:
                points.append((hi, m[0]))
            if floor is not None and (f := floor(plan)) is not None:
                return hi, plan, waits_bound(f)
            if hi <= bottom * (1 + 1e-9):
                return hi, plan, bound
        else:
            return hi, plan, bound
    fails = bound
    while (hi - slow) > resolution * slow:
        mid = 0.5 * (slow + hi)
        if guided:  # the guide's failure is just below the floor: try just above it first
            mid, guided = slow * (1 + 0.99 * resolution), False
        p = tried(mid)
        if p is None:
            slow, fails = mid, bound
        else:
            hi, plan = mid, p
    return hi, plan, fails


def line_speed_interval(plan_at, start: float, source: str,
                        resolution: float = INTERVAL_RESOLUTION, check=None,
                        slow_resolution: float | None = None, floor=None,
                        budget=None) -> SpeedInterval:
    """The line speeds that paint the job (docs/model.md §24.3): the run of speeds about
    ``start`` (the job's) that ``plan_at(speed)`` plans, each end bisected to ``resolution``
    (relative).

    If ``start`` does not plan, the first speed that does is found as
    :func:`fastest_line_speed` finds it. Up from there: doubled until a speed fails, then
    bisected (the fastest, as ``--max-line-speed`` finds it). Down: halved until a speed
    fails (or from the fastest too slow speed already tried), then bisected; a
    :class:`BudgetError` there (the path's samples past the budget: a slower line only
    waits longer) fails as the budget's floor, and the end says ``"budget floor"``. Only the
    speeds tried are planned: the interval is the run the bracketing finds, not a proof that
    every speed inside paints.

    Parameters
    ----------
    plan_at : Callable
        speed [m/s] ↦ the job's plan at that speed (with a ``speed`` attribute); raises
        :class:`LineSpeedError` where that speed does not paint.
    start : float
        The speed to start from [m/s].
    source : str
        The job's file, for the messages.
    resolution : float, optional
        Each end's relative bracket (default 5 %).
    check : Callable or None, optional
        ``check(plan)`` → the plan, checked in full (the clearance): run on both ends, as
        ``--max-line-speed`` checks its answer; its errors are raised.
    slow_resolution : float or None, optional
        The slow end's bracket if another (default ``resolution``); the interval states the
        coarser.
    floor : Callable or None, optional
        ``floor(plan)`` → where the plan waits at its turnarounds, the sample budget's floor
        [m/s] it paints down to (a slower line only waits longer), else None: the slow end
        is then the first plan that waits, its bound saying so (not planned further).
    budget : Callable or None, optional
        ``budget(plan)`` → (its path's samples, the sample budget), or None: the slow search
        jumps to just above the floor where the samples reach the budget, put from the last
        two plans (:func:`budget_floor`), instead of halving down to it.

    Returns
    -------
    SpeedInterval
        The ends, their bounds and their plans.

    Raises
    ------
    PlanError
        No speed paints the job (both sides named, and the constraint that binds each).
    """
    with ticking("line speed interval", "plan") as tick:
        def planned(s):
            tick()
            return plan_at(s)

        s, plan, (slow, slow_bound) = _find(planned, start, source, resolution)
        slow_res = resolution if slow_resolution is None else slow_resolution
        low, low_plan, low_bound = _descend(planned, s, plan, slow, slow_bound, slow_res,
                                            floor, budget)
        high, high_plan, high_bound = _climb(planned, s, plan, resolution)
    if check is not None:
        low_plan, high_plan = check(low_plan), check(high_plan)
    return SpeedInterval(low, high, max(resolution, slow_res), low_bound, high_bound,
                         low_plan, high_plan)


def plan_or_name_fastest(plan_at, speed: float, source: str, floor=None, name: bool = True,
                         budget=None):
    """``plan_at(speed)``; a speed that cannot be painted is refused naming the interval of
    speeds that do (:func:`line_speed_interval`: the fastest to :data:`SPEED_RESOLUTION`, as
    ``--max-line-speed`` finds it, the slowest to :data:`INTERVAL_RESOLUTION`, ``floor`` and
    ``budget`` as there), or, if none does, both sides and the constraint that binds each;
    ``name`` False: that speed's own :class:`LineSpeedError`, no other speed planned
    (docs/model.md §31.5)."""
    try:
        return plan_at(speed)
    except LineSpeedError as exc:
        if not name:
            raise
        try:
            found = line_speed_interval(plan_at, speed, source, SPEED_RESOLUTION,
                                        slow_resolution=INTERVAL_RESOLUTION, floor=floor,
                                        budget=budget)
        except PlanError as none:
            said = str(none).removeprefix(f"{source}: ")
            if isinstance(none, BudgetError):  # halved down to the floor, none painting
                said = "no slower line paints it, down to the sample budget's floor"
            raise PlanError(say_less(f"{source}: {exc}; {said}", f"{source}: at line speed "
                                     f"{speed:.4g} m/s {exc.why}; {said}", str(none))) from None
        slower = " or slower" if found.low_bound.startswith("waits") else ""
        paints = f"it paints at {found.said()}{slower} (--max-line-speed)"
        raise PlanError(say_less(f"{source}: {exc}; {paints}", f"{source}: at line speed "
                                 f"{speed:.4g} m/s {exc.why}; {paints}", f"{source}: line "
                                 f"speed {speed:.4g} m/s: {paints}")) from None


__all__ = ["BUDGET_FLOOR", "INTERVAL_RESOLUTION", "SPEED_RESOLUTION", "SPEED_TRIES",
           "SpeedInterval", "budget_floor", "constraint", "fastest_line_speed",
           "line_speed_interval", "plan_or_name_fastest", "remembering", "waits_bound"]
