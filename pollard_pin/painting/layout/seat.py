"""The robots at a proposed cell's edges seated by their plans (docs/model.md §26.5, "Seating
the end robots").

A proposal places each robot by its band (:mod:`.layout.cell`); at a bent edge the band says
where a robot reaches, not where its motors follow the passes (a robot moved onto a bevel
holds its need with millimetres spare, its ramps and turnarounds in the bevel's averaging,
and the robot below it paints up into that averaging). So before the cell is planned every
robot's program is planned alone at the job's line speed (the program the cell's plan then
takes: :func:`.cell.plan.plan_cell` remembers it within
:func:`.cell.plan.zone_plans_remembered`). Where only the robots of an edge pair (an
end robot along the cell's axis and its neighbour) are refused, the pair is seated:

1. the seam between them moved inwards (away from the edge) STEP at a time until the
   neighbour plans its shortened zone (at most SEAT_TRIES steps, the zone kept longer than a
   step);
2. the end robot moved outwards (towards its edge) STEP at a time, from where it stands, until
   it plans its zone from that seam (at most SEAT_TRIES steps): the seam stays while the
   moved band holds it with the run past a seam (``PlannerPolicy.seam_run``, else R), else
   moves out with the band (its lowest, or highest, held seam), the neighbour then planned
   again, as long as the neighbour's band still holds it with that run; a move past the
   edge's need ends the search.

Guarantee: in the seated layout every robot plans its zone alone at the job's line speed (the
same programs the cell's plan is made of, with the seams returned), every moved seam lies in
both neighbours' bands with the run past it, and the film at a seam is the split's (§26.3: the
trigger closes at the seam). The cell's own checks (the clearances between robots, the film)
still decide. Where a middle robot is refused, or an edge pair cannot be seated, the layout is
returned as proposed: the cell's plan then refuses it as before.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..cell.bands import STEP, job_strokes, robot_band
from ..cell.plan import plan_cell, zone_plans_remembered
from ..cell.split import EDGE_TOL, split_cell
from ..errors import BudgetError, PlanError

SEAT_TRIES = 6  # STEP moves of a seam, and of an end robot, at most (30 mm: a bevel's room)


def plans_alone(robot, job, cell_robot, act, split, part, policy) -> PlanError | None:
    """None if ``cell_robot`` plans its zone of ``split`` at the job's line speed, else the
    refusal (the cell's plan remembers the program: planned once)."""
    try:
        plan_cell(robot, replace(job, robots=(cell_robot,)), act, None, part, split,
                  clearance=False, policy=policy)
    except BudgetError:
        raise
    except PlanError as exc:
        return exc
    return None


def seat_ends(robot, job, act, policy, part=None):
    """(robots, seams): the job's robots with each refused edge pair seated (module
    docstring), and the seams of the robots facing the job's side (None: nothing moved,
    the robots as given).

    Parameters
    ----------
    robot : Robot
        The model every robot shares.
    job : PaintJob or pollard_pin.painting.job.PartJob
        A job with ``[line]`` and its proposed ``robots``.
    act : Actuators
        The motor ratings.
    policy : PlannerPolicy
        The planner's knobs (its ``seams``, if set, are where the seams start).
    part : object or None, optional
        The job's painted part if already read.
    """
    from ..job import PartJob
    from ..spray.occlusion import load_painted_part

    robots = tuple(job.robots)
    if len(robots) < 2:
        return robots, None
    if part is None and isinstance(job, PartJob):
        part = load_painted_part(job)
    split = split_cell(robot, job, robots, part, policy.seams, policy)
    zones = sorted((z for z in split.zones if z.facing is None), key=lambda z: z.lo)
    if len(zones) < 2:
        return robots, None
    side = [z.robot for z in zones]
    refused = {r.name for r in robots
               if plans_alone(robot, job, r, act, split, part, policy) is not None}
    # (end robot, its neighbour, their seam's index, the end is the top one)
    pairs = [(side[0], side[1], 0, False), (side[-1], side[-2], len(side) - 2, True)]
    if len(side) == 2:  # one seam: the pair whose end is refused (the top one first)
        pairs = [p for p in pairs[::-1] if p[0] in refused][:1] or pairs[1:]
    if not refused or not refused <= {n for p in pairs for n in p[:2]}:
        return robots, None  # all plan, or a middle robot is refused: the cell says why
    cell = {r.name: r for r in robots}
    seams = [z.hi for z in zones[:-1]]
    search = _Search(robot, job, act, policy, part,
                     replace(job_strokes(job, part), seam_run=policy.seam_run), refused)
    for end, nb, j, top in pairs:
        if refused & {end, nb}:
            found = search.seat(cell, end, nb, seams, j, top)
            if found is None:
                return robots, None
            cell[end], seams = found
    return tuple(cell[r.name] for r in robots), tuple(seams)


class _Search:
    """An edge pair's search (module docstring, steps 1 and 2)."""

    def __init__(self, robot, job, act, policy, part, strokes, refused: set):
        self.robot, self.job, self.act, self.policy = robot, job, act, policy
        self.part, self.strokes, self.refused = part, strokes, refused
        self.run = strokes.past_seam

    def plans(self, cell: dict, name: str, seams) -> bool:
        robots = tuple(cell.values())
        job = replace(self.job, robots=robots)
        split = split_cell(self.robot, job, robots, self.part, tuple(seams), self.policy)
        return plans_alone(self.robot, job, cell[name], self.act, split, self.part,
                           replace(self.policy, seams=tuple(seams))) is None

    def seat(self, cell: dict, end: str, nb: str, seams: list, j: int, top: bool):
        """(the end robot seated, the seams) or None."""
        out = 1.0 if top else -1.0  # the end robot's way out; its seam moves back
        seams = list(seams)
        e_lo, e_hi = self.strokes.extent
        inner = ((seams[j - 1] if j > 0 else e_lo) if top else
                 (seams[j + 1] if j + 1 < len(seams) else e_hi))  # the neighbour's far end
        moved_seam = 0
        ok = nb not in self.refused
        while not ok:  # 1. the seam inwards until the neighbour plans
            moved_seam += 1
            seams[j] -= out * STEP
            if moved_seam > SEAT_TRIES or (seams[j] - inner) * out <= STEP:
                return None
            ok = self.plans(cell, nb, seams)
        s = seams[j]
        need_lo, need_hi = self.strokes.needed(-math.inf, math.inf)
        nb_band = robot_band(self.robot, cell[nb], self.strokes)
        axis = np.asarray(self.strokes.axis, float)
        base = cell[end]
        for k in range(SEAT_TRIES + 1):  # 2. the end robot outwards until it plans
            moved = replace(base, base=tuple(round(float(c), 6) + 0.0 for c in
                                             base.origin + out * k * STEP * axis))
            band = robot_band(self.robot, moved, self.strokes)
            if band.empty:
                return None
            held = band.holding(hi=need_hi) if top else band.holding(lo=need_lo)
            if (held.hi < need_hi - EDGE_TOL) if top else (held.lo > need_lo + EDGE_TOL):
                return None  # moved past its edge's need
            at = max(s, held.lo + self.run) if top else min(s, held.hi - self.run)
            if ((at > nb_band.hi - self.run + EDGE_TOL) if top else
                    (at < nb_band.lo + self.run - EDGE_TOL)):
                return None  # the neighbour no longer holds the seam with its run
            trial = [*seams[:j], at, *seams[j + 1:]]
            if k == 0 and at == s and end not in self.refused and not moved_seam:
                return moved, trial
            placed = {**cell, end: moved}
            if self.plans(placed, end, trial) and (at == s or self.plans(placed, nb, trial)):
                return moved, trial
        return None


def paint_seated(robot, job, robots, actuators=None, options=None, part=None):
    """(robots, PaintedJob): the job painted with the proposed ``robots``, its refused edge
    pairs first seated (:func:`seat_ends`; at the job's line speed only, not with
    ``options.max_line_speed``), their seams then the policy's (``PlannerPolicy.seams``)."""
    from ..api import default_actuators, paint_job
    from ..options import PaintOptions

    options = options or PaintOptions()
    job = replace(job, robots=tuple(robots))
    with zone_plans_remembered():  # the search's programs are the cell's: planned once
        if not options.max_line_speed:
            act = default_actuators(job) if actuators is None else actuators
            seated, seams = seat_ends(robot, job, act, options.policy, part)
            if seams is not None:
                job = replace(job, robots=seated)
                options = replace(options, policy=replace(options.policy, seams=seams))
        return job.robots, paint_job(robot, job, actuators, options)


__all__ = ["SEAT_TRIES", "paint_seated", "plans_alone", "seat_ends"]
