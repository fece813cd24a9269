"""The package root (pollard_pin/__init__.py): the names a user calls, imported explicitly, and
a one-line pointer for each name that moved to its subpackage."""
import ast
import importlib
from pathlib import Path

import pytest

import pollard_pin as pp

INIT = Path(pp.__file__)


def test_the_root_imports_its_names_explicitly():
    """Every name of ``__all__`` is bound by an import statement of the root (no resolver),
    each once, and there are few enough to read (toppra's 15–40)."""
    tree = ast.parse(INIT.read_text(encoding="utf-8"))
    bound = [a.asname or a.name for n in tree.body if isinstance(n, ast.ImportFrom)
             for a in n.names]
    assert sorted(set(pp.__all__)) == sorted(pp.__all__) and len(pp.__all__) <= 55
    assert set(pp.__all__) <= set(bound)
    assert not [n for n in ast.walk(tree) if isinstance(n, ast.Call)
                and ast.unparse(n.func).endswith("import_module")]
    assert {"PollardError", "InputError", "SolveError", "DestinationError"} <= set(pp.__all__)
    assert pp.__version__ == importlib.import_module("pollard_pin.version").__version__


@pytest.mark.parametrize("name", sorted(pp._MOVED))
def test_a_moved_name_says_where_in_one_line(name):
    with pytest.raises(AttributeError) as info:
        getattr(pp, name)
    home = f"pollard_pin.{pp._MOVED[name]}"
    assert str(info.value) == f"pollard_pin.{name} moved: use {home}.{name}"
    module = importlib.import_module(home)
    assert hasattr(module, name), home  # the pointer points at the name
    if module.__file__.endswith("__init__.py"):  # a subpackage: its __all__ lists the name
        assert name in module.__all__, home


def test_moved_and_kept_are_apart_and_unknown_names_fail_as_usual():
    assert not set(pp._MOVED) & set(pp.__all__)
    with pytest.raises(AttributeError, match="^module 'pollard_pin' has no attribute 'nope'$"):
        pp.nope  # noqa: B018
    assert not hasattr(pp, "plan_paint") and hasattr(pp, "paint")


# A subpackage's public name that is also one of its modules' names hides the module
# (``import pollard_pin.x.y as m`` gives the name): the command line's entry point, and
# paint's place() beside its module (to move into painting/layout/).
HIDING = {("pollard_pin.cli", "main")}


def test_no_public_name_hides_a_module():
    package = Path(pp.__file__).parent
    hiding = set()
    for init in sorted(package.rglob("__init__.py")):
        name = ".".join(init.parent.relative_to(package.parent).parts)
        modules = {p.stem for p in init.parent.glob("*.py")} | {
            p.parent.name for p in init.parent.glob("*/__init__.py")}
        hiding |= {(name, n) for n in importlib.import_module(name).__all__ if n in modules}
    assert hiding == HIDING
