"""Session fixtures: one loaded robot, the examples planned once (tests/examples_planned.py);
``slow`` tests run only with --runslow."""
import pytest

pytest_plugins = ["examples_planned"]


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true", default=False,
                     help="also run tests marked slow (each > 60 s or needing a full install)")


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: long test, skipped unless --runslow is given")


# The files whose tests take longest (each tens of CPU seconds: they plan paint jobs, search
# line speeds, build a venv), heaviest first. `make test` hands whole files to its workers in
# collection order (--dist loadfile --no-loadscope-reorder): these go first, so that the many
# quick files fill in behind them and neither worker is left with a long file at the end.
# Only the order changes; a file missing here runs after them, as collected.
HEAVY_FIRST = (
    "cli/test_paint_line.py",
    "outputs/test_paint_cell_files.py",
    "dynamics/test_timeopt.py",
    "painting/cell/test_plan.py",
    "model/test_build.py",
    "cli/test_paint.py",
    "cli/test_size.py",
    "painting/line/test_phases.py",
    "painting/layout/test_cell.py",
    "painting/plan/test_panel.py",
    "painting/line/test_panel.py",
    "painting/line/test_speeds.py",
    "painting/line/test_part.py",
    "cli/test_fuzz_output.py",
    "cli/test_main.py",
    "cli/test_paint_robots.py",
    "painting/layout/test_place.py",
    "outputs/test_result.py",
    "test_doc_examples.py",
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
