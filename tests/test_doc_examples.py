"""The ``Examples`` of the public names' docstrings run and print what they say (doctest).

Every public name (the top level's ``__all__`` and every subpackage's, tests/public_names.py;
and the methods of the public classes), and the cross-check modules, are searched for ``>>>``
examples; each docstring runs as one doctest in a temporary folder, so an example may write
files. A wrong example fails with the doctest's report (expected vs got). Every public name's
parameters must appear in its numpydoc ``Parameters`` or ``Attributes`` section.
"""
import doctest
import importlib
import inspect

import pytest
from public_names import public_objects

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def _public_objects():
    """(name, object) of every public class and function (tests/public_names.py: the top
    level's and every subpackage's ``__all__``), each once."""
    for full, obj in public_objects().items():
        if inspect.isclass(obj) or inspect.isfunction(obj):
            yield full.removeprefix("pollard_pin."), obj


# Modules whose every docstring example runs too: the engines the tests compare against.
MODULES = ("pollard_pin.crosscheck.euler_lagrange", "pollard_pin.crosscheck.compare")


def _doctests():
    finder = doctest.DocTestFinder(exclude_empty=True)
    found = {}
    for name, obj in _public_objects():
        for test in finder.find(obj, name, module=inspect.getmodule(obj)):
            if test.examples:
                found.setdefault(f"{obj.__module__}.{test.name}", test)
    for module in map(importlib.import_module, MODULES):
        for test in finder.find(module):
            if test.examples:
                found.setdefault(test.name, test)
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


def _documented_names(doc: str, section: str) -> set[str]:
    """The names a numpydoc section lists (``a, b : type`` lines; ``*args``/``**kw`` bare)."""
    lines = inspect.cleandoc(doc).splitlines() + [""]

    def title(i):  # a section title: a line underlined by dashes
        return bool(lines[i].strip()) and set(lines[i + 1].strip()) == {"-"}

    starts = [i for i in range(len(lines) - 1) if title(i) and lines[i].strip() == section]
    names = set()
    for start in starts:
        for i in range(start + 2, len(lines) - 1):
            if title(i):
                break
            line = lines[i]
            if line.strip() and not line.startswith(" "):
                names.update(n.strip().lstrip("*") for n in line.split(" : ")[0].split(","))
    return names


def _signature_names(obj) -> list[str]:
    target = obj.__init__ if inspect.isclass(obj) else obj
    try:
        params = inspect.signature(target).parameters
    except (TypeError, ValueError):
        return []
    return [n for n in params if n not in ("self", "cls")]


def _undocumented():
    missing = {}
    for name, obj in _public_objects():
        if inspect.isclass(obj) and issubclass(obj, Exception):
            continue  # errors: one line of what and where, no parameters to list
        doc = inspect.getdoc(obj) or ""
        listed = _documented_names(doc, "Parameters") | _documented_names(doc, "Attributes")
        gaps = [n for n in _signature_names(obj) if n not in listed]
        if gaps:
            missing[name] = gaps
    return missing


def test_public_names_document_their_parameters():
    missing = _undocumented()
    assert not missing, f"parameters missing from the numpydoc sections: {missing}"
