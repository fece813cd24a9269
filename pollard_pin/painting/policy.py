"""The planners' policy, one home for panels, parts, lines and cells (docs/model.md §21, §23,
§24): the motors' reserve, the sampling of the duration searches and of the final check, the
path's time step and the budgets checked before anything is built. The planners take it as
an option (``policy=``), validated once; the defaults are the planners' own."""
from __future__ import annotations

from dataclasses import dataclass, fields

from ..checks import instance, integer, real, shorten
from ..errors import InputError

STROKES = ("auto", "across", "along")  # docs/model.md §24.2
STEP_FROM = ("leading", "trailing")
CHOICES = {"strokes": STROKES, "step_from": STEP_FROM}
CELL = ("seam_run", "smoothing", "seams")  # a cell's knobs, checked apart (_check_cell)
MAX_LENGTH = 10.0  # m: a cell's run, averaging or seam beyond this is a unit slip
MAX_SEAMS = 15  # a cell has at most 16 robots (cell.robots.MAX_ROBOTS)


@dataclass(frozen=True)
class PlannerPolicy:
    """The knobs every paint planner reads, validated once (docs/model.md §21, §23, §24).

    Parameters
    ----------
    utilisation : float, optional
        The share of each motor's peak torque and max speed the planner may use where it
        samples (its reserve for what it does not sample), in (0, 1] (default 0.97).
    turn_samples : int, optional
        Samples per turnaround or ramp in the duration search, at least 2 (default 48).
    check_refine : int, optional
        The final motor check samples the path this many times more densely, at least 1
        (default 4).
    max_step : float, optional
        The trajectory's largest time step [s], > 0 (default 0.002).
    step_sigma : float, optional
        The gun moves at most this many σ per step (film integration, §20), > 0
        (default 0.25).
    max_path_samples : int, optional
        The budget of the path's samples, checked before anything is built: the final motor
        check solves ``check_refine`` times as many at ≈ 3.3 KB and 20 µs each (default 250 000:
        ≈ 3.3 GB and 20 s), at least 2.
    max_passes : int, optional
        The budget of passes over all coats (the layout's cross-profile grid grows with their
        square), at least 1 (default 1000).
    first_deceleration : float, optional
        The duration search starts from a reversal at this rate [m/s²], > 0 (default 10).
    strokes : str, optional
        On a line, the strokes' direction (docs/model.md §24.2): ``"across"`` the travel,
        ``"along"`` it, or ``"auto"`` (default): of those that paint at the job's speed the
        shortest cycle. A still part keeps its shorter raster.
    step_from : str, optional
        On a line, the end the strokes step from: ``"leading"`` (default) or ``"trailing"``.
    clearance_stride : int, optional
        The clearance checks (docs/model.md §25, §26.4) take every this many of the path's
        samples (and its last), at least 1 (default 1: every sample). A larger stride is
        cheaper and more cautious: the least distance is over fewer samples, and the bound
        on what lies between them grows with the stride (the design study's search,
        docs/model.md §31.5).
    name_speeds : bool, optional
        A line speed that does not paint is refused naming the interval of speeds that do,
        found by planning others (docs/model.md §24.3; default True). False: refused as that
        speed's plan failed, its constraint named, without that search (the design study's
        search, which reads only the binding constraint, docs/model.md §31.5).
    seam_run : float or None, optional
        A cell's strokes run this far [m] past a seam, at least 0 (default None: R, the
        seam's run-out, docs/model.md §26.3). The trigger still closes at the seam on the
        constant-speed stroke, so the film is the same for any run; a shorter one keeps the
        ramps and turnarounds beyond it within the band the split gave the robot (§26.5).
    smoothing : float, optional
        A cell's passes over a part average the surface normal over at least this width [m]
        (docs/model.md §23), every robot alike (a seam is invisible only between two halves
        of one pass), at least 0 (default 0: the least that lets the gun follow).
    seams : tuple of float or None, optional
        A cell's seams [m along the split's axis, the part at t = 0], increasing, one fewer
        than the robots facing the job's side (default None: the split's, §26.2), where the
        motors allow rather than where the bands meet (§26.5).

    Raises
    ------
    pollard_pin.errors.InputError
        One line naming the field, the value and the rule.
    """

    utilisation: float = 0.97
    turn_samples: int = 48
    check_refine: int = 4
    max_step: float = 0.002
    step_sigma: float = 0.25
    max_path_samples: int = 250_000
    max_passes: int = 1000
    first_deceleration: float = 10.0
    strokes: str = "auto"
    step_from: str = "leading"
    clearance_stride: int = 1
    name_speeds: bool = True
    seam_run: float | None = None
    smoothing: float = 0.0
    seams: tuple[float, ...] | None = None

    def __post_init__(self):
        least = {"turn_samples": 2, "check_refine": 1, "max_path_samples": 2, "max_passes": 1,
                 "clearance_stride": 1}
        for name, allowed in CHOICES.items():
            if getattr(self, name) not in allowed:
                raise InputError(f"PlannerPolicy.{name} = {getattr(self, name)!r}: expected "
                                 f"one of {', '.join(allowed)}")
        if self.strokes == "along" and self.step_from == "trailing":
            raise InputError("PlannerPolicy.step_from = 'trailing': strokes along the travel "
                             "step across it, from no end of the part")
        instance(self.name_speeds, "PlannerPolicy.name_speeds", bool, "true or false")
        self._check_cell()
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in CHOICES or f.name in CELL or f.name == "name_speeds":
                continue
            if f.name in least:
                object.__setattr__(self, f.name, integer(value, f"PlannerPolicy.{f.name}",
                                                         least[f.name]))
            else:
                high = 1.0 if f.name == "utilisation" else float("inf")
                object.__setattr__(self, f.name, real(value, f"PlannerPolicy.{f.name}", 0.0,
                                                      high, above=True))

    def _check_cell(self) -> None:
        """The cell's knobs (docs/model.md §26.5): lengths at least 0, seams increasing."""
        if self.seam_run is not None:
            object.__setattr__(self, "seam_run", real(self.seam_run, "PlannerPolicy.seam_run",
                                                      0.0, MAX_LENGTH))
        object.__setattr__(self, "smoothing", real(self.smoothing, "PlannerPolicy.smoothing",
                                                   0.0, MAX_LENGTH))
        if self.seams is None:
            return
        if isinstance(self.seams, (str, bytes)) or not hasattr(self.seams, "__len__") or \
                not 1 <= len(self.seams) <= MAX_SEAMS:
            raise InputError(f"PlannerPolicy.seams = {shorten(self.seams)}: expected 1-"
                             f"{MAX_SEAMS} seams [m], increasing (or None)")
        seams = tuple(real(x, f"PlannerPolicy.seams[{i}]", -MAX_LENGTH, MAX_LENGTH)
                      for i, x in enumerate(self.seams))
        if any(b <= a for a, b in zip(seams, seams[1:])):
            raise InputError(f"PlannerPolicy.seams = {shorten(self.seams)}: must increase")
        object.__setattr__(self, "seams", seams)

    def cell_knobs(self) -> tuple[str, ...]:
        """The cell's knobs set away from their defaults (``seam_run``, ``smoothing``,
        ``seams``): only a cell's planner reads them, so a job of one robot refuses them."""
        return tuple(f.name for f in fields(self)
                     if f.name in CELL and getattr(self, f.name) != f.default)

    def first_guess(self, speed: float) -> float:
        """The duration search's first turnaround/ramp duration [s] at pass ``speed`` [m/s]:
        reversing at about ``first_deceleration``; the search then finds the shortest the
        motors allow."""
        return 4 * speed / self.first_deceleration

    def step(self, sigma: float, speed: float) -> float:
        """The path's time step [s] for a spot of ``sigma`` [m] moving at ``speed`` [m/s]:
        at most ``max_step``, and ``step_sigma`` σ of travel."""
        return min(self.max_step, self.step_sigma * sigma / speed)

    def coarser(self, dt: float, speed_set: bool | None = None) -> str:
        """What else takes fewer path samples at the time step ``dt`` [s], a shorter path
        aside: a faster gun where the step is ``max_step`` (``job.speed`` where the job sets
        it, ``speed_set``; a thinner film or more flow where it does not; None: either);
        where the step is ``step_sigma`` σ of travel the gun's speed cancels out (samples =
        path length / (``step_sigma`` σ)) and only a wider spray does."""
        if dt < self.max_step:
            return "a wider spray (gun.sigma)"
        return {True: "a faster gun (job.speed)", False: "a thinner film, more flow"}.get(
            speed_set, "a faster gun (a thinner film, more flow or job.speed)")

    @property
    def budget_fix(self) -> str:
        """The budget's own knob, said last in a sample-budget refusal."""
        return "or a larger policy.max_path_samples"


DEFAULT_POLICY = PlannerPolicy()  # the planners' default, shared (it is frozen)


__all__ = ["CHOICES", "DEFAULT_POLICY", "PlannerPolicy", "STEP_FROM", "STROKES"]
