"""How the design study's search plans a design that passes the screen (docs/model.md
§31.5): the same planner as the full evaluation (the same motions and cycle), its checks
cheaper; what it may change, and why the front is planned again exactly before it is
reported."""
from __future__ import annotations

from dataclasses import dataclass, replace

from ..checks import instance, real
from ..errors import InputError
from ..painting.options import PaintOptions


@dataclass(frozen=True)
class SearchFidelity:
    """How the study's search plans a design that passes the screen (``level="search"``,
    docs/model.md §31.5): the full level's planner (the same motions and cycle: the
    objectives the exact ones, but the motor use, which the coarser motor check may see
    lower), its checks cheaper; the study's front is planned again exactly before it is
    reported. Checked once.

    Attributes
    ----------
    film : float
        The film's grid spacing in σ of the spray spot, in (0, 1] (default 0.5; the full
        level's is the paint options', σ/3 by default): the film's share within ±5 % is
        judged on the coarser grid.
    clearance_stride : int
        The clearance checks take every this many of each program's samples (default 4,
        :attr:`~pollard_pin.painting.policy.PlannerPolicy.clearance_stride`): the least
        distance over fewer samples, the bound between them larger (more cautious).
    check_refine : int
        The final motor check samples the path this many times more densely (default 1: on
        the path's own samples, :attr:`~pollard_pin.painting.policy.PlannerPolicy.check_refine`;
        never denser than the full level's): the worst motor use between them unseen.
    name_speeds : bool
        A design refused at the job's line speed is refused naming the interval of line
        speeds that paint it (default False:
        :attr:`~pollard_pin.painting.policy.PlannerPolicy.name_speeds`; the search reads
        only the refusal's binding constraint, and that interval's search cost an infeasible
        design about as much again as its plan).
    """

    film: float = 0.5
    clearance_stride: int = 4
    check_refine: int = 1
    name_speeds: bool = False

    def __post_init__(self):
        object.__setattr__(self, "film", real(self.film, "SearchFidelity.film", 0.0, 1.0,
                                              above=True, why=" (a spacing in σ in (0, 1])"))
        for name in ("clearance_stride", "check_refine"):
            c = getattr(self, name)
            if isinstance(c, bool) or not isinstance(c, int) or c < 1:
                raise InputError(f"SearchFidelity.{name} = {c!r}: expected an integer >= 1")
        instance(self.name_speeds, "SearchFidelity.name_speeds", bool, "true or false")

    def options(self, options: PaintOptions, sigma: float) -> PaintOptions:
        """The paint options of the search: ``options`` with the film's spacing
        ``film``·σ, the clearance stride and the motor check's refinement (none of them
        finer than theirs), a refused line speed's interval named only if both ask."""
        policy = options.policy
        exact = sigma / 3 if options.resolution is None else options.resolution
        return replace(options, resolution=max(exact, self.film * sigma), policy=replace(
            policy, clearance_stride=max(policy.clearance_stride, self.clearance_stride),
            check_refine=min(policy.check_refine, self.check_refine),
            name_speeds=policy.name_speeds and self.name_speeds))


__all__ = ["SearchFidelity"]
