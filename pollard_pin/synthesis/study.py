"""The design study: optuna's NSGA-II over the design space, every evaluation stored in the
study database the moment it finishes (docs/model.md §31).

Why NSGA-II and not TPE (both are optuna's, both take constraints):

* **Constraints as a gradient.** Most of a design space cannot paint the job. NSGA-II ranks
  designs by Deb's constrained domination: a feasible design beats an infeasible one, and of
  two infeasible ones the smaller total violation wins. The screen's graded constraint values
  (how far out of reach, how far over a motor's rating) so steer the search towards the
  feasible region; TPE's constrained variant only splits the trials into feasible or not.
* **Batches without guessing.** The optimiser runs in this process and hands designs to every
  core, or to a Dask cluster, while others are still being planned. A genetic generation is
  such a batch by nature; TPE proposes one design from all finished ones, and in parallel it
  proposes from a stale model (its "constant liar" guesses the pending results).
* **Five objectives, constant cost.** Multi-objective TPE weighs its candidates by
  hypervolume, whose cost grows quickly with five objectives and with the number of trials;
  NSGA-II's cost per design is a sort of one population.
* **A front, not a point.** The answer is a Pareto front (robots against parts per hour
  against motor use, stiffness and mass). NSGA-II keeps a spread population along it (its
  crowding distance); that is what it is for.

What it costs: NSGA-II needs more evaluations than TPE for the same front. The screen makes
most of them cheap (an infeasible design is rejected in milliseconds), which is where the
evaluations go. Optuna stores the generation of each trial in the database, so a resumed study
continues the same generation.

A study runs :func:`~pollard_pin.synthesis.backends.run_design` for each design (the screen, then
the full plan of a design that passes it) and ``tell``s the result at once: a killed run loses
only the designs being evaluated. The trial's user attributes hold the evaluation's level,
feasibility, binding constraint, objectives, figures and times, and a feasible full design's
files; its constraints are optuna's named constraints (≤ 0: met).
"""
from __future__ import annotations

import contextlib
import math
import os
import signal
import threading
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..checks import SEEDS, callback, instance, is_integer, scheduler_address, shorten
from ..errors import InputError, SolveError
from .backends import Outcome, failure, make_runner
from .fidelity import SearchFidelity
from .front import SENSES, FrontResolution
from .storage import require_optuna

FILES = ("params.toml", "actuators.toml", "robots.toml")
# an objective an infeasible design has no figure for: a stand-in for optuna (which needs a
# number); constrained domination never compares it, and the tables show no value
STAND_IN = 0.0
# stop with one line when this many evaluations raised (a bug, not an infeasible design)
MAX_ERRORS = 10
EVALUATION = "evaluation"  # the trial's user attribute that holds what its evaluation found




