"""Where a study's designs are evaluated (synthesis/backends.py): in this process, on a local
pool, on a Dask cluster, each design's outcome is the same; the screen gates the full plan."""
import pytest
import synthesis_stub as stub

from pollard_pin.errors import InputError, SolveError
from pollard_pin.synthesis.backends import SerialRunner, failure, make_runner, run_design

CTX = {"speed": 0.012, "shift": 0.0}
GOOD = {"chain0.x32": 0.35, "y": 0.5, "motor": 0, "robots": 1}
BAD = {"chain0.x32": 0.30, "y": 0.1, "motor": 0, "robots": 1}  # out of reach


def _all(runner, designs):
    for k, values in enumerate(designs):
        runner.submit(k, values)
    out = {}
    while len(out) < len(designs):
        out.update(runner.done())
    return [out[k] for k in range(len(designs))]


def test_the_screen_gates_the_full_plan():
    good, bad = run_design(GOOD, CTX, stub.evaluate), run_design(BAD, CTX, stub.evaluate)
    assert good.final.level == "full" and good.final.feasible and good.seconds >= 0
    assert bad.final.level == "screen" and bad.final.binding == "reach"
    assert run_design(GOOD, CTX, stub.evaluate, level="screen").final.level == "screen"


def test_pool_and_dask_give_the_serial_outcomes():
    from distributed import LocalCluster

    designs = [dict(GOOD, y=y) for y in (0.1, 0.5, 0.9)] + [BAD]
    serial = _all(SerialRunner(CTX, stub.evaluate), designs)
    with make_runner(CTX, stub.evaluate, workers=2) as pool:
        pooled = _all(pool, designs)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster:
        with make_runner(CTX, stub.evaluate, dask=cluster.scheduler_address) as runner:
            assert runner.capacity == 4
            dasked = _all(runner, designs)
    for a, b, c in zip(serial, pooled, dasked):
        assert a.final == b.final == c.final


def _raises(values, ctx, level="screen"):
    raise SolveError("cannot reach")


def test_an_evaluation_that_raises_comes_back_as_its_exception():
    (outcome,) = _all(SerialRunner(CTX, _raises), [GOOD])
    assert isinstance(outcome, SolveError) and failure(outcome) == "cannot reach"
    assert failure(ZeroDivisionError("x")) == "ZeroDivisionError: x"


def test_bad_runner_options_are_one_line():
    with pytest.raises(InputError, match="workers = 0"):
        make_runner(CTX, stub.evaluate, workers=0)
    with pytest.raises(InputError, match="an empty scheduler address"):
        make_runner(CTX, stub.evaluate, dask=" ")
    import dask

    with dask.config.set({"distributed.comm.timeouts.connect": "0.5s"}), \
            pytest.raises(SolveError, match="cannot connect to the Dask scheduler"):
        make_runner(CTX, stub.evaluate, dask="tcp://127.0.0.1:1")


def _blas(values, ctx, level="screen"):
    """The worker's BLAS libraries' thread counts, as threadpoolctl reads them."""
    from threadpoolctl import threadpool_info

    return [p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"]


def test_pool_workers_run_one_blas_thread():
    """A pool worker (forked: numpy's OpenBLAS already loaded with a thread per core) runs one
    BLAS thread: the workers are one per core already. (The test's own process is given two
    first: under xdist tests/conftest.py limits it to one, which the fork would inherit.)"""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=2, user_api="blas"):
        assert set(_blas(None, None)) == {2}  # what the fork inherits, before the runner's
        with make_runner(CTX, _blas, workers=2) as pool:
            (outcome,) = _all(pool, [GOOD])
    counts = outcome.final
    assert counts and set(counts) == {1}
