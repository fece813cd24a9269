"""The kinds of paint job, one module each (docs/model.md §20–§26), and THE table
:func:`~pollard_pin.painting.api.paint_job` dispatches on: a new kind is a module defining a
:class:`~.base.JobKind` (its recipe, report, summary lines and outputs) and one line here."""
from __future__ import annotations

from ..errors import JobKindError
from . import cell, line_panel, line_part, panel, part
from .base import JobKind

#: The kinds by name, in the order :func:`kind_of` asks them: a new kind is one more line.
KINDS: dict[str, JobKind] = {k.name: k for k in (
    panel.KIND,
    part.KIND,
    line_panel.KIND,
    line_part.KIND,
    cell.PANEL,
    cell.PART,
)}


def kind_of(job) -> JobKind:
    """The kind in :data:`KINDS` that recognises ``job``.

    Parameters
    ----------
    job : PaintJob or PartJob
        From :func:`~pollard_pin.load_job`.

    Raises
    ------
    JobKindError
        Anything else, naming its type.
    """
    for kind in KINDS.values():
        if kind.recognises(job):
            return kind
    shown = repr(job) if len(repr(job)) <= 40 else f"{repr(job)[:37]}..."
    raise JobKindError(f"job = {shown}: cannot paint a {type(job).__name__}: expected a paint "
                       f"job of kind {', '.join(KINDS)} (a PaintJob or PartJob, from load_job)")


__all__ = ["KINDS", "JobKind", "kind_of"]
