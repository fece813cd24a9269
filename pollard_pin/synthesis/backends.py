"""Where a design study's evaluations run: in this process, on a local process pool, or on a
Dask cluster. The optimiser stays in this process (optuna's ask/tell); each runner takes
designs (:meth:`Runner.submit`) and hands back those that finished (:meth:`Runner.done`), in
the order they finish, so that every one is stored the moment it is known.

What runs is :func:`run_design`: the screen, then the search's or the full evaluation of a
design that passes it ("cheap first, exact last"), a plain module-level function of the
design's values, the prepared context and the evaluator, so that a pool or a Dask worker can
run it.
"""
from __future__ import annotations

import os
import signal
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from ..checks import scheduler_address
from ..errors import InputError, PollardError, SolveError

# How long a runner waits for a finished evaluation before it hands control back: the study
# loop then sees a signal (SIGTERM stops the run within a second).
POLL = 0.2


@dataclass(frozen=True)
class Outcome:
    """One design's evaluation: ``final``, the search's or the full one, or the screen's when
    the screen rejected the design (or only the screen was asked for); ``seconds``, its wall
    time."""

    final: Any
    seconds: float


def run_design(values: Mapping, ctx, evaluate: Callable, level: str = "full",
               notes: dict | None = None) -> Outcome:
    """Screen the design, and plan it when it passes and ``level`` asks for it (the
    evaluator's ``level="search"`` and ``"full"`` screen first and stop there when the screen
    rejects the design).

    Parameters
    ----------
    values : Mapping
        The design variables' values (name → value).
    ctx : object
        The prepared context (:func:`pollard_pin.synthesis.evaluation.prepare`'s).
    evaluate : Callable
        ``evaluate(values, ctx, level)`` → an evaluation with ``level`` and ``feasible``.
    level : str, optional
        ``"screen"``, ``"search"`` (planned at the search's fidelity) or ``"full"`` (default).
    notes : dict or None, optional
        The design's notes from its search (the evaluation's ``notes``), handed to
        ``evaluate`` as ``notes=`` (None: not passed).

    Returns
    -------
    Outcome
        The evaluation that judges the design, and its time [s].
    """
    t0 = time.perf_counter()
    more = {} if notes is None else {"notes": notes}
    found = evaluate(dict(values), ctx, level=level, **more)
    return Outcome(found, time.perf_counter() - t0)


class Runner:
    """Runs :func:`run_design` for submitted designs: ``submit(key, values, level, notes)``,
    ``done()`` → [(key, Outcome or the exception it raised)], ``capacity`` designs in
    flight at once, ``close()`` (stops what is still running)."""

    capacity = 1

    def submit(self, key: int, values: Mapping, level: str = "full",
               notes: dict | None = None) -> None:
        raise NotImplementedError

    def done(self) -> list[tuple[int, Any]]:
        raise NotImplementedError

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class SerialRunner(Runner):
    """In this process, one design at a time (``submit`` only queues it; ``done`` runs it)."""

    def __init__(self, ctx, evaluate: Callable):
        self.ctx, self.evaluate, self.queue = ctx, evaluate, []

    def submit(self, key, values, level="full", notes=None):
        self.queue.append((key, values, level, notes))

    def done(self):
        if not self.queue:
            return []
        key, values, level, notes = self.queue.pop(0)
        return [(key, _guarded(run_design, values, self.ctx, self.evaluate, level, notes))]


def _guarded(fn, *args):
    try:
        return fn(*args)
    except Exception as exc:  # noqa: BLE001 — handed to the study, which names the design
        return exc


# --- a local process pool ------------------------------------------------------------------
_WORKER: dict = {}  # a pool worker's context and evaluator, set once by _init_worker


