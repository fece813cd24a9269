"""The paint result that writes itself, on the outputs floor: :func:`paint` is
``pollard_pin.paint``, and :class:`PaintResult` is painting's
:class:`~pollard_pin.painting.result.PaintedJob` with :meth:`PaintResult.write`. It lives here,
above the writers and the figures, so that painting never imports a layer above its own."""
from __future__ import annotations

from dataclasses import dataclass, fields
from pathlib import Path

from ..checks import file_path
from ..dynamics.motors import Actuators
from ..painting.api import paint_job
from ..painting.layout.auto import fewest_robots as fewest_painted
from ..painting.layout.cell import LayoutOptions
from ..painting.options import PaintOptions
from ..painting.result import PaintedJob
from .paint_cell_files import write_cell
from .paint_files import write_paint


@dataclass(frozen=True)
class PaintResult(PaintedJob):
    """What :func:`paint` returns: the job planned, filmed and reported, and :meth:`write`,
    which writes what ``pollard-pin paint`` writes.

    Attributes
    ----------
    job, kind, plan, film, report, actuators, options, painter
        As :class:`~pollard_pin.painting.result.PaintedJob`'s: the job, its kind's name, the
        plan, the film, the numbers of ``paint.json``, the motor ratings, the options and
        the kind that painted it.
    """

    @classmethod
    def of(cls, painted: PaintedJob) -> PaintResult:
        """``painted`` (from :func:`~pollard_pin.painting.api.paint_job`, or a layout
        proposal's) as a result that writes itself."""
        if isinstance(painted, cls):
            return painted
        return cls(**{f.name: getattr(painted, f.name) for f in fields(PaintedJob)})

    def write(self, folder: str | Path, format: str = "csv") -> Path:
        """Write path.csv, thickness.csv|parquet, film.ply, paint.json and thickness.png in
        ``folder`` (a cell: each robot's path.csv in its own folder), every one or none, as
        ``pollard-pin paint`` does; the film table's path."""
        return write_result(self, file_path(folder, "folder"), format)


def write_result(result: PaintedJob, folder: Path, format: str = "csv") -> Path:
    """Every output of ``result`` in ``folder``, or none (a cell: a folder per robot,
    docs/model.md §26); the film table's path.

    Parameters
    ----------
    result : PaintedJob
        A painted job (:func:`~pollard_pin.painting.api.paint_job`, a layout proposal's).
    folder : str or Path
        The output folder.
    format : str, optional
        The film table's format, ``"csv"`` (default) or ``"parquet"``.
    """
    writer = write_cell if result.painter.outputs.per_robot else write_paint
    return writer(result, Path(folder), format)


def paint(robot, job, actuators: Actuators | str | Path | None = None,
          options: PaintOptions | None = None) -> PaintResult:
    """Plan the job (a panel or a part, still or on a line, painted by one robot or by a
    cell of several), integrate its film and compute its report (docs/model.md §20–§24,
    §26): what ``pollard-pin paint`` does (:func:`~pollard_pin.painting.api.paint_job`'s
    computation, returned as a result that writes itself).

    A job with ``[line]`` and ``[[robot]]`` tables (``job.robots``) is a cell: the part is
    split into zones, one per robot (:func:`~pollard_pin.painting.cell.split.split_cell`),
    each robot's program is planned in its own base frame on the cell's clock
    (:func:`~pollard_pin.painting.cell.plan.plan_cell`), the robots' clearance from each
    other and from the part is checked, and the film is that of all robots together;
    ``result.kind`` is then ``"cell panel"`` or ``"cell part"``. To propose the robots'
    bases: :func:`~pollard_pin.propose_layout`, :func:`~pollard_pin.fewest_robots`.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        From :func:`~pollard_pin.load_job`.
    actuators : Actuators or str or Path or None, optional
        The motor ratings the program must keep, or an actuator file's path (read by
        :func:`~pollard_pin.load_actuators`) (default: the job's ``actuators`` file, else the
        package's, ``examples/actuators.toml``).
    options : PaintOptions or None, optional
        Film resolution, the line speed search.

    Returns
    -------
    PaintResult
        The plan, the film, the report; ``result.write(folder)`` writes the outputs (for a
        cell: ``folder/<robot>/path.csv`` per robot, one film for the whole part).

    Raises
    ------
    PlanError
        No program meets the job: out of reach (naming where, and the largest panel that
        fits), a budget broken (a film too thick for the flow, a panel narrower than the
        spot), the gun's body too close to the part; for a cell, a robot that cannot paint
        its zone, or two robots (or a robot and the part) closer than the clearance.
    JobKindError
        A job of a kind the planner does not handle.
    pollard_pin.errors.InputError
        Options of the wrong type, ``max_line_speed`` without a line.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> job = pp.job_from_dict({
    ...     "panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
    ...               "width": 0.26, "height": 0.12},
    ...     "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
    ...     "job": {"thickness": 25e-6}})
    >>> result = pp.paint(pp.load(), job)
    >>> result.kind, result.report.data["passes"], round(result.report.cycle_time, 1)
    ('panel', 9, 10.0)
    >>> result.report.thickness["within_5pct"]
    1.0
    >>> sorted(p.name for p in result.write("out").parent.iterdir())[:3]
    ['film.ply', 'paint.json', 'path.csv']
    """
    return PaintResult.of(paint_job(robot, job, actuators, options))


def fewest_robots(robot, job, actuators: Actuators | None = None,
                  options: PaintOptions | None = None, layout: LayoutOptions | None = None,
                  count: int | None = None):
    """The fewest robots that paint the job and their cell's result, which writes itself:
    :func:`pollard_pin.painting.layout.auto.fewest_robots` (docs/model.md §26.5), its
    painted job returned as a :class:`PaintResult`.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        A job with ``[line]`` and no ``[[robot]]`` tables.
    actuators : Actuators or str or Path or None, optional
        The motor ratings (default: the job's file, else the package's).
    options : PaintOptions or None, optional
        As for :func:`paint`.
    layout : LayoutOptions or None, optional
        The spacing, the names, the room at the free edges and the top robot's pitch.
    count : int or None, optional
        This many robots only, plain then with the levers (default None: the fewest).

    Returns
    -------
    robots : tuple of CellRobot
        The proposed robots.
    result : PaintResult
        The cell's plan, film and report with them; ``result.write(folder)`` writes them.

    Raises
    ------
    pollard_pin.painting.LayoutSearchError
        No count tried paints the part: one line naming each count's cause; its ``causes``
        maps each count to its :class:`~pollard_pin.painting.causes.Cause`.
    pollard_pin.painting.errors.PlanError
        With ``count``: that count's refusal.
    """
    robots, painted = fewest_painted(robot, job, actuators, options, layout, count)
    return robots, PaintResult.of(painted)


__all__ = ["PaintResult", "fewest_robots", "paint", "write_result"]
