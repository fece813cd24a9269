"""Painting: the job file, the spray deposition model, the planners of every job kind, the
motion checks and the film (docs/model.md §20–§27).

The entry point is the plain function :func:`pollard_pin.paint`; the names a user calls are
imported here, the rooms' own in their subpackages (``cell``, ``plan``, ``film``, ``spray`` …).
"""
from .api import PaintOptions, PaintReport, PaintResult, paint
from .cell.layout import LayoutOptions, fewest_robots, propose_layout
from .errors import JobKindError, PlanError
from .job import JobError, PaintJob, job_from_dict, load_job
from .place import PlaceError, PlaceOptions, PlaceResult, place
from .report import paint_report

__all__ = ["paint", "PaintOptions", "PaintResult", "PaintReport", "load_job", "job_from_dict",
           "PaintJob", "place", "PlaceOptions", "PlaceResult", "propose_layout", "fewest_robots",
           "LayoutOptions", "paint_report", "JobError", "JobKindError", "PlaceError", "PlanError"]
