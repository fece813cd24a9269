"""Running a sweep: serially, on a local process pool or on a Dask cluster; rows come back
in input order and are the same whichever way they were computed."""
from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

from ..checks import callback, instance, scheduler_address
from .evaluate import SweepError, evaluate_variant
from .grid import Sweep

# --- running ----------------------------------------------------------------------------------
Progress = Callable[[int, int], None]


def _checked(name: str, future_or_fn, *args):
    try:
        return future_or_fn(*args)
    except Exception as exc:  # a bug, not an infeasible design: name the variant
        raise SweepError(f"variant {name!r} crashed: {type(exc).__name__}: {exc}") from exc


def run_sweep(sweep: Sweep, *, workers: int | None = None, dask: Any = None,
              progress: Progress | None = None, mp_context: str | None = None) -> list[dict]:
    """Evaluate every variant; the rows of the result table, in the sweep's variant order.

    ``dask``: a scheduler address (``"tcp://host:8786"``) or a ``distributed.Client`` runs
    the variants on that Dask cluster. Otherwise ``workers`` processes of a local pool
    (default ``os.cpu_count()``); ``workers=1`` runs serially in this process.
    ``progress(done, total)`` is called as variants finish. The rows are the same whichever
    way they were computed.

    Parameters
    ----------
    sweep : pollard_pin.sweep.grid.Sweep
        From :func:`~pollard_pin.make_sweep` or :func:`~pollard_pin.load_grid`.
    workers : int or None, optional
        Local processes (default every core).
    dask : str or distributed.Client or None, optional
        A Dask scheduler address or client (needs the ``cluster`` extra).
    progress : Callable or None, optional
        ``progress(done, total)``.
    mp_context : str or None, optional
        The local pool's start method (default ``"fork"`` where safe, else ``"spawn"``).

    Returns
    -------
    list of dict
        One row per variant (:func:`~pollard_pin.sweep.evaluate_variant`'s), in variant order.

    Raises
    ------
    SweepError
        A bad worker count or scheduler address, a Dask scheduler without
        ``dask.distributed``, a variant that crashed (a bug), a worker process that died.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> sweep = pp.make_sweep(grid={"bodies.gun.mass": [0.035, 0.05]}, samples=201)
    >>> rows = pp.run_sweep(sweep, workers=1)
    >>> [round(r["peak_tau_theta21"], 3) for r in rows]           # N·m
    [1.212, 1.26]

    The pool starts its workers with the multiprocessing start method ``mp_context``. The
    default is ``"fork"`` where the platform has it and this process runs a single Python
    thread (workers start at once, with everything imported), otherwise ``"spawn"`` (a fresh
    interpreter: safe in a threaded parent such as a Dask client or a GUI). Under ``"spawn"``
    or ``"forkserver"`` a script that calls this must guard its top level with
    ``if __name__ == "__main__":``, as with any such pool.
    """
    instance(sweep, "sweep", Sweep, "a Sweep (pollard_pin.make_sweep or load_grid)",
             error=SweepError)
    callback(progress, "progress", error=SweepError)
    specs = sweep.specs()
    if scheduler_address(dask, "dask", error=SweepError) is not None:
        return _run_dask(specs, dask, progress)
    n = len(specs)
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise SweepError(f"workers = {workers}: must be >= 1")
    rows: list[dict | None] = [None] * n
    if workers == 1 or n == 1:
        for k, spec in enumerate(specs):
            rows[k] = _checked(spec["name"], evaluate_variant, spec)
            if progress is not None:
                progress(k + 1, n)
        return rows  # type: ignore[return-value]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    if mp_context is None:
        import threading

        fork_ok = ("fork" in multiprocessing.get_all_start_methods()
                   and threading.active_count() == 1)
        mp_context = "fork" if fork_ok else "spawn"
    ctx = multiprocessing.get_context(mp_context)
    with ProcessPoolExecutor(max_workers=min(workers, n), mp_context=ctx) as pool:
        futures = {pool.submit(evaluate_variant, spec): k for k, spec in enumerate(specs)}
        try:
            for done, fut in enumerate(as_completed(futures), start=1):
                k = futures[fut]
                try:
                    rows[k] = _checked(specs[k]["name"], fut.result)
                except SweepError as exc:
                    if isinstance(exc.__cause__, BrokenProcessPool):
                        raise SweepError(
                            f"a worker process died ({exc.__cause__}); a script that runs a "
                            "sweep on the process pool needs an `if __name__ == '__main__':` "
                            "guard, or run it with workers=1") from exc.__cause__
                    raise
                if progress is not None:
                    progress(done, n)
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise
    return rows  # type: ignore[return-value]


def require_distributed():
    """The ``distributed`` module, or SweepError: a Dask scheduler needs the extra (checked
    before anything is said or done)."""
    try:
        import distributed
    except ImportError:
        raise SweepError("a Dask scheduler needs dask.distributed: "
                         "pip install 'pollard-pin[cluster]'") from None
    return distributed


def connect(address: Any, error: type[Exception] = SweepError) -> tuple[Any, bool]:
    """A ``distributed.Client`` for a scheduler ``address`` (connected now: an unreachable one
    is ``error``, one line, before any work), or ``address`` itself if it is a client; and
    whether the caller owns it (closes it when done)."""
    distributed = require_distributed()
    if isinstance(address, distributed.Client):
        return address, False
    try:
        return distributed.Client(address), True
    except (OSError, TimeoutError, ValueError) as exc:  # ValueError: a malformed address
        raise error(f"cannot connect to the Dask scheduler at {address!r}: {exc}") from None


def _run_dask(specs: list[dict], address: Any, progress: Progress | None) -> list[dict]:
    as_completed = require_distributed().as_completed
    client, own = connect(address)
    try:
        futures = client.map(evaluate_variant, specs, pure=False)
        index = {f.key: k for k, f in enumerate(futures)}
        rows: list[dict | None] = [None] * len(specs)
        try:
            for done, fut in enumerate(as_completed(futures), start=1):
                k = index[fut.key]
                rows[k] = _checked(specs[k]["name"], fut.result)
                if progress is not None:
                    progress(done, len(specs))
        except BaseException:
            client.cancel(futures)
            raise
        return rows  # type: ignore[return-value]
    finally:
        if own:
            client.close()
