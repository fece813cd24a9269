"""Session fixtures: one loaded robot, the examples planned once (tests/examples_planned.py);
``slow`` tests run only with --runslow; one BLAS/OpenMP thread in each of several workers."""
import os

import pytest

pytest_plugins = ["examples_planned"]


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true", default=False,
                     help="also run tests marked slow (each > 60 s, needing a full install, "
                          "or only checking that a script runs)")


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: long test, skipped unless --runslow is given")
    if int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1")) > 1:
        one_thread_per_worker(config)


def one_thread_per_worker(config):
    """The xdist workers are one per core (-n auto): numpy's OpenBLAS and pinocchio's OpenMP
    with a thread per core each oversubscribe them (measured: the heaviest files' wall time
    -15 %). One thread in this worker (threadpoolctl, kept until the session ends) and in the
    processes it starts (their environment)."""
    from threadpoolctl import threadpool_limits

    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(name, "1")
    config.stash[LIMITS] = threadpool_limits(limits=1)


LIMITS = pytest.StashKey[object]()


# The files whose tests take longest (each over 4 s: they plan paint jobs, search line speeds,
# build a venv), longest first. `make test` hands whole files to its workers in collection
# order (--dist loadfile --no-loadscope-reorder), the next file to whichever worker is short of
# work: these go first (longest processing time first), so that the end of the run is files
# of a few seconds and both workers finish together. Only the order changes; a file missing
# here runs after them, as collected. The order: `--durations=0` of a whole run, summed per
# file (session plans land in the first file that asks for them).
HEAVY_FIRST = (
    "cli/test_paint_line.py",
    "dynamics/test_timeopt.py",
    "painting/cell/test_plan.py",
    "outputs/test_paint_cell_files.py",
    "cli/test_paint.py",
    "painting/line/test_phases.py",
    "painting/layout/test_cell.py",
    "painting/test_real_meshes.py",
    "cli/test_size.py",
    "model/test_build.py",
    "painting/line/test_part.py",
    "test_docs.py",
    "cli/test_fuzz.py",
    "cli/test_fuzz_output.py",
    "painting/plan/test_panel.py",
    "synthesis/test_study.py",
    "painting/line/test_panel.py",
    "cli/test_view.py",
    "painting/checks/test_cell_compliance.py",
    "io/test_retime.py",
    "painting/layout/test_place.py",
    "dynamics/test_passes.py",
    "sweep/test_backends.py",
    "cli/test_main.py",
    "painting/line/test_speeds.py",
    "dynamics/test_cycle.py",
    "viz/test_viewer.py",
    "test_doc_examples.py",
    "cli/test_workspace.py",
    "synthesis/test_evaluation.py",
    "outputs/test_result.py",
    "test_repository.py",
    "painting/spray/test_occlusion.py",
    "painting/film/test_part.py",
    "cli/test_plot.py",
)


def _heavy_rank(item) -> int:
    path = item.path.as_posix()
    return next((i for i, name in enumerate(HEAVY_FIRST) if path.endswith("/tests/" + name)),
                len(HEAVY_FIRST))


def pytest_collection_modifyitems(config, items):
    items.sort(key=_heavy_rank)  # stable: within a file, and past the list, as collected
    if config.getoption("--runslow"):
        return
    skip = pytest.mark.skip(reason="slow: run with --runslow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


@pytest.fixture(scope="session")
def robot():
    """The shipped model, ``pollard_pin.load()``. Tests must not modify ``robot.model``."""
    import pollard_pin

    return pollard_pin.load()


@pytest.fixture(scope="module")
def one_parser_per_module():
    """The CLI parsed by one parser for the whole module (tests/cli_run.one_parser)."""
    from cli_run import one_parser

    with one_parser():
        yield
