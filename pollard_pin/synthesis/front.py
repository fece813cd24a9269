"""The Pareto front of a design study, the chosen design and what each front design gains
against the thesis robot. Plain functions of the evaluations' numbers: no optimiser here.

A design ``a`` dominates ``b`` when it is at least as good in every objective and better in
one (each objective by its sense: more parts per hour, fewer robots, a lower worst motor use, a
higher ``kmin``, less moving mass). The front is the feasible designs no feasible design
dominates, each design once.

The reported front is its ε-front (:func:`epsilon_front`, :class:`FrontResolution`,
docs/model.md §31.5): designs closer than each objective's resolution are one box, shown once.

The chosen design (:func:`choose`), unless the caller picks a front row: among the front
designs whose worst motor use is at most :data:`MOTOR_USE_LIMIT`, the fewest robots, then the
most parts per hour, then the least moving mass (when no front design keeps that margin: the
same rule over the whole front). The front's rows are in that order too, so the chosen design
is the first row that keeps the margin.
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields

from ..checks import real
from ..errors import InputError
from .evaluation import SENSES as OBJECTIVE_SENSES

MOTOR_USE_LIMIT = 0.9  # the margin a chosen design keeps on its busiest motor
# The objectives' senses as signs (+1: more is better), in the study's order
SENSES = {n: 1 if s == "max" else -1 for n, s in OBJECTIVE_SENSES.items()}

def dominates(a: Mapping, b: Mapping, senses: Mapping[str, int] = SENSES) -> bool:
    """Whether objectives ``a`` dominate ``b`` (no worse in any, better in one)."""
    better = False
    for name, sense in senses.items():
        da, db = sense * a[name], sense * b[name]
        if da < db:
            return False
        better |= da > db
    return better


def non_dominated(rows: Sequence[Mapping], senses: Mapping[str, int] = SENSES) -> list[int]:
    """Indices of the rows (objective mappings) no other row dominates; of rows with equal
    objectives, the first only.

    Parameters
    ----------
    rows : Sequence of Mapping
        Each row's objectives (name → value), every one finite.
    senses : Mapping, optional
        name → +1 (more is better) or -1 (less is better).

    Returns
    -------
    list of int
        The front's row indices, in input order.
    """
    keep = []
    for i, a in enumerate(rows):
        if any(dominates(b, a, senses) for j, b in enumerate(rows) if j != i):
            continue
        if any(all(rows[k][n] == a[n] for n in senses) for k in keep):
            continue  # the same figures twice: one row
        keep.append(i)
    return keep


@dataclass(frozen=True)
class FrontResolution:
    """How far apart two designs' objectives must be for the reported front to tell them
    apart (docs/model.md §31.5: each default's reason). Each objective's axis is cut into
    boxes of this size (relative: boxes of equal ratio; absolute: of equal width); the
    robots are counted, never boxed. All 0: the exact front. Checked once.

    Attributes
    ----------
    parts_per_hour : float
        Relative, in [0, 1] (default 0.01: 1 %).
    motor_use : float
        Absolute, in [0, 1] (default 0.01).
    kmin : float
        Relative, in [0, 1] (default 0.1: 10 %).
    moving_mass : float
        Relative, in [0, 1] (default 0.02: 2 %).
    """

    parts_per_hour: float = 0.01
    motor_use: float = 0.01
    kmin: float = 0.1
    moving_mass: float = 0.02

    RELATIVE = ("parts_per_hour", "kmin", "moving_mass")  # class constant (no annotation)

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, real(
                getattr(self, f.name), f"FrontResolution.{f.name}", 0.0, 1.0,
                why=" (a resolution in [0, 1])"))

    def described(self) -> dict:
        """Each objective's resolution as front.csv's metadata keeps it: ``{"relative": x}``
        or ``{"absolute": x}`` (the robots: absolute 0, counted)."""
        out = {}
        for name in SENSES:
            kind = "relative" if name in self.RELATIVE else "absolute"
            out[name] = {kind: getattr(self, name, 0.0)}
        return out

    def phrase(self) -> str:
        """The summary's words: ``" (one per box of parts/h 1 %, …)"``; none when exact."""
        out = [f"{name.replace('_', ' ').replace('parts per hour', 'parts/h')} "
               + (f"{100 * eps:g} %" if name in self.RELATIVE else f"{eps:g}")
               for name in SENSES if (eps := getattr(self, name, 0.0))]
        return f" (one per box of {', '.join(out)})" if out else ""

    def box(self, objectives: Mapping) -> dict:
        """The box ``objectives`` fall in: name → its index along each objective (0
        resolution: the figure itself; a relative one's figure at or below 0: a box below
        every other), compared as figures are (``dominates``)."""
        out = {}
        for name in SENSES:
            v, eps = objectives[name], getattr(self, name, 0.0)
            if eps == 0:
                out[name] = v
            elif name not in self.RELATIVE:
                out[name] = math.floor(v / eps)
            else:
                out[name] = math.floor(math.log(v) / math.log1p(eps)) if v > 0 else -math.inf
        return out


EXACT = FrontResolution(0.0, 0.0, 0.0, 0.0)  # the plain Pareto front


def epsilon_front(rows: Sequence[Mapping], resolution: FrontResolution = EXACT) -> list[int]:
    """The rows' ε-front (ε-box dominance, Laumanns et al. 2002): the front's rows
    (:func:`non_dominated`) in boxes of ``resolution``; of a box that no other box dominates
    (no worse in every objective's box, better in one, by the objectives' senses), the row
    :func:`rank_key` puts first (the first in input order on a tie); and always the row
    :func:`choose` takes from the whole front. Every front row is then within one box of a
    kept one in every objective, no worse beyond it; all resolutions 0: the front itself.

    Parameters
    ----------
    rows : Sequence of Mapping
        Each row's objectives (name → value), every one finite.
    resolution : FrontResolution, optional
        The boxes (default: none, the exact front).

    Returns
    -------
    list of int
        The kept row indices, in input order.
    """
    front = non_dominated(rows)
    if not front:
        return []
    boxes = {i: resolution.box(rows[i]) for i in front}
    first: dict[tuple, int] = {}  # a box (its indices) → the row rank_key puts first in it
    for i in front:
        b = tuple(boxes[i].values())
        if b not in first or rank_key(rows[i]) < rank_key(rows[first[b]]):
            first[b] = i
    kept = {i for i in first.values()
            if not any(dominates(boxes[j], boxes[i]) for j in first.values())}
    kept.add(min(front, key=lambda i: rank_key(rows[i])))  # choose's row, whatever its box
    return sorted(kept)


def rank_key(objectives: Mapping) -> tuple:
    """The order of the front's rows and of :func:`choose`: within the motor-use margin
    first, then the fewest robots, the most parts per hour, the least moving mass."""
    return (objectives["motor_use"] > MOTOR_USE_LIMIT, objectives["robots"],
            -objectives["parts_per_hour"], objectives["moving_mass"])


def choose(front: Sequence[Mapping], pick: int | None = None) -> int:
    """The index of the chosen design in ``front`` (rows in :func:`rank_key` order).

    Parameters
    ----------
    front : Sequence of Mapping
        The front's objectives, in :func:`rank_key` order.
    pick : int or None, optional
        The front row to choose, counted from 1 (None: the rule of the module's docstring,
        which is then row 1).

    Returns
    -------
    int
        The chosen row's index (0-based).

    Raises
    ------
    InputError
        An empty front, or ``pick`` outside it.
    """
    if not front:
        raise InputError("the study found no feasible design: there is nothing to choose")
    if pick is None:
        return min(range(len(front)), key=lambda i: rank_key(front[i]))
    if not 1 <= pick <= len(front):
        raise InputError(f"--pick {pick}: the front has {len(front)} designs (1.."
                         f"{len(front)})")
    return pick - 1


def _figure(name: str, value: float) -> str:
    if name == "robots":
        return f"{value:.0f} robot{'s' if value != 1 else ''}"
    if name == "kmin":
        return f"kmin {value:.3g} N/m"
    if name == "parts_per_hour":
        return f"{value:.4g} parts/h"
    if name == "motor_use":
        return f"motor use {value:.2f}"
    return f"moving mass {value:.3g} kg"


def _change(name: str, value: float, base: float) -> str:
    if name == "robots" or name == "motor_use":
        return f"{value - base:+.{0 if name == 'robots' else 2}f}"
    if base == 0 or not math.isfinite(base):
        return f"{value - base:+.3g}"
    return f"{100 * (value - base) / abs(base):+.0f} %"


def gains(objectives: Mapping, baseline: Mapping | None) -> str:
    """What a design gains (and gives up) against the baseline, one phrase per objective:
    ``1 robot (-1), 212 parts/h (+18 %), …``; the design's own figures when there is no
    feasible baseline.

    Parameters
    ----------
    objectives : Mapping
        The design's objectives.
    baseline : Mapping or None
        The thesis robot's objectives, or None (it cannot paint the job).

    Returns
    -------
    str
        The phrases, joined by commas.
    """
    out = []
    for name in SENSES:
        text = _figure(name, objectives[name])
        if baseline is not None:
            text += f" ({_change(name, objectives[name], baseline[name])})"
        out.append(text)
    return ", ".join(out)
