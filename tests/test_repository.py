"""The repository stands on its own: nothing points outside it, the package's layers import one
way, every core dependency is used, and each optional one that is missing gives one clear line.
"""
import ast
import functools
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "pollard_pin"
# What a file would name to point outside the repository (the project's model document is
# docs/model.md). Built from parts, so that this file names none of them and is checked too.
OUTSIDE = tuple("".join(parts) for parts in (("..", "/", "shared"), ("model", "-spec"),
                                              ("/", "work", "/"), ("verified", "-facts")))


def _tracked_files():
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True,
                             check=True).stdout.decode()
        return [ROOT / f for f in out.split("\0") if f]
    except (OSError, subprocess.CalledProcessError):  # not a checkout: every file but the venv
        return [f for f in ROOT.rglob("*") if f.is_file() and ".venv" not in f.parts
                and ".git" not in f.parts]


def test_no_tracked_file_points_outside_the_repository():
    bad = []
    for f in _tracked_files():
        if not f.is_file():
            continue
        try:
            text = f.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue  # pictures
        bad += [f"{f.relative_to(ROOT)}: {s}" for s in OUTSIDE if s in text]
    assert not bad, "files that refer to something outside the repository:\n" + "\n".join(bad)


def test_citations_point_into_the_model_document():
    sections = {int(line.split()[1].rstrip(".")) for line in
                (ROOT / "docs" / "model.md").read_text(encoding="utf-8").splitlines()
                if line.startswith("## ") and line.split()[1].rstrip(".").isdigit()}
    import re

    cited = set()
    for f in _tracked_files():
        if f.suffix in (".py", ".md", ".toml", ".urdf", ".srdf"):
            for m in re.finditer(r"model\.md ((?:§\d+(?:[–,-] ?)?)+)", f.read_text("utf-8")):
                cited |= {int(n) for n in re.findall(r"§(\d+)", m.group(1))}
    assert cited and cited <= sections, f"cited sections missing: {sorted(cited - sections)}"


# --- layers --------------------------------------------------------------------------------
# Lower rank = lower layer; a module may import only modules of its own rank or below. The
# joint vocabulary and the numpy-only analytic leaves (jets, task-space conventions, the closed
# form) sit under the model, which uses the closed form for its home posture (docs/model.md §9).
RANKS = [
    ("pollard_pin.version", 0), ("pollard_pin.timing", 0), ("pollard_pin.errors", 0),
    ("pollard_pin.checks", 0), ("pollard_pin.names", 0),
    ("pollard_pin.film_scale", 0),  # the film's colours: any writer's, any figure's
    ("pollard_pin.compiled", 0),  # the compiled loops' loader: the kinematics' and the spray's
    ("pollard_pin.analytic.jet", 0),
    ("pollard_pin.analytic.taskspace", 0), ("pollard_pin.analytic", 1),
    ("pollard_pin.model", 2), ("pollard_pin.paths", 2), ("pollard_pin.kinematics", 3),
    ("pollard_pin.dynamics", 4),
    ("pollard_pin.io", 5), ("pollard_pin.workspace", 6), ("pollard_pin.painting", 6),
    ("pollard_pin.crosscheck", 6),
    ("pollard_pin.run", 7), ("pollard_pin.viz", 8),
    ("pollard_pin.outputs", 9),  # paint's outputs: written, read back, the result that writes
    ("pollard_pin.sweep", 10), ("pollard_pin.synthesis", 10),
    ("pollard_pin.cli", 11), ("pollard_pin", 12),
]
def _rank(module: str) -> int:
    return next(r for prefix, r in RANKS if module == prefix or module.startswith(prefix + "."))


@functools.cache
def _package_trees() -> dict:
    """{path: syntax tree} of every module of the package, parsed once for the tests that
    read its import statements (not to be modified)."""
    return {p: ast.parse(p.read_text(encoding="utf-8")) for p in sorted(PACKAGE.rglob("*.py"))}


