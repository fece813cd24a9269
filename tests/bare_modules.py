"""Run code in a fresh interpreter where pollard_pin's package ``__init__`` files do not run
and some modules cannot be imported: what a module needs is then its own import closure.

The package root imports every layer (pinocchio included) for its top-level names, so "module
X does not need Pinocchio" is a property of X's own imports: every ``pollard_pin`` package is
a stub module (its ``__path__`` only, so that its modules are found), and each hidden module is
``None`` in ``sys.modules`` (importing it raises ImportError).
"""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

PRELUDE = """\
import sys, types
from pathlib import Path
root = Path({package!r})
for init in sorted(root.rglob("__init__.py")):
    name = ".".join(init.parent.relative_to(root.parent).parts)
    stub = types.ModuleType(name)
    stub.__path__ = [str(init.parent)]
    stub.__package__ = name
    sys.modules[name] = stub
    if "." in name:
        parent, _, leaf = name.rpartition(".")
        setattr(sys.modules[parent], leaf, stub)
for hidden in {hidden!r}:
    sys.modules[hidden] = None
"""


def run_bare(code: str, hidden=("pinocchio",), timeout: float = 120):
    """The finished process of ``code`` run after the prelude (stub packages, hidden modules)."""
    prelude = PRELUDE.format(package=str(ROOT / "pollard_pin"), hidden=tuple(hidden))
    return subprocess.run([sys.executable, "-c", prelude + code], cwd=ROOT,
                          capture_output=True, text=True, timeout=timeout)
