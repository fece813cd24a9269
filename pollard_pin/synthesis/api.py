"""``pollard_pin.synthesis``: search the design space for the robots that paint a job, and give
back the front, the baseline and the chosen design (:func:`design`; the CLI is a thin layer
over it)."""
from __future__ import annotations

import contextlib
import sys
import time
import warnings
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from ..checks import callback, clip, instance, shorten
from ..errors import InputError, SolveError
from .backends import failure, make_runner
from .front import choose, epsilon_front, rank_key
from .ladder import first_generation
from .result import DesignResult, shown
from .storage import check_study_file, job_fingerprint, open_study
from .study import (
    EVALUATION,
    DesignOptions,
    close_stale,
    enqueue,
    finished,
    objectives_of,
    outside_bounds,
    run_study,
    sampler,
)


def default_evaluator():
    """The design evaluator: ``prepare``, ``evaluate`` and ``OBJECTIVES``
    (:mod:`pollard_pin.synthesis.evaluation`)."""
    import importlib

    # the module, not the package's ``evaluate`` (the function of that name)
    return importlib.import_module(f"{__package__}.evaluation")


def _as_job(job):
    if isinstance(job, (str, Path)):
        from ..painting.job import load_job

        return load_job(job)
    if not callable(getattr(job, "to_dict", None)):  # a job's (or a stand-in's) interface
        raise InputError(f"job = {shorten(job)}: expected a paint job (PaintJob, PartJob) or "
                         f"a job file's path, got {type(job).__name__}")
    return job


def _as_space(space):
    if isinstance(space, (str, Path)):
        from .space import load_space

        return load_space(space)
    if isinstance(space, Mapping):
        from .space import space_from_dict

        return space_from_dict(space)
    if not all(callable(getattr(space, m, None)) for m in ("variables", "fingerprint")):
        raise InputError(f"space = {shorten(space)}: expected a DesignSpace, a space file's "
                         f"path or its table (a Mapping), got {type(space).__name__}")
    return space


def trial_rows(study, variables, names: Sequence[str]) -> list[dict]:
    """One row per evaluation the study holds (complete, or failed with an error)."""
    import optuna

    rows = []
    for t in study.get_trials(deepcopy=False):
        complete = t.state == optuna.trial.TrialState.COMPLETE
        if not complete and "error" not in t.user_attrs:
            continue  # cut short by a stop: never finished
        a = t.user_attrs.get(EVALUATION, {})
        objectives = a.get("objectives") or {}
        rows.append({"trial": t.number, "state": "complete" if complete else "error",
                     "level": a.get("level"), "feasible": bool(a.get("feasible")),
                     "binding": a.get("binding") or t.user_attrs.get("error"),
                     **{n: objectives.get(n) for n in names},
                     **shown(variables, t.params),
                     **{f"c_{k}": c for k, c in sorted((a.get("constraints") or {}).items())},
                     "seconds": a.get("seconds")})
    return rows


def _replan(runner, designs: list[dict], notes: list | None = None) -> list:
    """Each design planned in full on ``runner`` (the study's, still open), in parallel,
    with its search's ``notes`` (a list beside ``designs``, None each where none: the same
    plans made again without their searches); the outcomes (or exceptions) in input order.
    The most robots first (the longest plans: the last to finish is then a short one, not a
    worker idle beside a long one)."""
    out: list = [None] * len(designs)
    notes = [None] * len(designs) if notes is None else notes
    pending = sorted(enumerate(designs), key=lambda kv: -float(kv[1].get("robots", 1)))
    inflight = 0
    while pending or inflight:
        while pending and inflight < runner.capacity:
            k, values = pending.pop(0)
            runner.submit(k, values, "full", notes[k])
            inflight += 1
        for k, outcome in runner.done():
            out[k], inflight = outcome, inflight - 1
    return out


def _design_row(k: int, trial, values: dict, outcome, names) -> dict | None:
    if isinstance(outcome, BaseException) or not outcome.final.feasible:
        return None
    ev = outcome.final
    return {"design": k, "trial": trial, "values": values, "feasible": True,
            "level": ev.level, "objectives": {n: float(ev.objectives[n]) for n in names},
            "figures": dict(ev.figures or {}), "binding": ev.binding,
            "files": {n: t for n, t in (("params.toml", ev.params_toml),
                                        ("actuators.toml", ev.actuators_toml),
                                        ("robots.toml", ev.robots_toml)) if t}}


def _no_front(rows: list[dict]) -> SolveError:
    binding = Counter(r["binding"] for r in rows if not r["feasible"] and r["binding"])
    most = (f"; the binding constraint most often: {binding.most_common(1)[0][0]} "
            f"({binding.most_common(1)[0][1]} of {len(rows)})" if binding else "")
    return SolveError(f"no design of the space paints the job in {len(rows)} evaluations"
                      f"{most}")


