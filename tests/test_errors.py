"""The one exception root (pollard_pin/errors.py): every exception class defined anywhere in
the package derives from PollardError through one of its three families, and each family is
also the builtin it always was."""
import ast
import builtins
import importlib
import sys
from pathlib import Path

import pytest

from pollard_pin.errors import DestinationError, InputError, PollardError, SolveError

PACKAGE = Path(__file__).resolve().parent.parent / "pollard_pin"
FAMILIES = (InputError, SolveError, DestinationError)


def _local_class(node: ast.ClassDef, mod):
    """A stand-in for a class defined in a function: a class with the bases it names that
    resolve in its module or the builtins (a base it cannot resolve is left out)."""
    bases = []
    for b in node.bases:
        try:
            base = eval(ast.unparse(b), vars(mod), vars(builtins))  # names and attributes
        except Exception:  # a local name
            continue
        if isinstance(base, type):
            bases.append(base)
    return type(node.name, tuple(bases), {}) if bases else None


def _visit(node, mod, prefix, reachable, out):
    for child in ast.iter_child_nodes(node):
        if isinstance(child, ast.ClassDef):
            qual = prefix + child.name
            if reachable:
                obj = mod
                for part in qual.split("."):
                    obj = getattr(obj, part, None)
            else:  # a class made in a function: an exception if a base it names is one
                obj = _local_class(child, mod)
            if isinstance(obj, type) and issubclass(obj, Exception):
                out.append((mod.__name__, qual, obj))
            _visit(child, mod, qual + ".", reachable, out)
        elif isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
            _visit(child, mod, prefix + child.name + ".<locals>.", False, out)
        else:
            _visit(child, mod, prefix, reachable, out)


def _exception_classes(package: Path):
    """(module, qualified name, class) of every class statement in ``package`` whose class is
    an Exception (not BaseException-only signals such as KeyboardInterrupt); a class defined in
    a function is judged by the bases it names."""
    out = []
    for path in sorted(package.rglob("*.py")):
        if path.name == "__main__.py":  # importing it would run the CLI
            continue
        parts = path.relative_to(package.parent).with_suffix("").parts
        mod = importlib.import_module(".".join(parts).removesuffix(".__init__"))
        _visit(ast.parse(path.read_text(encoding="utf-8")), mod, "", True, out)
    return out


def _strays(package: Path, found=None):
    """Every exception class but the root that is in none of the families, or in more than
    one (a family's error that also claims another's: the rule in pollard_pin/errors.py
    sorts each error into one); of ``found`` (:func:`_exception_classes` of ``package``,
    walked here if None)."""
    found = _exception_classes(package) if found is None else found
    return [f"{m}.{q} ({', '.join(b.__name__ for b in c.__mro__[1:-1])})"
            for m, q, c in found
            if c is not PollardError and sum(issubclass(c, f) for f in FAMILIES) != 1]


def test_every_exception_class_derives_from_the_root():
    found = _exception_classes(PACKAGE)
    assert len(found) >= 30  # the walk sees the package's errors (32 when written)
    names = {q for _, q, _ in found}
    assert {"PlanError", "KinematicsError", "OutputError", "SweepError"} <= names
    strays = _strays(PACKAGE, found)  # the same walk (it took a second)
    assert not strays, "exceptions outside pollard_pin.errors' families:\n" + "\n".join(strays)


