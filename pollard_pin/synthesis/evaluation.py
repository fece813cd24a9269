"""One design judged against a paint job (docs/model.md §31.3): the cheap screen, then the
full plan (paint, film, motors, cycle, stiffness), as an :class:`Evaluation` that never
raises for a design that cannot paint: it is infeasible, and says which constraint binds.

Objectives (:data:`OBJECTIVES`, senses :data:`SENSES`):

* ``parts_per_hour`` (max): the cell's parts per hour at the job's line speed (a job without
  a line: 3600 / cycle time);
* ``robots`` (min): the robots in the cell;
* ``motor_use`` (min): the worst motor's use of its rating (peak torque, RMS torque or speed)
  over the program, any robot;
* ``kmin`` (max): the softest tip stiffness [N/m] over the program (docs/model.md §27), any
  robot;
* ``moving_mass`` (min): the cell's moving mass [kg] (every robot's links and the motors they
  carry), the cost proxy (``figures["price"]`` when the catalogue has prices).

Constraints (:data:`CONSTRAINTS`), each ≤ 0 when it holds, > 0 by how far it is off: ``home``
(the home pose reachable), ``reach`` (the zone's need beyond the band [m]), ``motors_static``
(the holding torque's use over 1), ``plan`` (1 when the planner refuses the job), ``motors``
(the worst use over 1), ``clearance`` (required minus least distance [m]) and ``film`` (0.99
minus the share of the area within ±5 % of the target).
"""
from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, PollardError
from ..model.build import load
from ..model.overrides import ParameterError
from ..outputs.result import paint
from ..painting.causes import binding_of
from ..painting.cell.bands import job_strokes
from ..painting.job import PartJob, load_job
from ..painting.line.notes import plan_notes
from ..painting.options import PaintOptions
from .concrete import Design, actuators_toml, build, params_toml
from .fidelity import SearchFidelity
from .layout import back_offset, placed_job
from .screen import held_poses, motors, panel_reach, reach, turn_runon
from .space import DesignSpace

#: The objectives a design is judged by, in the order of :meth:`Evaluation.objective_vector`.
OBJECTIVES = ("parts_per_hour", "robots", "motor_use", "kmin", "moving_mass")
class _Senses(dict):
    """Each objective of :data:`OBJECTIVES` → its sense, "max" or "min" (a dict)."""


#: Each objective's sense: "max" or "min".
SENSES = _Senses({"parts_per_hour": "max", "robots": "min", "motor_use": "min", "kmin": "max",
          "moving_mass": "min"})
UNITS = {"parts_per_hour": "1/h", "robots": "", "motor_use": "", "kmin": "N/m",
         "moving_mass": "kg"}
#: The constraints, in the order of :meth:`Evaluation.constraint_vector` (≤ 0 holds).
CONSTRAINTS = ("home", "reach", "motors_static", "plan", "motors", "clearance", "film")
FILM_SHARE = 0.99  # of the area within ±5 % of the target (the acceptance, docs/model.md §31.3)
REFUSED = 0.01  # a constraint the planner's refusal names: this beyond what the screen saw
KMIN_SAMPLES = 400  # program samples kmin is taken over at most, evenly spread
LEVELS = ("screen", "search", "full")


@dataclass(frozen=True)
class Evaluation:
    """What one design scored (see the module's help for the names).

    Attributes
    ----------
    level : str
        ``"screen"``, ``"search"`` or ``"full"``: how far it was taken (``"search"``: planned,
        its checks at the search's fidelity).
    feasible : bool
        Every constraint ≤ 0.
    objectives : dict
        :data:`OBJECTIVES` → value (finite; an infeasible design's are its screen's, with
        parts per hour 0 and kmin 0 where not planned).
    constraints : dict
        Constraint → value, ≤ 0 holds (those computed at this level).
    binding : str or None
        The constraint that failed first (None: feasible).
    figures : dict
        Other numbers: band [m], robots needed, cycle [s], film, clearance, times [s], price.
    params_toml, actuators_toml, robots_toml : str or None
        The design's files (robots_toml: a cell's ``[[robot]]`` tables) after a full
        evaluation (None after the screen: :func:`design_files` writes them).
    message : str or None
        The planner's refusal, one line (None: none).
    notes : dict or None
        A planned design's notes (``level="search"``): the layout and what its line plans
        searched (:mod:`pollard_pin.painting.line.notes`), plain data, with which
        ``evaluate(values, ctx, "full", notes)`` plans the same design exactly without
        searching again (None: none).
    """

    level: str
    feasible: bool
    objectives: dict[str, float]
    constraints: dict[str, float]
    binding: str | None
    figures: dict[str, float]
    params_toml: str | None = None
    actuators_toml: str | None = None
    robots_toml: str | None = None
    message: str | None = None
    notes: dict | None = field(default=None, repr=False, compare=False)

    def objective_vector(self) -> tuple[float, ...]:
        """The objectives in :data:`OBJECTIVES` order (senses: :data:`SENSES`)."""
        return tuple(float(self.objectives[k]) for k in OBJECTIVES)

    def constraint_vector(self) -> tuple[float, ...]:
        """The constraints in :data:`CONSTRAINTS` order, ≤ 0 holds; one not computed at this
        level is 0 (an optimiser's constraint function: any > 0 is infeasible)."""
        return tuple(float(self.constraints.get(k, 0.0)) for k in CONSTRAINTS)