def _connected(dask: Any, stack: contextlib.ExitStack) -> Any:
    """``dask`` (a scheduler address) as a connected client, closed by ``stack`` (a client
    or None: as given; an empty address: make_runner's refusal)."""
    if not isinstance(dask, str) or not dask.strip():
        return dask
    from ..sweep.backends import connect

    client, _ = connect(dask, SolveError)
    stack.callback(client.close)
    return client


def design(job, space, options: DesignOptions | None = None, *, evaluator=None,
           progress: Callable | None = None) -> DesignResult:
    """Search the design space for the robots that paint ``job`` (docs/model.md §31): an
    NSGA-II study over the space's variables, started with the thesis robot and the best
    designs of a screened ladder (:mod:`~pollard_pin.synthesis.ladder`), every design
    screened and, when it passes,
    planned in full, so that every front design is judged by its full plan (a study run with
    ``screen_only`` plans its front in full at the end); the thesis robot (the study's first
    design) as the baseline.

    Parameters
    ----------
    job : PaintJob or PartJob or str or Path
        The paint job (a job file's path is read by :func:`~pollard_pin.load_job`).
    space : DesignSpace or str or Path or Mapping
        The design space (a path: :func:`~pollard_pin.synthesis.space.load_space`).
    options : DesignOptions or None, optional
        Trials, workers or Dask, the study file, ``resume``, ``pick``.
    evaluator : object or None, optional
        ``prepare(job, space)``, ``evaluate(values, ctx, level)``, ``baseline_values(space, ctx)``
        and ``OBJECTIVES`` (default: :mod:`pollard_pin.synthesis.evaluation`).
    progress : Callable or None, optional
        ``progress(done, total, feasible, best)`` after each evaluation (default: a bar on a
        terminal when ``options.progress``).

    Returns
    -------
    DesignResult
        ``result.write(folder)`` writes the chosen design's files, the tables and the plot.

    Raises
    ------
    pollard_pin.synthesis.storage.StudyFileError
        A study file that cannot be used (another job or space, damaged, a FIFO …).
    SolveError
        No feasible design in the study's evaluations (naming the constraint that binds most
        often), too many evaluations that raised.
    KeyboardInterrupt
        SIGINT or SIGTERM: the study file keeps every finished evaluation.
    """
    t0 = time.perf_counter()
    options = DesignOptions() if options is None else options
    instance(options, "options", DesignOptions, "DesignOptions or None")
    callback(progress, "progress")
    ev = default_evaluator() if evaluator is None else evaluator
    job, space = _as_job(job), _as_space(space)
    names = tuple(ev.OBJECTIVES)
    if options.study is not None:  # its refusals before the work, and before any write
        check_study_file(options.study, options.resume)
    stack = contextlib.ExitStack()  # the cluster and the study's runner, until the front
    dask = _connected(options.dask, stack)  # an unreachable one before the work and writes
    try:
        ctx = ev.prepare(job, space, search=options.search)
        variables = list(space.variables())
        base = ev.baseline_values(space, ctx)
        study, close = open_study(options.study, job=job_fingerprint(job),
                                  space=space.fingerprint(), objectives=objectives_of(names),
                                  sampler=None, resume=options.resume)
    except BaseException:
        stack.close()
        raise
    report = progress if progress is not None else (_bar(options) if options.progress
                                                    else None)
    try:
        close_stale(study)
        if not study.trials:  # the thesis robot is the study's first design, then the ladder's
            # on this machine's cores even with --dask: a screen (ms) is shorter than a
            # cluster's round trip, and 500 of them queued there took minutes
            first, line = ([], None) if not options.ladder else first_generation(
                variables, base, ctx, ev.evaluate, min(options.population, options.trials) - 1,
                options.workers)
            outside = outside_bounds(base, variables)
            if outside:  # a bound in other units (rad for deg, mm for m) shows here
                warnings.warn(f"the reference design (the study's first row) lies outside the "
                              f"space: {clip(outside, 160)}; it is evaluated as it is "
                              "(bounds in models/pollard.toml's units: m, deg)", stacklevel=2)
            enqueue(study, [base, *first])
            if line is not None:
                study.set_user_attr("ladder", line)
        study.sampler = sampler(options, finished(study)[0])
        runner = stack.enter_context(make_runner(ctx, ev.evaluate, options.workers, dask))
        run_study(study, variables, ctx, ev.evaluate, names, options, report, runner)
        rows = trial_rows(study, variables, names)
        stored = {t.number: (dict(t.params), t.user_attrs.get(EVALUATION, {}))
                  for t in study.get_trials(deepcopy=False)}
    except BaseException:
        stack.close()
        raise
    finally:
        if hasattr(report, "close"):
            report.close()
        close()
    with stack:
        trial = next((n for n, (values, found) in stored.items() if values == base and found),
                     None)
        front, notes, outcomes = _front(rows, stored, runner, names, options, trial)
        baseline = _baseline(base, trial, stored, runner, names, outcomes)
    # the exact figures' ε-front (the same boxes as the selection re-planned, §31.5)
    keep = epsilon_front([d["objectives"] for d in front], options.front)
    front = sorted((front[i] for i in keep), key=lambda d: rank_key(d["objectives"]))
    for k, d in enumerate(front, start=1):
        d["design"] = k
    chosen = choose([d["objectives"] for d in front], options.pick)
    return DesignResult(tuple(variables), names, tuple(rows), tuple(front), baseline, chosen,
                        None if options.study is None else str(options.study),
                        time.perf_counter() - t0, tuple(notes), options.front)