def test_the_walk_finds_a_stray(tmp_path, monkeypatch):
    """A class in two families, a plain ValueError subclass, one nested in a class and one
    defined in a function are all reported, family members and classes that are not exceptions
    are not: the test above can fail."""
    pkg = tmp_path / "strayed"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "sub" / "mod.py").write_text(
        "from pollard_pin.errors import InputError\n"
        "from pollard_pin.errors import SolveError\n"
        "class Fine(InputError):\n    pass\n"
        "class Both(InputError, SolveError):\n    pass\n"
        "class Plain(ValueError):\n    pass\n"
        "class Holder:\n    class Inner(RuntimeError):\n        pass\n"
        "def make():\n    class Local(OSError):\n        pass\n"
        "    class Fine2(InputError):\n        pass\n"
        "    class Rows:\n        pass\n    return Local\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        strays = _strays(pkg)
    finally:
        for m in [m for m in sys.modules if m == "strayed" or m.startswith("strayed.")]:
            del sys.modules[m]
    assert [s.split(" ")[0] for s in strays] == [
        "strayed.sub.mod.Both", "strayed.sub.mod.Plain", "strayed.sub.mod.Holder.Inner",
        "strayed.sub.mod.make.<locals>.Local"]


@pytest.mark.parametrize("family, builtin", [(InputError, ValueError),
                                             (SolveError, RuntimeError),
                                             (DestinationError, OSError)])
def test_families_are_their_builtins(family, builtin):
    assert issubclass(family, PollardError) and issubclass(family, builtin)
    assert str(family("one line")) == "one line"


def test_destination_error_is_its_message():
    """OSError's str would add errno and filename; the CLI prints the message alone."""
    assert str(DestinationError("cannot write x.csv: not a folder")) == \
        "cannot write x.csv: not a folder"
    assert str(DestinationError()) == "cannot write the output"


def test_the_named_pairs_agree():
    """The rule of pollard_pin/errors.py on the pairs it names: a pose out of reach is a
    SolveError whichever solver finds it, a malformed argument an InputError whichever layer
    reads it; the closed form's error keeps ValueError, the builtin it had as an InputError."""
    from pollard_pin.analytic.closed_form import (
        SingularPoseError,
        UnreachableError,
        WristSingularError,
    )
    from pollard_pin.analytic.taskspace import TaskInputError
    from pollard_pin.kinematics.errors import (
        KinematicsError,
        KinematicsInputError,
        SingularityError,
        UnreachablePoseError,
    )
    from pollard_pin.model.params import ParameterError

    for solve in (UnreachableError, WristSingularError, SingularPoseError, UnreachablePoseError,
                  SingularityError):
        assert issubclass(solve, SolveError) and not issubclass(solve, InputError), solve
    for bad in (KinematicsInputError, TaskInputError, ParameterError):
        assert issubclass(bad, InputError) and not issubclass(bad, SolveError), bad
    assert issubclass(UnreachableError, ValueError) and issubclass(KinematicsInputError, ValueError)
    assert not issubclass(KinematicsInputError, KinematicsError)


def test_the_rule_is_written_once():
    """The families' rule is pollard_pin/errors.py's docstring, and it settles the out-of-reach
    pose."""
    import pollard_pin.errors as errors

    doc = errors.__doc__
    assert "InputError" in doc and "SolveError" in doc and "DestinationError" in doc
    assert "out of reach is a :class:`SolveError`" in " ".join(doc.split())


def test_say_less_gives_the_first_version_within_the_longest_line(caplog):
    from pollard_pin.errors import LONGEST_LINE, MESSAGE_ROOM, say_less

    assert say_less("a" * LONGEST_LINE, "b", width=LONGEST_LINE) == "a" * LONGEST_LINE
    full, short = "a" * (MESSAGE_ROOM + 1), "b" * MESSAGE_ROOM
    assert say_less("fits  as\n it is", short) == "fits as it is"
    with caplog.at_level("INFO", logger="pollard_pin"):
        assert say_less(full, short, "c") == short
    assert full in caplog.text  # the full story is logged (-v)
    assert say_less(full, full + "d") == full + "d"  # none fits: the last, whole


def test_without_asides_drops_the_words_and_keeps_figures_and_names():
    from pollard_pin.errors import without_asides

    text = ("pass 3 is 1.2 m (run-on included) at (0.1, 0.2) m: a part facing the robot "
            "(part.facing)? (12 mm of margin)")
    assert without_asides(text) == ("pass 3 is 1.2 m at (0.1, 0.2) m: a part facing the robot "
                                    "(part.facing)? (12 mm of margin)")