@dataclass(frozen=True, eq=False)
class DesignContext:
    """What every evaluation of a study shares, built once by :func:`prepare` (picklable: it
    is sent to the workers).

    Attributes
    ----------
    job : PaintJob or pollard_pin.painting.job.PartJob
        The paint job.
    space : DesignSpace
        The design space.
    strokes : pollard_pin.painting.cell.bands.Strokes or None
        The job's middle stroke, the screen's reach envelope, its run-on and run-out
        lengthened by the turnarounds' (:func:`~pollard_pin.synthesis.screen.turn_runon`;
        None: a job without a line).
    options : PaintOptions
        How the full evaluation paints.
    search : SearchFidelity or None
        How the search's evaluations (``level="search"``) plan (None: as the full ones).
    """

    job: Any
    space: DesignSpace
    strokes: Any
    options: PaintOptions = field(default_factory=PaintOptions)
    search: SearchFidelity | None = None


def prepare(job, space: DesignSpace, options: PaintOptions | None = None,
            search: SearchFidelity | None = None) -> DesignContext:
    """The :class:`DesignContext` of a job (a file's path, or a loaded job) and a space.

    Parameters
    ----------
    job : str or pathlib.Path or PaintJob or pollard_pin.painting.job.PartJob
        The paint job (a line job for a cell of robots).
    space : DesignSpace
        The design space.
    options : PaintOptions or None, optional
        How the full evaluation paints (default: no compliance pass, the film at σ/3).
    search : SearchFidelity or None, optional
        How the search's evaluations plan (default None: as the full ones).

    Returns
    -------
    DesignContext
        The job, the space, the job's strokes (the screen's reach envelope).

    Raises
    ------
    pollard_pin.errors.InputError
        A job that cannot be read, or a space with several robots and a job without a line.
    """
    if isinstance(job, (str, Path)):
        job = load_job(job)
    if space.robots[1] > 1 and job.line is None:
        raise InputError(f"{job.source}: a cell of robots needs the job's [line]; the space "
                         f"allows {space.robots[1]} robots")
    if job.robots:
        raise InputError(f"{job.source}: the design places the robots; drop the job's "
                         "[[robot]] tables")
    options = PaintOptions(compliance=False) if options is None else options
    strokes = None
    if job.line is not None:  # the screen's envelope: the middle stroke (docs/model.md §31.3)
        strokes = job_strokes(job)
        run = turn_runon(job)  # the turnarounds' and ramps' run-on past the passes' ends
        strokes = replace(strokes, samples=(strokes.samples[len(strokes.samples) // 2],),
                          run_on=strokes.run_on + run, runout=strokes.runout + run)
    if search is not None and not isinstance(search, SearchFidelity):
        raise InputError(f"search: expected a SearchFidelity or None, got "
                         f"{type(search).__name__}")
    return DesignContext(job, space, strokes, options, search)


def _objectives(design: Design | None, n: int, **known) -> dict[str, float]:
    mass = design.moving_mass * n if design is not None else math.inf
    out = {"parts_per_hour": 0.0, "robots": float(n), "motor_use": 10.0, "kmin": 0.0,
           "moving_mass": mass}
    out.update(known)
    return out


def _infeasible(level, design, n, constraints, binding, figures, message=None, **known):
    files = _files(design) if design is not None and level != "screen" else (None, None)
    return Evaluation(level, False, _objectives(design, n, **known), constraints, binding,
                      figures, *files, None, message)


def design_files(values: Mapping[str, Any], space: DesignSpace) -> tuple[str, str]:
    """The parameter and actuator files' texts of a design (``--params``, ``--actuators``).

    Parameters
    ----------
    values : Mapping
        The design's values.
    space : DesignSpace
        Its space.

    Returns
    -------
    tuple of str
        (params TOML, actuators TOML).
    """
    return _files(build(values, space))


def _files(design: Design) -> tuple[str, str]:
    return (params_toml(design, "a design of pollard-pin design (docs/model.md §31)"),
            actuators_toml(design, "the motors of a design of pollard-pin design "
                           "(docs/model.md §31)"))


def _screen(values, ctx: DesignContext):
    """(design, robot, Evaluation of the screen)."""
    space, t0 = ctx.space, time.perf_counter()
    n = space.robot_count(values)
    figures: dict[str, float] = {}
    try:
        design = build(values, space)
    except ParameterError as exc:
        figures["screen_s"] = time.perf_counter() - t0
        return None, None, _infeasible("screen", None, n, {"home": 1.0}, "home", figures,
                                       str(exc))
    if design.price is not None:
        figures["price"] = design.price * n
    cons = {"home": -1.0}
    back = space.place_back(values)
    try:
        robot = load(design.params)
        if ctx.strokes is not None:
            o = back_offset(ctx, back)
            strokes = replace(ctx.strokes, samples=tuple((w, tips + o, ax) for w, tips, ax
                                                         in ctx.strokes.samples))
            cons["reach"], more, band = reach(robot, strokes, n)
            figures.update(more)
            poses = None if band.empty else held_poses(robot, strokes, band)
            if poses is not None:
                cons["motors_static"], more = motors(robot, design.actuators, poses)
                figures.update(more)
        elif not isinstance(ctx.job, PartJob):  # a still panel: its poses in reach
            cons["reach"], more = panel_reach(robot, ctx.job)
            figures.update(more)
    except PollardError as exc:  # a model the package cannot build or solve: said
        figures["screen_s"] = time.perf_counter() - t0
        cons["reach"] = max(cons.get("reach", 0.0), 0.0) + REFUSED
        return design, None, _infeasible("screen", design, n, cons, "reach", figures,
                                         str(exc).split("\n")[0])
    figures["screen_s"] = time.perf_counter() - t0
    binding = next((k for k in CONSTRAINTS if cons.get(k, -1.0) > 0), None)
    use = max(figures.get("static_peak_use", 0.0), figures.get("static_rated_use", 0.0))
    ev = Evaluation("screen", binding is None,
                    _objectives(design, n, motor_use=use if use > 0 else 10.0), cons,
                    binding, figures)
    return design, robot, ev


def _kmin(robot, plans, actuators) -> float:
    """The least kmin [N/m] over the programs' samples (at most :data:`KMIN_SAMPLES` each);
    0 when a motor's catalogue entry has no stiffness."""
    from ..analytic.closed_form import position_ik_masked
    from ..dynamics.drives.stiffness import stiffness_at

    if any(u.stiffness is None for u in actuators.units):
        return 0.0
    k = actuators.stiffness()
    least = math.inf
    for traj in plans:
        poses = traj.poses[np.unique(np.linspace(0, len(traj) - 1, KMIN_SAMPLES).astype(int))]
        q = position_ik_masked(robot.params, poses)[0][:, :12]
        q = q[np.isfinite(q).all(axis=1)]
        if len(q):
            least = min(least, float(stiffness_at(robot, q, k).kmin.min()))
    return least if math.isfinite(least) else 0.0


def _full(values, design: Design, robot, ctx: DesignContext, screened: Evaluation,
          level: str = "full", notes: dict | None = None) -> Evaluation:
    from ..outputs.robots_toml import robots_toml

    t0 = time.perf_counter()
    options = ctx.options
    if level == "search":  # the same plan, cheaper checks (docs/model.md §31.5)
        options = ctx.search.options(options, ctx.job.sigma)
    n = design.robots
    figures = dict(screened.figures)
    cons = dict(screened.constraints)
    made = dict(notes or {})  # the search's notes taken, its own added (not the caller's)
    try:
        job = placed_job(values, ctx, robot, n, made)
        robots = job.robots or None
        with plan_notes(made):  # the same plan made again: its searches not repeated
            result = paint(robot, job, design.actuators, options)
    except PollardError as exc:  # the planner's refusal (a SolveError, a CellError): said
        figures["full_s"] = time.perf_counter() - t0
        binding = binding_of(str(exc))
        cons["plan"] = 1.0
        if binding != "plan":  # the refusal names it: off by more than the screen saw
            cons[binding] = max(cons.get(binding, 0.0), 0.0) + REFUSED
        return _infeasible(level, design, n, cons, binding, figures, str(exc).split("\n")[0],
                           motor_use=screened.objectives["motor_use"])
    data = result.report.data
    uses = [u for m in data["motors"].values() for u in m.values()]
    line = data.get("line") or {}
    pph = line.get("parts_per_hour", 3600.0 / data["cycle_time"])
    clear = data.get("clearance") or {}
    least = min(v for k, v in clear.items() if k in ("min_m", "between_robots_m",
                                                      "to_part_m", "gun_to_part_m")
                and v is not None)
    within = data["thickness"]["within_5pct"]
    cons.update({"plan": -1.0, "motors": max(uses) - 1.0,
                 "clearance": clear.get("required_m", 0.0) - least,
                 "film": FILM_SHARE - within})
    plans = ([r.plan.trajectory for r in result.plan.robots] if robots is not None
             else [result.plan.trajectory])
    kmin = _kmin(robot, plans, design.actuators)
    figures.update({"cycle_s": data["cycle_time"], "film_within_5pct": within,
                    "film_min_um": data["thickness"]["min"] * 1e6,
                    "film_max_um": data["thickness"]["max"] * 1e6, "clearance_m": least,
                    "full_s": time.perf_counter() - t0})
    binding = next((k for k in CONSTRAINTS if cons.get(k, -1.0) > 0), None)
    objectives = _objectives(design, n, parts_per_hour=float(pph), motor_use=max(uses),
                             kmin=kmin)
    text = None if robots is None else robots_toml(
        robots, f"[[robot]] tables of a design of pollard-pin design for {_job_name(ctx.job)}\n"
        "(docs/model.md §31): add them to the job to plan with them")
    return Evaluation(level, binding is None, objectives, cons, binding, figures,
                      *_files(design), text, notes=made if level == "search" else None)


def _job_name(job) -> str:
    """The job by its file's name (the folder a design is written to moves with it)."""
    return Path(str(job.source)).name or str(job.source)


def evaluate(values: Mapping[str, Any], ctx: DesignContext, level: str = "full",
             notes: dict | None = None) -> Evaluation:
    """Judge one design (docs/model.md §31.3).

    Parameters
    ----------
    values : Mapping
        A value per :meth:`~pollard_pin.synthesis.space.DesignSpace.variables` (keys left out:
        the middle of their bounds, motor and ratio 0, the fewest robots).
    ctx : DesignContext
        From :func:`prepare`.
    level : str, optional
        ``"screen"``: the cheap checks only; ``"full"`` (default): the screen, then, if it
        passes, the paint plan, film, motors, cycle and kmin; ``"search"``: as ``"full"``,
        its checks at ``ctx.search``'s fidelity (:class:`SearchFidelity`; an evaluation of
        level ``"search"``), or exactly ``"full"`` when the context has none.
    notes : dict or None, optional
        The design's notes from its search (:attr:`Evaluation.notes`): its layout and line
        plans' searches taken from there where their inputs are the same (the plan made
        again is the same plan, only its checks at this level's fidelity), none by default.

    Returns
    -------
    Evaluation
        Feasible or not, never raised for a design that cannot paint.

    Raises
    ------
    pollard_pin.errors.InputError
        ``level`` unknown, or values out of the space's ranges (an index, a robot count).
    """
    if level not in LEVELS:
        raise InputError(f"level = {level!r}: expected 'screen', 'search' or 'full'")
    design, robot, ev = _screen(values, ctx)
    if level == "screen" or not ev.feasible:
        return ev
    return _full(values, design, robot, ctx, ev,
                 "search" if level == "search" and ctx.search is not None else "full", notes)


def baseline_values(space: DesignSpace, ctx: DesignContext | None = None) -> dict[str, Any]:
    """The values of the reference design (every factor 1, every bounded key at the
    reference's value, in the space or not, standing at the origin) with the catalogue motor
    and ratio nearest the shipped actuators; the fewest robots the space allows, or with
    ``ctx``, the fewest whose screen it passes (the thesis robot as the cell it paints in).

    Parameters
    ----------
    space : DesignSpace
        The design space.
    ctx : DesignContext or None, optional
        The job's context (:func:`prepare`): the robot count from the screen.

    Returns
    -------
    dict
        A value per variable: the thesis robot's row of a study.
    """
    from ..dynamics.motors import load_actuators
    from ..model.overrides import lookup

    values: dict[str, Any] = {k: float(lookup(space.reference, k)) for k in space.bounds}
    values.update({f"scale.{g.name}": 1.0 for g in space.scales})
    shipped = load_actuators()
    cat = space.catalogue
    for group, joints in space.motor_groups:
        a = shipped[joints[0]]
        values[f"motor.{group}"] = int(np.argmin([abs(math.log(m.peak_torque / a.peak_torque))
                                                  for m in cat.motors]))
        values[f"ratio.{group}"] = int(np.argmin([abs(math.log(r / a.gear_ratio))
                                                  for r in cat.ratios]))
    if space.back[0] < space.back[1]:
        values["place.back"] = space.back[0]
    if space.robots[0] < space.robots[1]:
        values["robots"] = space.robots[0]
        counts = range(space.robots[0], space.robots[1] + 1) if ctx is not None else ()
        for n in counts:  # the screen is cheap (docs/model.md §31.3)
            if evaluate({**values, "robots": n}, ctx, level="screen").feasible:
                values["robots"] = n
                break
    return values


__all__ = ["CONSTRAINTS", "DesignContext", "Evaluation", "LEVELS", "OBJECTIVES", "SENSES",
           "UNITS", "baseline_values", "design_files", "evaluate", "prepare"]