@dataclass(frozen=True)
class DesignOptions:
    """How a design study runs (checked once).

    Attributes
    ----------
    trials : int
        The evaluations the study holds when it stops (a resumed study counts those it had).
    workers : int or None
        Local processes (None: every core; 1: this process).
    dask : str or distributed.Client or None
        A Dask scheduler address or client: the evaluations run there (a blank or malformed
        address is refused here, by ``--dask``'s rule, ``pollard_pin.checks.address_problem``).
    seed : int or None
        The sampler's seed (None: random).
    population : int
        NSGA-II's population (designs per generation).
    study : str or Path or None
        The SQLite study file (None: a study in memory, not stored).
    resume : bool
        Continue the study in ``study`` (started with the same job and space).
    pick : int or None
        The front row to choose, from 1 (None: :func:`~pollard_pin.synthesis.front.choose`).
    screen_only : bool
        Judge designs by the screen alone (no full plan): a quick look, not an answer.
    progress : bool or Callable
        A progress bar on a terminal (True), or ``progress(done, total, feasible, best)``.
    ladder : bool
        Start a new study with the screened ladder's best designs after the thesis robot
        (:mod:`~pollard_pin.synthesis.ladder`; False: NSGA-II's random first generation).
    search : SearchFidelity or None
        How the search plans a design that passes the screen (default
        :class:`~pollard_pin.synthesis.SearchFidelity`: the film on a coarser grid,
        the clearance over fewer samples); the front and the baseline are planned again
        exactly before they are reported. None: every design planned exactly.
    front : FrontResolution
        The resolution the reported front tells designs apart at (default
        :class:`~pollard_pin.synthesis.front.FrontResolution`: parts per hour 1 %, motor use
        0.01, kmin 10 %, moving mass 2 %, docs/model.md §31.5): of designs closer than that,
        one is planned again and reported. All 0: the exact Pareto front.
    """

    trials: int = 200
    workers: int | None = None
    dask: Any = None
    seed: int | None = 0
    population: int = 24
    study: str | Path | None = None
    resume: bool = False
    pick: int | None = None
    screen_only: bool = False
    progress: bool | Callable = False
    ladder: bool = True
    search: SearchFidelity | None = SearchFidelity()
    front: FrontResolution = FrontResolution()

    def __post_init__(self):
        for name, low in (("trials", 1), ("population", 2), ("workers", 1), ("pick", 1)):
            value = getattr(self, name)
            if value is None and name in ("workers", "pick"):
                continue
            if not is_integer(value, low):
                raise InputError(f"DesignOptions.{name}: must be an integer >= {low}, got "
                                 f"{shorten(value)}")
            object.__setattr__(self, name, int(value))  # numpy's integers too, as ints
        if self.seed is not None:
            if not is_integer(self.seed, 0, SEEDS - 1):
                raise InputError(f"DesignOptions.seed: must be an integer 0..2^32 − 1 (numpy's "
                                 f"seeds) or None, got {shorten(self.seed)}")
            object.__setattr__(self, "seed", int(self.seed))
        for flag in ("resume", "screen_only", "ladder"):  # "no" is truthy: real bools only
            instance(getattr(self, flag), f"DesignOptions.{flag}", bool, "True or False")
        if not isinstance(self.progress, bool):
            callback(self.progress, "DesignOptions.progress")
        scheduler_address(self.dask, "DesignOptions.dask")  # --dask's rule, before any work
        if self.resume and self.study is None:
            raise InputError("DesignOptions.resume: needs a study file to resume")
        if self.search is not None and not isinstance(self.search, SearchFidelity):
            raise InputError(f"DesignOptions.search: expected a SearchFidelity or None, got "
                             f"{type(self.search).__name__}")
        instance(self.front, "DesignOptions.front", FrontResolution, "FrontResolution")

    @property
    def stage(self) -> str:
        """The level the study judges designs at: ``"screen"`` (``screen_only``),
        ``"search"`` (a search fidelity) or ``"full"``."""
        return "screen" if self.screen_only else "full" if self.search is None else "search"


def objectives_of(names: Sequence[str]) -> list[tuple[str, str]]:
    """(name, optuna direction) of each objective, in order."""
    return [(n, "maximize" if SENSES[n] > 0 else "minimize") for n in names]


def sampler(options: DesignOptions, finished: int = 0):
    """NSGA-II with the options' population and seed (a resumed study: the seed moved on by
    the evaluations it holds, so that it proposes new designs, not the first ones again)."""
    optuna = require_optuna()
    seed = None if options.seed is None else (options.seed + finished) % SEEDS
    return optuna.samplers.NSGAIISampler(population_size=options.population, seed=seed)


def suggest(trial, variables) -> dict:
    """The trial's values of the design variables (optuna's distributions, one per kind)."""
    values = {}
    with warnings.catch_warnings():
        # an enqueued design outside a bound (the thesis robot's row) is meant: said once in
        # the project's words (outside_bounds), not by optuna per parameter and trial
        warnings.filterwarnings("ignore", message="Fixed parameter .* is out of range")
        for v in variables:
            if v.kind == "categorical":  # an index into the choices, as the evaluator takes it
                values[v.name] = trial.suggest_categorical(v.name,
                                                           list(range(len(v.choices))))
            elif v.kind == "int":
                values[v.name] = trial.suggest_int(v.name, int(v.low), int(v.high))
            else:
                values[v.name] = trial.suggest_float(v.name, float(v.low), float(v.high))
    return values


