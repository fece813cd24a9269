"""The example scripts run and use the public API only."""
import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPTS = Path(__file__).resolve().parent.parent / "scripts"
EXAMPLES = {  # script → (arguments, text its output must contain, files it must write)
    "thesis_run.py": (["--samples", "401"], "| `theta21` |", ["run.csv"]),
    "custom_trajectory.py": ([], "wrote circle_run.csv", ["circle.csv", "circle_run.csv"]),
    "view.py": (["--html", "p.html"], "wrote p.html", ["p.html"]),
    "cross_check.py": ([], "Pinocchio vs thesis", []),
}
# the package root and its subpackages (their __all__: the public names), and the modules of
# viz the guide names
PUBLIC = {".".join(p.parent.relative_to(SCRIPTS.parent).parts)
          for p in (SCRIPTS.parent / "pollard_pin").rglob("__init__.py")
          if "cli" not in p.parts} | {
    "pollard_pin.viz.report", "pollard_pin.viz.viewer", "pollard_pin.viz.plots"}


# Runs each example script as ``__main__`` (runpy), in its own folder with its own argv and
# standard output, one after the other in ONE fresh interpreter: a process per script paid
# the package's import (~1.4 s of CPU) four times. Per script: its exit status (0, or 1 and
# the traceback on standard error) and what it printed.
_RUNNER = """
import contextlib, io, json, os, runpy, sys, traceback
done = {}
for name, script, args, folder in json.loads(sys.argv[1]):
    os.chdir(folder)
    sys.argv = [script, *args]
    out, err = io.StringIO(), io.StringIO()
    code = 0
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            runpy.run_path(script, run_name="__main__")
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        except BaseException:
            traceback.print_exc()
            code = 1
    done[name] = dict(returncode=code, stdout=out.getvalue(), stderr=err.getvalue())
print(json.dumps(done))
"""


@pytest.fixture(scope="module")
def examples_run(tmp_path_factory):
    """(results by script name, folder by script name) of every EXAMPLES script, run once."""
    folders = {name: tmp_path_factory.mktemp(name.removesuffix(".py")) for name in EXAMPLES}
    todo = [(name, str(SCRIPTS / name), EXAMPLES[name][0], str(folders[name]))
            for name in sorted(EXAMPLES)]
    # the package beside the scripts, not whichever checkout is installed
    env = {**os.environ, "PYTHONPATH": str(SCRIPTS.parent)}
    r = subprocess.run([sys.executable, "-c", _RUNNER, json.dumps(todo)],
                       cwd=tmp_path_factory.getbasetemp(), capture_output=True, text=True,
                       timeout=300, env=env)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.splitlines()[-1]), folders


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_example_script_runs(name, examples_run):
    args, expect, files = EXAMPLES[name]
    results, folders = examples_run
    r = results[name]
    assert r["returncode"] == 0, r["stderr"]
    assert expect in r["stdout"]
    for f in files:
        assert (folders[name] / f).stat().st_size > 0, f


@pytest.mark.parametrize("name", sorted(EXAMPLES) + ["make_docs.py"])
def test_example_script_uses_public_api(name):
    tree = ast.parse((SCRIPTS / name).read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module.startswith("pollard_pin"):
            assert node.module in PUBLIC, f"{name} imports {node.module}"
            assert not any(a.name.startswith("_") for a in node.names), name
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                and node.value.id == "pp":
            assert not node.attr.startswith("_"), f"{name} uses pp.{node.attr}"


@pytest.mark.slow  # only that it runs (6 s CPU); the ribbed plate's film is tested elsewhere
def test_bench_paint_quick_runs(tmp_path):
    """scripts/bench_paint.py --quick (the paint targets' figures; no asserts of its
    own): the ribbed plate's film at 5 mm with compliance, in a subprocess, prints its
    times and memory."""
    env = {**os.environ, "PYTHONPATH": str(SCRIPTS.parent)}
    r = subprocess.run([sys.executable, str(SCRIPTS / "bench_paint.py"), "--quick"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr
    line = r.stdout.splitlines()[-1]
    assert "ribbed plate film at 5 mm" in line and "peak memory" in line, r.stdout
    assert "film " in line and "compliance " in line, line  # paint.json's timings: it painted
