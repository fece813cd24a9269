"""The version is written once, in a leaf module: pyproject.toml, the installed metadata and
the package root all read it from there, and the leaf imports nothing."""
import ast
import importlib.metadata
import tomllib
from pathlib import Path

import pollard_pin
from pollard_pin import version

ROOT = Path(__file__).resolve().parent.parent


def test_the_version_is_written_once():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert "version" not in project["project"] and "version" in project["project"]["dynamic"]
    attr = project["tool"]["setuptools"]["dynamic"]["version"]["attr"]
    assert attr == "pollard_pin.version.__version__"
    assert importlib.metadata.version("pollard-pin") == version.__version__
    assert pollard_pin.__version__ is version.__version__


def test_the_version_module_is_a_leaf():
    tree = ast.parse(Path(version.__file__).read_text(encoding="utf-8"))
    assert not [n for n in ast.walk(tree) if isinstance(n, ast.Import | ast.ImportFrom)]