def outside_bounds(values: Mapping, variables) -> str | None:
    """Which of ``values`` lie outside their variable's bounds ("KEY = x, bound [lo, hi]",
    joined), or None: a reference design outside the space, or a bound in other units."""
    out = [f"{v.name} = {values[v.name]:g} (bound [{v.low:g}, {v.high:g}])" for v in variables
           if v.kind == "float" and v.name in values and not v.low <= values[v.name] <= v.high]
    return "; ".join(out) or None


@contextlib.contextmanager
def _signals_held():
    """SIGINT and SIGTERM held back while the study's database is written: the study stays
    consistent, and the signal's own handler runs the moment the write is done. (Python runs
    handlers in the main thread whichever thread the signal reached, so a thread's signal
    mask would not hold them: the handlers are swapped instead.)"""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    held = (signal.SIGINT, signal.SIGTERM)
    old = {s: signal.signal(s, lambda signum, frame: caught.append(signum)) for s in held}
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        for s in dict.fromkeys(caught):
            handler = old[s]
            if callable(handler):
                handler(s, None)
            elif handler == signal.SIG_DFL:
                os.kill(os.getpid(), s)


def enqueue(study, designs: Sequence[Mapping]) -> None:
    """Put ``designs`` first in the study's queue (optuna's waiting trials, stored: a resumed
    study evaluates those it has not), each write with the signals held."""
    for values in designs:
        with _signals_held():
            study.enqueue_trial(dict(values))


def plain(value):
    """``value`` as JSON-ready data (numpy scalars and arrays as numbers and lists; a
    non-finite float as None)."""
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "tolist"):
        return plain(value.tolist())
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if value is None or isinstance(value, (bool, int, str)):
        return value
    return str(value)


def record(study, trial, outcome: Outcome | BaseException, names: Sequence[str]) -> bool:
    """Tell the study what ``trial``'s evaluation found, in one write; whether feasible.

    An evaluation that raised is a failed trial (its message kept as the ``error`` user
    attribute); otherwise the trial is complete, with its constraints, objectives (a stand-in
    for those an infeasible design lacks) and user attributes.
    """
    optuna = require_optuna()
    with _signals_held():
        if isinstance(outcome, BaseException):
            trial.set_user_attr("error", failure(outcome))
            study.tell(trial, state=optuna.trial.TrialState.FAIL)
            return False
        ev = outcome.final
        objectives = {n: _finite(ev.objectives.get(n)) for n in names}
        constraints = {str(k): _finite(v) for k, v in dict(ev.constraints).items()}
        constraints = {k: (1e6 if v is None else v) for k, v in constraints.items()}
        feasible = bool(ev.feasible) and all(v <= 0 for v in constraints.values())
        # the evaluation's own verdict, as a constraint too: the sampler agrees with it
        constraints["evaluation"] = 0.0 if feasible else 1.0
        attrs = {"level": ev.level, "feasible": feasible, "binding": ev.binding,
                 "objectives": objectives, "constraints": constraints,
                 "figures": plain(dict(ev.figures or {})), "seconds": outcome.seconds}
        if feasible and ev.level != "screen":
            attrs["files"] = {n: t for n, t in zip(FILES, (ev.params_toml, ev.actuators_toml,
                                                          ev.robots_toml)) if t}
        if feasible and ev.level == "search" and getattr(ev, "notes", None):
            attrs["notes"] = ev.notes  # its exact plan, if on the front, without searching
        trial.set_user_attr(EVALUATION, attrs)  # one write: every write is a commit
        for k, v in constraints.items():  # optuna's named constraints: NSGA-II reads them
            trial.set_constraint(k, v)
        study.tell(trial, [STAND_IN if objectives[n] is None else objectives[n]
                           for n in names])
    return feasible


def _finite(value) -> float | None:
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def finished(study) -> tuple[int, int, int]:
    """(evaluations kept, feasible, raised) of the study: complete trials and failed ones
    with an ``error``; trials cut short by a stop are not counted."""
    optuna = require_optuna()
    done = feasible = errors = 0
    for t in study.get_trials(deepcopy=False):
        if t.state == optuna.trial.TrialState.COMPLETE:
            done += 1
            feasible += bool(t.user_attrs.get(EVALUATION, {}).get("feasible"))
        elif t.state == optuna.trial.TrialState.FAIL and "error" in t.user_attrs:
            errors += 1
    return done + errors, feasible, errors


