"""What :func:`~pollard_pin.painting.api.paint_job` returns: the film a plan leaves, the numbers
of ``paint.json`` and the result that holds them with the plan (docs/model.md §20–§26)."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..dynamics.motors import Actuators
from .cell.plan import CellPlan
from .film.mesh import MeshFilm
from .film.points import SurfacePoints
from .job import PaintJob, PartJob
from .line.panel import LinePlan
from .line.part import LinePartPlan
from .options import PaintOptions
from .plan.panel import PaintPlan
from .plan.part import SurfacePlan
from .spray.deposition import Film

if TYPE_CHECKING:  # the kinds import this module: a kind's type only
    from .kinds.base import JobKind


@dataclass(frozen=True)
class PaintFilm:
    """The film a plan leaves. A panel: ``points`` (nv, nu, 3) on the grid ``grid`` = (U, V),
    ``film`` a :class:`~pollard_pin.painting.spray.deposition.Film`. A part: ``points`` the
    film points (``painting.film.points.SurfacePoints``: points, normals, areas, faces),
    ``film`` a ``painting.film.mesh.MeshFilm``,
    ``painted`` the mask of points on painted faces, ``efficiency`` the transfer
    efficiency. On a line, the part (or panel) at its t = 0 pose, world coordinates."""

    points: np.ndarray | SurfacePoints
    film: Film | MeshFilm
    resolution: float
    grid: tuple | None = None
    painted: np.ndarray | None = None
    efficiency: float | None = None

    @property
    def thickness(self) -> np.ndarray:
        """The film thickness [m] at every point."""
        return self.film.thickness


@dataclass(frozen=True)
class PaintReport:
    """The numbers of ``paint.json`` (docs/model.md §21, §23, §24), its main ones typed.

    Attributes
    ----------
    kind : str
        The job's kind (``"panel"``, ``"part"``, ``"line panel"``, ``"line part"``).
    cycle_time : float
        The program's cycle [s].
    target : float
        The target film thickness [m].
    thickness : Mapping
        The film statistics: ``mean``, ``min``, ``max``, ``std`` [m], ``uniformity``,
        ``within_5pct`` and ``within_10pct`` (shares of the area), ``deviation_min`` and
        ``deviation_max`` (relative to the target).
    motors : Mapping
        Per motor, each limit's use over its rating (``peak_torque``, ``rms_torque``,
        ``speed``).
    line : Mapping or None
        On a line: start delay, window, travel, cycle, pitch, parts per hour, the speed's
        upper bound (with ``PaintOptions(speeds=True)`` the ``speeds`` that paint the job,
        docs/model.md §24.3); None when still.
    timings : Mapping
        Seconds spent planning and integrating the film.
    data : Mapping
        The whole report (``paint.json`` adds film.ply's colour map).
    """

    kind: str
    cycle_time: float
    target: float
    thickness: Mapping
    motors: Mapping
    line: Mapping | None
    timings: Mapping
    data: Mapping

    @classmethod
    def from_dict(cls, kind: str, rep: dict) -> PaintReport:
        return cls(kind, rep["cycle_time"], rep["target"], rep["thickness"], rep["motors"],
                   rep.get("line"), rep["timings"], rep)

    def to_dict(self) -> dict:
        """paint.json's content (a copy at the top level)."""
        return dict(self.data)


@dataclass(frozen=True)
class PaintedJob:
    """A job planned, filmed and reported, before anything is written: what
    :func:`~pollard_pin.painting.api.paint_job` returns (:func:`pollard_pin.paint` returns
    it as a :class:`~pollard_pin.PaintResult`, which also writes itself).

    Attributes
    ----------
    job : PaintJob or pollard_pin.painting.job.PartJob
        The job.
    kind : str
        Its kind (``"panel"``, ``"part"``, ``"line panel"``, ``"line part"``, ``"cell panel"``,
        ``"cell part"``: a name in ``pollard_pin.painting.kinds.KINDS``).
    plan : PaintPlan, SurfacePlan, LinePlan, LinePartPlan or CellPlan
        The plan of that kind (a :class:`~pollard_pin.painting.plan.PaintPlan` for a still
        panel): its ``trajectory`` (the program, a :class:`~pollard_pin.Trajectory`) and
        ``spray`` (the gun's trigger per sample), passes, speed, cycle time.
    film : pollard_pin.painting.result.PaintFilm
        The film points and the thickness [m] at each.
    report : PaintReport
        The numbers of ``paint.json``.
    actuators : Actuators
        The motor ratings the program was checked against.
    options : PaintOptions
        How it was planned.
    painter : pollard_pin.painting.kinds.base.JobKind
        The kind that painted it: its summary lines, what it writes.

    :meth:`summary_lines` are the lines ``pollard-pin paint`` prints.
    """

    job: PaintJob | PartJob
    kind: str
    plan: PaintPlan | SurfacePlan | LinePlan | LinePartPlan | CellPlan
    film: PaintFilm
    report: PaintReport
    actuators: Actuators
    options: PaintOptions
    painter: JobKind

    @property
    def robot_folders(self) -> tuple[str, ...]:
        """The robots with a folder of their own in the outputs (a cell's; else none)."""
        if not self.painter.outputs.per_robot:
            return ()
        return tuple(r.robot.name for r in self.plan.robots)

    def summary_lines(self) -> list[str]:
        """The lines ``pollard-pin paint`` prints: the kind's own, then the gun body's
        clearance and the compliance where the report has them."""
        from .summary import closing_lines

        rep = self.report.data
        return [*self.painter.summary_lines(rep, self.actuators.names), *closing_lines(rep)]


__all__ = ["PaintFilm", "PaintReport", "PaintedJob"]
