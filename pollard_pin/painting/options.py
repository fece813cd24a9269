"""How :func:`~pollard_pin.painting.api.paint_job` plans and integrates: its options, checked
once."""
from __future__ import annotations

import numbers
from dataclasses import dataclass

from ..checks import instance, is_real, shorten
from ..errors import InputError
from .line.speeds import SPEED_RESOLUTION
from .policy import DEFAULT_POLICY, PlannerPolicy


@dataclass(frozen=True)
class PaintOptions:
    """How :func:`~pollard_pin.painting.api.paint_job` plans and integrates, validated once.

    Parameters
    ----------
    resolution : float or None, optional
        The film's point spacing [m] (a panel's grid, a part's film points), at most the
        spray spot's σ; None: σ/3.
    max_line_speed : bool, optional
        A job on a line is planned at the fastest line speed that paints it instead of the
        job's speed (docs/model.md §24; default False).
    speed_resolution : float, optional
        That search's relative bracket, in (0, 1) (default 0.01).
    speeds : bool, optional
        A job on a line also states the interval of line speeds that paint it, each end
        to 5 % and planned in full (paint.json's ``line.speeds``, docs/model.md §24.3;
        default False: it costs ~10 more plans).
    compliance : bool, optional
        Report what the drives' compliance does to the gun and the film (docs/model.md
        §27.7; a second film integration; default True).
    policy : PlannerPolicy, optional
        The planners' knobs: the motors' reserve, the sampling and the budgets (default:
        the planners' own, ``PlannerPolicy()``).
    progress : bool, optional
        Progress bars on standard error over the long loops, when it is a terminal
        (:mod:`pollard_pin.painting.progress`; default False: the command line sets it).

    Raises
    ------
    pollard_pin.errors.InputError
        A resolution that is not > 0, a flag that is not a bool, a bracket outside (0, 1),
        a policy that is not a :class:`~pollard_pin.painting.policy.PlannerPolicy`.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> options = pp.PaintOptions(resolution=0.004)
    >>> options.resolution, options.max_line_speed, options.policy.utilisation
    (0.004, False, 0.97)
    """

    resolution: float | None = None
    max_line_speed: bool = False
    speed_resolution: float = SPEED_RESOLUTION
    speeds: bool = False
    compliance: bool = True
    policy: PlannerPolicy = DEFAULT_POLICY
    progress: bool = False

    def __post_init__(self):
        r = self.resolution
        if r is not None and not is_real(r, 0.0, above=True):
            raise InputError(f"PaintOptions.resolution = {shorten(r)}: expected a spacing > 0 "
                             "[m] (or None for σ/3)")
        for flag in ("max_line_speed", "speeds", "compliance", "progress"):
            instance(getattr(self, flag), f"PaintOptions.{flag}", bool, "True or False")
        s = self.speed_resolution
        if isinstance(s, bool) or not isinstance(s, numbers.Real) or not 0 < s < 1:
            raise InputError(f"PaintOptions.speed_resolution = {shorten(s)}: expected a relative "
                             "bracket in (0, 1)")
        if not isinstance(self.policy, PlannerPolicy):
            raise InputError(f"PaintOptions.policy = {shorten(self.policy)}: expected a "
                             "PlannerPolicy")


__all__ = ["PaintOptions"]
