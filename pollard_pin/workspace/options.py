"""What a workspace map takes (docs/model.md §22): :class:`WorkspaceOptions`, checked once, and
the rules of its values shared with the CLI (orientation, a finite number)."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..analytic.taskspace import MAX_ABS_TASK, TASK_NAMES
from ..checks import instance, real, shorten
from ..errors import InputError
from ..kinematics.margins import Margins, as_margins
from ..model.values import parse_float

CHUNK = 8192  # points per stacked evaluation: ≈ 10 MB of working arrays


class WorkspaceError(InputError):
    """A workspace request that cannot be mapped (one line: which value, why; for a plane or
    bounds with nothing reachable, the reachable bounding box)."""


@dataclass(frozen=True, eq=False)
class WorkspaceOptions:
    """How :func:`~pollard_pin.map_workspace` maps, checked once here.

    Parameters
    ----------
    volume : bool, optional
        Map a box rather than a plane (default False).
    orientation : tuple of float, optional
        The tool orientation (ψ, θ, φ) [rad], ZYZ (default (0, 0, 0): the gun along +x).
    resolution : float, optional
        The grid step [m] (default 0.005).
    bounds : Mapping or None, optional
        ``{axis: (low, high)}`` [m] (default: the whole reach with a margin).
    actuators : Actuators or None, optional
        Adds the static payload capacity per point (:func:`~pollard_pin.load_actuators`).
    margins : Margins or None, optional
        Singularity margins (default ``run``'s).
    length_scale : float or None, optional
        The conditioning index's length [m] (default: the platform arm).
    keep : bool or None, optional
        Keep every chunk's columns in the map (default: in plane mode only).
    chunk : int, optional
        Points per stacked evaluation (default 8192).

    Raises
    ------
    WorkspaceError
        An orientation that is not three finite angles, a non-positive length scale or
        chunk, a ``volume`` or ``keep`` that is not a bool (or None for ``keep``).
    MarginError
        Margins that are not a :class:`~pollard_pin.Margins`.

    Examples
    --------
    >>> import math
    >>> import pollard_pin as pp
    >>> pp.WorkspaceOptions(orientation=(0.0, math.radians(20), 0.0)).orientation[1]
    0.3490658503988659
    """

    volume: bool = False
    orientation: Any = (0.0, 0.0, 0.0)
    resolution: float = 0.005
    bounds: Mapping | None = None
    actuators: Any = None
    margins: Margins | None = None
    length_scale: float | None = None
    keep: bool | None = None
    chunk: int = CHUNK

    def __post_init__(self):
        instance(self.volume, "volume", bool, "True or False", error=WorkspaceError)
        instance(self.keep, "keep", bool, "True, False or None", none=True,
                 error=WorkspaceError)
        object.__setattr__(self, "orientation", check_orientation(self.orientation))
        object.__setattr__(self, "margins", as_margins(self.margins))
        if self.length_scale is not None:
            object.__setattr__(self, "length_scale", real(
                self.length_scale, "length_scale", 0.0, above=True, why=" [m]",
                error=WorkspaceError))
        if isinstance(self.chunk, bool) or not isinstance(self.chunk, int) or self.chunk < 1:
            raise WorkspaceError(f"chunk = {shorten(self.chunk)}: must be a whole number of points "
                                 ">= 1")


def finite_value(value, what: str, unit: str, limit: float = 1e3) -> float:
    """``value`` as a float, finite and within ±``limit`` [``unit``] (text as typed)."""
    try:  # text as the user typed it: no "0.5_5", no full-width digits
        v = parse_float(value) if isinstance(value, str) else float(value)
    except OverflowError:  # an integer beyond a float
        v = math.inf
    except (TypeError, ValueError):
        raise WorkspaceError(f"{what} = {shorten(value)} is not a number [{unit}]") from None
    if not math.isfinite(v) or abs(v) > limit:
        within = f" within ±{limit:g} {unit}" if math.isfinite(limit) else f" [{unit}]"
        raise WorkspaceError(f"{what} = {shorten(value)} must be a finite number{within}")
    return v


def check_orientation(orientation, deg: bool = False) -> tuple[float, float, float]:
    """(ψ, θ, φ) [rad], three finite numbers; given in degrees if ``deg`` (a command line's),
    then named in degrees as typed, returned in radians."""
    unit = "deg" if deg else "rad"
    try:
        vals = [float(v) for v in orientation]
    except (TypeError, ValueError, OverflowError):  # OverflowError: an integer beyond a float
        raise WorkspaceError(f"orientation {shorten(orientation)}: expected three numbers "
                             f"(psi, theta, phi) [{unit}]") from None
    if len(vals) != 3 or not all(math.isfinite(v) for v in vals):
        raise WorkspaceError(f"orientation {shorten(orientation)}: expected three finite "
                             f"numbers (psi, theta, phi) [{unit}]")
    limit = math.degrees(MAX_ABS_TASK) if deg else MAX_ABS_TASK
    for name, v in zip(TASK_NAMES[3:], vals):
        if abs(v) > limit:  # the poses' own rule (analytic.taskspace)
            said = f"{MAX_ABS_TASK:g} rad; " if deg else ""  # the rule's own unit too
            raise WorkspaceError(f"orientation {name} = {v:.6g} {unit} is absurd: |{name}| > "
                                 f"{limit:g} {unit} ({said}a unit or data error?)")
    return tuple(math.radians(v) for v in vals) if deg else tuple(vals)
