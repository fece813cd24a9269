"""``view --paint DIR``: a paint output folder as the viewer's overlay, read by
:mod:`pollard_pin.outputs` (its files, its report, its film); here its refusals name the
flag."""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

from .common import UsageError


@contextmanager
def paint_flag():
    """A folder that is not what paint wrote, said as --paint's usage error."""
    from ..outputs.folder import PaintFolderError

    try:
        yield
    except PaintFolderError as exc:
        raise UsageError(f"--paint {exc}") from None


def paint_overlay(folder, path: str = "path.csv"):
    """:func:`pollard_pin.outputs.overlay.paint_overlay` of ``--paint folder``."""
    from ..outputs.overlay import paint_overlay as overlay

    with paint_flag():
        return overlay(Path(folder), path)
