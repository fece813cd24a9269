"""The study's first generation (docs/model.md §31.5): a ladder of designs judged by the screen
alone (milliseconds each), the best of them handed to the full stage as the study's first
designs.

NSGA-II's first generation is random. In the example's ten dimensions the designs that paint
the door with one robot are a thin slab: both length factors near 1.7 together, a base motor
strong enough and the robot standing about 0.3 m back; a random generation of 24, and the
generations bred from it, rarely land in it. The ladder walks the space along what decides a
design's reach and its motors instead:

* every shared length factor (``scale.*``) at the same fraction of its range, in
  :data:`LEVELS` steps (the space's length factors grown together);
* the robots' place (``place.back``) in :data:`BACK_LEVELS` steps over its range;
* the thesis robot's motors, and each catalogue motor of one motor group at a time (``motor.G``
  set to each of its choices, every other choice the thesis robot's);
* the robot count from the space's fewest up, to the first the screen passes (``robots``;
  skipping to the screen's ``robots_needed`` figure when it gives one), a design the screen
  rejects for another reason than its reach left out.

Of the designs the screen passes, the fewest robots first; among those, one design of each
choice of motors in turn (lightest first: the lightest of each, then the second lightest of
each, …), so that the first generation spreads over the motors rather than piling onto one.
:func:`seeds` returns them; the study enqueues them once, after the thesis robot, when it
starts (a resumed study never enqueues them again: those not yet evaluated wait in its file).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from .backends import make_runner

LEVELS = 9  # length-factor steps over the range ([1, 1.8]: 0.1 apart)
BACK_LEVELS = 5  # place steps over the range ([0, 0.4] m: 0.1 m apart)


def ladder(variables: Sequence, base: Mapping[str, Any]) -> list[dict]:
    """The ladder's designs (the robot count the fewest; :func:`screened` raises it).

    Parameters
    ----------
    variables : Sequence
        The design variables (``name``, ``low``, ``high``, ``kind``, ``choices``).
    base : Mapping
        The thesis robot's values (:func:`~pollard_pin.synthesis.evaluation.baseline_values`).

    Returns
    -------
    list of dict
        A value per variable for each design, distinct, the thesis robot's left out.
    """
    scales = [v for v in variables if v.name.startswith("scale.")]
    back = next((v for v in variables if v.name == "place.back"), None)
    robots = next((v for v in variables if v.name == "robots"), None)
    fractions = np.linspace(0.0, 1.0, LEVELS) if scales else [None]
    backs = np.linspace(back.low, back.high, BACK_LEVELS) if back is not None else [None]
    choices: list[dict] = [{}] + [{m.name: k} for m in variables
                                  if m.name.startswith("motor.") and m.kind == "categorical"
                                  for k in range(len(m.choices)) if k != base.get(m.name)]
    out, seen = [], {_key(base)}
    for t in fractions:
        for b in backs:
            for c in choices:
                v = dict(base)
                if t is not None:
                    v.update({s.name: round(float(s.low + t * (s.high - s.low)), 9)
                              for s in scales})
                if b is not None:
                    v["place.back"] = round(float(b), 9)
                if robots is not None:
                    v["robots"] = int(robots.low)
                v.update(c)
                if _key(v) not in seen:
                    seen.add(_key(v))
                    out.append(v)
    return out


def _key(values: Mapping) -> tuple:
    return tuple(sorted((k, repr(v)) for k, v in values.items()))


def screened(designs: Sequence[dict], variables: Sequence, ctx, evaluate: Callable,
             workers: int | None = None, dask: Any = None) -> list[tuple[dict, Any]]:
    """Each design screened at the robot counts from its own up, to the first the screen
    passes: (values, the screen's evaluation) of those it passes, in the designs' order.

    Parameters
    ----------
    designs : Sequence of dict
        The designs (:func:`ladder`).
    variables : Sequence
        The design variables (the ``robots`` one's range, if free).
    ctx : object
        The prepared context.
    evaluate : Callable
        ``evaluate(values, ctx, level)``.
    workers, dask : optional
        Where the screens run (:func:`~pollard_pin.synthesis.backends.make_runner`).

    Returns
    -------
    list of (dict, Evaluation)
        The designs the screen passes (robot count set) and their screens.
    """
    robots = next((v for v in variables if v.name == "robots"), None)
    most = int(robots.high) if robots is not None else None
    passed: dict[int, tuple[dict, Any]] = {}
    pending = list(enumerate(dict(d) for d in designs))
    inflight: dict[int, dict] = {}
    with make_runner(ctx, evaluate, workers, dask) as runner:
        while pending or inflight:
            while pending and len(inflight) < runner.capacity:
                k, values = pending.pop(0)
                inflight[k] = values
                runner.submit(k, values, "screen")
            for k, outcome in runner.done():
                values = inflight.pop(k)
                if isinstance(outcome, BaseException):
                    continue  # a design the evaluator cannot judge: not a seed
                ev = outcome.final
                if ev.feasible:
                    passed[k] = (values, ev)
                elif most is not None and ev.binding == "reach" and values["robots"] < most:
                    need = int((ev.figures or {}).get("robots_needed") or 0)
                    n = max(values["robots"] + 1, need)
                    if n <= most:  # more robots: shorter zones (docs/model.md §31.3)
                        pending.append((k, {**values, "robots": n}))
    return [passed[k] for k in sorted(passed)]


def seeds(passed: Sequence[tuple[dict, Any]], count: int) -> list[dict]:
    """The first ``count`` designs of the screened ladder in the order the module's help
    gives: the fewest robots first, and among them each choice of motors in turn, lightest
    first.

    Parameters
    ----------
    passed : Sequence of (dict, Evaluation)
        The designs the screen passes (:func:`screened`).
    count : int
        How many.

    Returns
    -------
    list of dict
        Their values.
    """
    groups: dict[tuple, list] = {}
    for values, ev in passed:
        motors = tuple((k, v) for k, v in sorted(values.items())
                       if k.startswith(("motor.", "ratio.")))
        o = ev.objectives
        groups.setdefault((o["robots"], motors), []).append(
            ((o["moving_mass"], o["motor_use"]), values))
    for members in groups.values():
        members.sort(key=lambda m: m[0])
    order = sorted(groups, key=lambda g: (g[0], groups[g][0][0]))
    out: list[dict] = []
    for robots in dict.fromkeys(g[0] for g in order):  # fewest first
        mine = [groups[g] for g in order if g[0] == robots]
        for rank in range(max(len(m) for m in mine)):  # each motor choice in turn
            out += [m[rank][1] for m in mine if rank < len(m)]
    return out[:count]


def first_generation(variables: Sequence, base: Mapping, ctx, evaluate: Callable,
                     count: int, workers: int | None = None, dask: Any = None
                     ) -> tuple[list[dict], str]:
    """The ladder screened and its best ``count`` designs (:func:`seeds`), with a line
    saying how many the screen passed.

    Parameters
    ----------
    variables : Sequence
        The design variables.
    base : Mapping
        The thesis robot's values.
    ctx : object
        The prepared context.
    evaluate : Callable
        ``evaluate(values, ctx, level)``.
    count : int
        How many designs to hand to the full stage.
    workers, dask : optional
        Where the screens run.

    Returns
    -------
    tuple of (list of dict, str)
        The designs, and the line.
    """
    designs = ladder(variables, base)
    if count < 1 or not designs:
        return [], "no ladder"
    passed = screened(designs, variables, ctx, evaluate, workers, dask)
    passed = [(v, ev) for v, ev in passed if v != dict(base)]  # the thesis robot: first already
    chosen = seeds(passed, count)
    fewest = min((ev.objectives["robots"] for _, ev in passed), default=None)
    return chosen, (f"the ladder: {len(designs)} designs screened, {len(passed)} passed"
                    + (f" (the fewest robots {fewest:.0f})" if fewest is not None else "")
                    + f", the first {len(chosen)} planned first")


__all__ = ["BACK_LEVELS", "LEVELS", "first_generation", "ladder", "screened", "seeds"]
