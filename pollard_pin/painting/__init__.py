"""Painting: the job file, the spray deposition model, the planners of every job kind, the
motion checks and the film (docs/model.md §20–§27).

The entry point is the plain function :func:`pollard_pin.paint` (on the outputs floor: it
returns :func:`paint_job`'s result as one that writes itself); the names a user calls are
imported here, the rooms' own in their subpackages (``kinds``, ``checks``, ``layout``, ``cell``,
``plan``, ``film``, ``spray`` …).
"""
from .api import paint_job
from .errors import CellError, JobError, JobKindError, LayoutSearchError, PlaceError, PlanError
from .job import PaintJob, job_from_dict, load_job
from .kinds.panel import paint_report
from .layout.cell import LayoutOptions, propose_layout
from .layout.place import PlaceOptions, PlaceResult, place
from .options import PaintOptions
from .policy import PlannerPolicy
from .result import PaintedJob, PaintReport

__all__ = ["paint_job", "PaintOptions", "PaintedJob", "PaintReport", "PlannerPolicy", "load_job",
           "job_from_dict", "PaintJob", "place", "PlaceOptions", "PlaceResult",
           "propose_layout", "LayoutOptions", "paint_report", "CellError",
           "JobError", "JobKindError", "LayoutSearchError", "PlaceError", "PlanError"]