def _front(rows, stored, runner, names, options, base: int | None = None
           ) -> tuple[list[dict], list[str], dict]:
    """The front's designs (the ε-front at ``options.front`` of the study's feasible
    evaluations, :func:`~pollard_pin.synthesis.front.epsilon_front`), each judged by a full
    plan: the study's own full evaluations (from the database); a design the study judged by
    the screen alone or by the search's cheaper checks is planned in full now, with what its
    search noted (its layout and line plans' searches: the same plan made again without them,
    only its checks exact; one that fails it leaves the front, with a note, and the designs
    it hid are considered in turn);
    the notes; the outcomes of the plans made, by trial. The baseline's trial ``base``, if
    it needs a full plan (:func:`_needs_plan`), is planned with the first of them (on the
    same workers, not after them)."""
    levels = ("screen",) if options.screen_only else ("search", "full")
    candidates = [r for r in rows if r["feasible"] and r["level"] in levels]
    if not candidates:
        raise _no_front(rows)
    planned: dict[int, dict] = {}
    outcomes: dict[int, object] = {}
    notes: list[str] = []
    while True:
        pool = [r for r in candidates if r["trial"] not in planned or planned[r["trial"]]]
        if not pool:
            raise SolveError("no front design stayed feasible when planned in full: "
                             + "; ".join(notes))
        trials = [pool[i]["trial"] for i in epsilon_front(pool, options.front)]
        todo = [n for n in trials if n not in planned and stored[n][1].get("level") != "full"]
        if not todo:
            return ([planned.get(n) or _stored_row(n, *stored[n], names) for n in trials],
                    notes, outcomes)
        also = [base] if base is not None and base not in todo and base not in outcomes \
            and _needs_plan(stored[base][1]) else []
        designs = [stored[n][0] for n in todo + also]
        searched = [stored[n][1].get("notes") for n in todo + also]  # their plans' notes
        outcomes.update(zip(todo + also, _replan(runner, designs, searched)))
        for n, values in zip(todo, designs):
            outcome = outcomes[n]
            planned[n] = _design_row(0, n, values, outcome, names) or {}
            if not planned[n]:
                why = (failure(outcome) if isinstance(outcome, BaseException)
                       else outcome.final.binding)
                notes.append(f"trial {n} left the front when planned in full: {why}")


def _stored_row(trial: int, values: dict, found: dict, names) -> dict:
    return {"design": 0, "trial": trial, "values": values, "feasible": True,
            "level": found["level"], "objectives": {n: found["objectives"][n] for n in names},
            "figures": found.get("figures") or {}, "binding": None,
            "files": found.get("files") or {}}


def _needs_plan(found: dict) -> bool:
    """Whether the baseline's stored evaluation ``found`` is not its answer: the study only
    screened it and it passed, or judged it by the search's checks."""
    return not (found["level"] == "full" or (found["level"] == "screen"
                                             and not found["feasible"]))


def _baseline(base, trial, stored, runner, names, outcomes: dict) -> dict:
    """The thesis robot's row: its evaluation in the study (its first design, ``trial``),
    planned in full if the study only screened it and it passed, or judged it by the
    search's checks (or if the study lacks it); a plan the front made (``outcomes``, by
    trial) is not made again."""
    found = stored[trial][1] if trial is not None else None
    if found is not None and not _needs_plan(found):
        return {"values": base, "trial": trial, "feasible": bool(found["feasible"]),
                "binding": found.get("binding"),
                "objectives": ({n: found["objectives"][n] for n in names}
                               if found["feasible"] else None)}
    (b,) = [outcomes[trial]] if trial in outcomes else _replan(
        runner, [base], [None if found is None else found.get("notes")])
    if isinstance(b, BaseException):
        return {"values": base, "trial": trial, "feasible": False, "objectives": None,
                "binding": failure(b)}
    fb = b.final
    return {"values": base, "trial": trial, "feasible": bool(fb.feasible),
            "binding": fb.binding, "objectives": ({n: float(fb.objectives[n]) for n in names}
                                                  if fb.feasible else None)}


def _bar(options: DesignOptions):
    """A tqdm bar on a terminal: evaluations done, feasible, best so far."""
    from tqdm import tqdm

    from .study import best_text

    state = SimpleNamespace(bar=None)

    def report(done, total, feasible, best):
        if state.bar is None:
            state.bar = tqdm(total=total, initial=done, desc="design", unit="design",
                             disable=None, leave=False, file=sys.stderr)
        state.bar.update(done - state.bar.n)
        state.bar.set_postfix_str(f"feasible {feasible}, best {best_text(best)}",
                                  refresh=False)

    report.close = lambda: state.bar is not None and state.bar.close()
    return report