def close_stale(study) -> int:
    """Mark the trials a killed run left running as failed (they were never finished); how
    many. A resumed study then counts only what was finished."""
    optuna = require_optuna()
    stale = [t for t in study.get_trials(deepcopy=False)
             if t.state == optuna.trial.TrialState.RUNNING]
    for t in stale:
        with _signals_held():
            study.tell(t.number, state=optuna.trial.TrialState.FAIL)
    return len(stale)


def best_text(study_best: dict | None) -> str:
    """The progress bar's "best so far": the fewest robots, then the most parts per hour."""
    if not study_best:
        return "none feasible"
    return (f"{study_best['robots']:.0f} robot(s), {study_best['parts_per_hour']:.4g} parts/h")


def run_study(study, variables, ctx, evaluate: Callable, names: Sequence[str],
              options: DesignOptions, report: Callable | None = None,
              runner=None) -> None:
    """Evaluate designs until the study holds ``options.trials`` evaluations.

    Parameters
    ----------
    study : optuna.Study
        From :func:`~pollard_pin.synthesis.storage.open_study`.
    variables : Sequence
        The design variables (``name``, ``low``, ``high``, ``kind``, ``choices``).
    ctx : object
        The prepared context.
    evaluate : Callable
        ``evaluate(values, ctx, level)``.
    names : Sequence of str
        The objectives, in the study's order.
    options : DesignOptions
        Workers, Dask, trials.
    report : Callable or None, optional
        ``report(done, total, feasible, best)`` after each evaluation.
    runner : Runner or None, optional
        Where the designs run, left open for the caller's next stage (default: one of
        ``options``' workers or Dask, :func:`~pollard_pin.synthesis.backends.make_runner`,
        closed at the end).

    Raises
    ------
    SolveError
        :data:`MAX_ERRORS` evaluations raised (naming the first), a worker process died.
    KeyboardInterrupt
        SIGINT or SIGTERM: the designs in flight are marked failed first, so the study holds
        exactly the finished ones.
    """
    optuna = require_optuna()
    done, feasible, errors = finished(study)
    best = _best(study, names)
    inflight: dict[int, Any] = {}
    first_error = None
    if report is not None:
        report(done, options.trials, feasible, best)
    with (contextlib.nullcontext(runner) if runner is not None
          else make_runner(ctx, evaluate, options.workers, options.dask)) as runner:
        try:
            while done < options.trials or inflight:
                while len(inflight) < runner.capacity and done + len(inflight) < options.trials:
                    # every database write with the signals held: a stop between two
                    # leaves the study consistent (and the trial noted, to be failed)
                    with _signals_held():
                        trial = study.ask()
                        inflight[trial.number] = trial
                        values = suggest(trial, variables)
                    runner.submit(trial.number, values, options.stage)
                for key, outcome in runner.done():
                    ok = record(study, inflight[key], outcome, names)
                    del inflight[key]
                    done += 1
                    feasible += ok
                    if isinstance(outcome, BaseException):
                        errors += 1
                        first_error = first_error or failure(outcome)
                        if errors >= MAX_ERRORS:
                            raise SolveError(f"{errors} design evaluations raised; the first: "
                                             f"{first_error}")
                    elif ok:
                        best = _better(best, outcome_objectives(outcome, names))
                    if report is not None:
                        report(done, options.trials, feasible, best)
        except BaseException:
            with _signals_held():  # cut short: failed, so the study is consistent
                for number in inflight:
                    with contextlib.suppress(RuntimeError, ValueError):  # told already
                        study.tell(number, state=optuna.trial.TrialState.FAIL)
            raise


def _better(best: dict | None, objectives: dict) -> dict:
    if best is None:
        return objectives
    new = (objectives["robots"], -objectives["parts_per_hour"])
    return objectives if new < (best["robots"], -best["parts_per_hour"]) else best


def _best(study, names) -> dict | None:
    best = None
    for t in study.get_trials(deepcopy=False):
        found = t.user_attrs.get(EVALUATION, {})
        if found.get("feasible"):
            best = _better(best, found["objectives"])
    return best


def outcome_objectives(outcome: Outcome, names) -> dict:
    return {n: _finite(outcome.final.objectives.get(n)) for n in names}
