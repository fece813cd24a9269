"""The ``Examples`` of the public names' docstrings run and print what they say (doctest).

Every name of ``pollard_pin.__all__`` (and the methods of the public classes) is searched for
``>>>`` examples; each docstring runs as one doctest in a temporary folder, so an example may
write files. A wrong example fails with the doctest's report (expected vs got).
"""
import doctest
import inspect

import pytest

import pollard_pin as pp

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def _public_objects():
    for name in pp.__all__:
        obj = getattr(pp, name)
        if name == "paint":  # the callable subpackage: its entry point holds the docstring
            from pollard_pin.paint.api import paint as obj
        if inspect.isclass(obj) or inspect.isfunction(obj):
            yield name, obj


def _doctests():
    finder = doctest.DocTestFinder(exclude_empty=True)
    found = {}
    for name, obj in _public_objects():
        for test in finder.find(obj, name, module=inspect.getmodule(obj)):
            if test.examples:
                found.setdefault(f"{obj.__module__}.{test.name}", test)
    return found


DOCTESTS = _doctests()


def test_the_public_api_has_examples():
    # a floor, so that a finder that finds nothing (a renamed module, a lost docstring)
    # fails here instead of passing vacuously
    assert len(DOCTESTS) >= 40, sorted(DOCTESTS)


@pytest.mark.parametrize("key", sorted(DOCTESTS))
def test_docstring_example(key, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    test = DOCTESTS[key]
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    report = []
    runner.run(test, out=report.append, clear_globs=True)
    assert runner.failures == 0, "".join(report)