def one_blas_thread() -> None:
    """One BLAS thread in this process (threadpoolctl): the pool's workers are one per core
    already, and a BLAS pool in each of them only competes for the cores (its threads cost
    6–9 % of an evaluation's CPU time, the figures the same to the bit). A forked worker
    inherits its parent's loaded BLAS, so the libraries are told directly, not through the
    environment."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")


def _init_worker(ctx, evaluate) -> None:
    # Ctrl-C and SIGTERM are the parent's to handle: it stops the workers itself
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    one_blas_thread()
    _WORKER.update(ctx=ctx, evaluate=evaluate)


def _pool_task(values, level, notes=None):
    return run_design(values, _WORKER["ctx"], _WORKER["evaluate"], level, notes)


class PoolRunner(Runner):
    """A local process pool of ``workers`` processes; the context is sent to each worker once
    (its initializer), not with every design."""

    def __init__(self, ctx, evaluate: Callable, workers: int, mp_context: str | None = None):
        import multiprocessing
        import threading
        from concurrent.futures import ProcessPoolExecutor

        if mp_context is None:  # fork where safe (as sweep's pool): workers start at once
            fork_ok = ("fork" in multiprocessing.get_all_start_methods()
                       and threading.active_count() == 1)
            mp_context = "fork" if fork_ok else "spawn"
        self.capacity = workers
        self.pool = ProcessPoolExecutor(max_workers=workers,
                                        mp_context=multiprocessing.get_context(mp_context),
                                        initializer=_init_worker, initargs=(ctx, evaluate))
        self.futures: dict = {}

    def submit(self, key, values, level="full", notes=None):
        self.futures[self.pool.submit(_pool_task, dict(values), level, notes)] = key

    def done(self):
        from concurrent.futures import FIRST_COMPLETED, wait
        from concurrent.futures.process import BrokenProcessPool

        if not self.futures:
            return []
        finished, _ = wait(list(self.futures), timeout=POLL, return_when=FIRST_COMPLETED)
        out = []
        for fut in finished:
            key = self.futures.pop(fut)
            exc = fut.exception()
            if isinstance(exc, BrokenProcessPool):
                raise SolveError(f"a design worker process died ({exc}); a script that runs a "
                                 "study on the process pool needs an `if __name__ == "
                                 "'__main__':` guard, or run it with workers=1") from exc
            out.append((key, exc if exc is not None else fut.result()))
        return out

    def close(self):
        # a worker may be minutes into a full plan: stop it, do not wait for it (the
        # executor has no public way to end its processes before Python 3.14)
        processes = list((getattr(self.pool, "_processes", None) or {}).values())
        self.pool.shutdown(wait=False, cancel_futures=True)
        for p in processes:
            if p.is_alive():
                p.terminate()
        for p in processes:
            p.join(timeout=1.0)


# --- a Dask cluster ------------------------------------------------------------------------
class DaskRunner(Runner):
    """Designs on a Dask cluster (a scheduler address, or a ``distributed.Client``). The
    context is scattered to the workers once. A design whose worker dies is run again by the
    scheduler, and one that raises is retried ``retries`` times: only it is lost."""

    def __init__(self, ctx, evaluate: Callable, address: Any, retries: int = 2):
        from ..sweep.backends import connect, require_distributed

        distributed = require_distributed()
        self.client, self.own = connect(address, SolveError)
        workers = len(self.client.scheduler_info().get("workers", {})) or 1
        self.capacity = 2 * workers  # one queued behind each running design
        self.ctx = self.client.scatter(ctx, broadcast=True)
        self.evaluate, self.retries, self.futures = evaluate, retries, {}
        self.wait = distributed.wait

    def submit(self, key, values, level="full", notes=None):
        fut = self.client.submit(run_design, dict(values), self.ctx, self.evaluate, level,
                                 notes, pure=False, retries=self.retries)
        self.futures[fut] = key

    def done(self):
        if not self.futures:
            return []
        try:
            finished = self.wait(list(self.futures), timeout=POLL,
                                 return_when="FIRST_COMPLETED").done
        except TimeoutError:
            return []
        out = []
        for fut in finished:
            key = self.futures.pop(fut)
            if fut.status == "error":
                out.append((key, fut.exception()))
            elif fut.status == "cancelled":
                out.append((key, SolveError("the Dask cluster cancelled the evaluation")))
            else:
                out.append((key, fut.result()))
        return out

    def close(self):
        try:
            if self.futures:
                self.client.cancel(list(self.futures))
        finally:
            if self.own:
                self.client.close()


def make_runner(ctx, evaluate: Callable, workers: int | None = None, dask: Any = None,
                mp_context: str | None = None) -> Runner:
    """The runner for ``dask`` (an address or client), else ``workers`` local processes
    (default: every core; 1: this process).

    Parameters
    ----------
    ctx : object
        The prepared, picklable context.
    evaluate : Callable
        The evaluator (a module-level function).
    workers : int or None, optional
        Local processes (default ``os.cpu_count()``).
    dask : str or distributed.Client or None, optional
        A Dask scheduler address or client.
    mp_context : str or None, optional
        The local pool's start method.

    Returns
    -------
    Runner
        A context manager; leaving it stops what still runs.
    """
    if scheduler_address(dask, "dask") is not None:
        return DaskRunner(ctx, evaluate, dask)
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise InputError(f"workers = {workers}: must be >= 1")
    if workers == 1:
        return SerialRunner(ctx, evaluate)
    return PoolRunner(ctx, evaluate, workers, mp_context)


def failure(exc: BaseException) -> str:
    """One line for an evaluation that raised: the project's own message, else the kind."""
    text = " ".join(str(exc).split())
    if isinstance(exc, PollardError):
        return text or type(exc).__name__
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__
