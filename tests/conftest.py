"""Session fixtures: one loaded robot, the examples planned once (tests/examples_planned.py);
``slow`` tests run only with --runslow."""
import pytest

pytest_plugins = ["examples_planned"]


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true", default=False,
                     help="also run tests marked slow (each > 60 s or needing a full install)")


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: long test, skipped unless --runslow is given")


def pytest_collection_modifyitems(config, items):
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