@functools.cache
def _module_imports():
    """{module: {imported pollard_pin module}} from every import statement (lazy ones too);
    made once (the two tests of the layers read it, neither modifies it)."""
    files = {".".join(p.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__"): p
             for p in _package_trees()}
    graph = {}
    for mod, path in files.items():
        pkg = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
        out = set()
        for node in ast.walk(_package_trees()[path]):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = pkg.split(".")[: len(pkg.split(".")) - node.level + 1] if node.level \
                    else []
                stem = ".".join(base + ([node.module] if node.module else []))
                # ``from package import module`` depends on the module, not the package
                names = [f"{stem}.{a.name}" if f"{stem}.{a.name}" in files else stem
                         for a in node.names]
            else:
                continue
            for n in names:
                while n and n not in files:
                    n = n.rpartition(".")[0]
                if n and n != mod:
                    out.add(n)
        graph[mod] = out
    return graph


def test_layers_import_one_way():
    graph = _module_imports()
    assert len(graph) > 20
    upward = [f"{m} (rank {_rank(m)}) imports {t} (rank {_rank(t)})"
              for m, ts in graph.items() for t in ts
              if _rank(t) > _rank(m) and not (m == "pollard_pin" or t == "pollard_pin")]
    assert not upward, "\n".join(upward)


def test_no_import_cycle_between_modules():
    graph = {m: {t for t in ts if t != "pollard_pin" and not m.startswith(t + ".")}
             for m, ts in _module_imports().items()}
    state = {}

    def visit(m, path):
        state[m] = "open"
        for t in graph.get(m, ()):
            if state.get(t) == "open":
                pytest.fail("import cycle: " + " -> ".join(path + [m, t]))
            if t not in state:
                visit(t, path + [m])
        state[m] = "done"

    for m in graph:
        if m not in state:
            visit(m, [])


# --- dependencies ---------------------------------------------------------------------------
IMPORT_NAME = {"pin": "pinocchio", "numpy": "numpy", "scipy": "scipy",
               "matplotlib": "matplotlib", "meshcat": "meshcat", "tqdm": "tqdm",
               "polars": "polars", "pyarrow": "pyarrow"}


def test_every_core_dependency_is_imported_by_the_package():
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    names = {d.split(">")[0].split("<")[0].split("=")[0].strip() for d in deps}
    assert not names & {"example-robot-data", "yourdfpy"}, "test-only packages in the core"
    imported = set()
    for tree in _package_trees().values():
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                imported |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and not node.level:
                imported.add(node.module.split(".")[0])
    # trimesh's ray engines: the package asks trimesh for rays, trimesh imports these
    names -= {"embreex", "rtree"}
    unused = [n for n in names if IMPORT_NAME.get(n, n) not in imported]
    assert not unused, f"core dependencies no module imports: {unused}"


def _run_hidden(module: str, code: str):
    """Run ``code`` in a fresh interpreter where ``import module`` fails."""
    prelude = f"import sys; sys.modules[{module!r}] = None\n"
    return subprocess.run([sys.executable, "-c", prelude + code], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)


def _one_line(text: str) -> str:
    lines = [ln for ln in text.strip().splitlines() if ln.strip()]
    assert len(lines) == 1 and "Traceback" not in text, text
    return lines[0]


def test_mujoco_missing_gives_one_line():
    r = _run_hidden("mujoco", "from pollard_pin.crosscheck.mujoco import build_mujoco\n"
                              "try:\n    build_mujoco()\n"
                              "except ImportError as e:\n    print(e)\n")
    assert r.returncode == 0, r.stderr
    assert "pip install 'pollard-pin[mujoco]'" in _one_line(r.stdout)


def test_dask_missing_gives_one_line():
    r = _run_hidden("distributed", "import sys; from pollard_pin.cli import main\n"
                    "sys.exit(main(['sweep', '--grid', 'examples/sweep.toml', '--dask', "
                    "'tcp://127.0.0.1:1', '--out', 'never.csv']))")
    assert r.returncode == 2, r.stderr
    assert "pip install 'pollard-pin[cluster]'" in r.stderr.splitlines()[-1]
    assert "Traceback" not in r.stderr and not (ROOT / "never.csv").exists()


def test_chromium_missing_gives_one_line_and_writes_nothing():
    before = {p: p.stat().st_mtime_ns for p in (ROOT / "docs").rglob("*.png")}
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_docs.py")], cwd=ROOT,
                       capture_output=True, text=True, timeout=120,
                       env={"PATH": "/usr/bin:/bin", "POLLARD_CHROMIUM": "/nonexistent/chrome"})
    assert r.returncode == 1
    assert "needs Chromium" in _one_line(r.stderr)
    assert before == {p: p.stat().st_mtime_ns for p in (ROOT / "docs").rglob("*.png")}


# --- tests mirror the package ---------------------------------------------------------------
# tests/<layer>/test_<module>.py for pollard_pin/<layer>/<module>.py (top level:
# tests/test_<module>.py), one to one; CLI tests under tests/cli/.
# Test files that mirror no single module, on purpose.
UNMIRRORED_TESTS = {
    "tests/test_repository.py",  # the repository as a whole
    "tests/test_scripts.py",  # scripts/
    "tests/test_docs.py",  # docs/: the site's sources
    # the CLI fuzz suite, every command's bad input: tests/cli/test_fuzz*.py (by class)
    "tests/kinematics/test_solver_edges.py",  # edge cases across ik_*, singularity, closure
    "tests/painting/test_real_meshes.py",  # third-party meshes through place and paint
    "tests/test_doc_examples.py",  # the public names' docstring examples, across layers
    "tests/cli/test_paint_line.py",  # paint of the line kinds end to end (cli/paint.py)
    "tests/test_init.py",  # the package root: its names and the moved names' pointers
}


def _mirror(module: Path) -> Path:
    rel = module.relative_to(PACKAGE)
    return ROOT / "tests" / rel.parent / f"test_{rel.name}"


def _package_modules():
    return sorted(p for p in PACKAGE.rglob("*.py")
                  if p.name not in ("__init__.py", "__main__.py"))


def test_every_module_has_its_mirror_test_file():
    missing = [f"{m.relative_to(ROOT)} -> {_mirror(m).relative_to(ROOT)}"
               for m in _package_modules() if not _mirror(m).is_file()]
    assert not missing, "modules without their mirror test file:\n" + "\n".join(missing)


def test_every_test_file_mirrors_a_module():
    mirrors = {_mirror(m) for m in _package_modules()}
    stray = [str(t.relative_to(ROOT)) for t in sorted((ROOT / "tests").rglob("test_*.py"))
             if t not in mirrors and str(t.relative_to(ROOT)) not in UNMIRRORED_TESTS
             and not (t.parent.name == "cli" and t.name.startswith("test_fuzz"))]
    assert not stray, "test files that mirror no module:\n" + "\n".join(stray)
    # and the mirror rule is the one the check above uses
    assert _mirror(PACKAGE / "painting" / "plan.py") == ROOT / "tests" / "painting" / "test_plan.py"
    assert _mirror(PACKAGE / "errors.py") == ROOT / "tests" / "test_errors.py"


def test_the_wheel_lists_every_package_folder():
    """pyproject.toml names its packages one by one: every folder with an __init__.py is
    among them, or a plain install leaves it out (and fails at its first import)."""
    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
                 ["packages"])
    folders = {".".join(p.parent.relative_to(ROOT).parts) for p in PACKAGE.rglob("__init__.py")}
    assert folders - listed == set(), f"package folders missing from pyproject: {folders - listed}"
