"""The cyclic garbage collector paused while pytest collects (loaded by pyproject.toml's
``addopts``, ``-p collection_gc``): rewriting the test modules' asserts makes millions of
short-lived syntax nodes, and with the package and its dependencies imported every full
collection walked their whole heap, about 3 s of the 10 s of CPU each worker spent collecting.
Back on once collected; nothing else changes (no test reads the collector)."""
import gc

import pytest


@pytest.hookimpl(wrapper=True)
def pytest_collection(session):
    was = gc.isenabled()
    gc.disable()
    try:
        return (yield)
    finally:
        if was:
            gc.enable()
