"""The shipped examples and the common test jobs, each planned (or painted or sized by the CLI) once
per test session: every test that needs a plan, a film or an output folder of the same job
and inputs takes it from here (loaded by tests/conftest.py). A test that plans with other
inputs (another speed, a moved part, a patched knob) plans its own.

These values are read, never written: plans and jobs are frozen dataclasses, the arrays of
the plans and films are made read-only (:func:`_read_only`: a test writing into one fails),
and an output folder's files are checked unchanged when the session ends
(:func:`_unchanged`).

Under pytest-xdist each worker is a process with its own session fixtures: :func:`_once`
makes each plan (and output folder) once per run, in the first worker that asks; the others
read its pickle (the same numbers: a plan is deterministic)."""
import dataclasses
import fcntl
import os
import pickle
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


def _read_only(value, seen=None):
    """``value``, every numpy array reachable through its dataclass fields, tuples, lists and
    dicts made read-only (a robot's model excepted)."""
    seen = set() if seen is None else seen
    if id(value) in seen:
        return value
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        value.flags.writeable = False
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        if type(value).__name__ != "Robot":
            for f in dataclasses.fields(value):
                _read_only(getattr(value, f.name, None), seen)
    elif isinstance(value, (list, tuple)):
        for v in value:
            _read_only(v, seen)
    elif isinstance(value, dict):
        for v in value.values():
            _read_only(v, seen)
    return value


def _unchanged(folder: Path):
    """Yield ``folder``; at the session's end, fail if a test changed anything in it."""
    from cli_run import tree_state

    before = tree_state(folder)
    yield folder
    assert tree_state(folder) == before, f"a test wrote into the session's folder {folder}"


def run_folder(tmp_path_factory) -> Path:
    """The folder common to this run's workers (pytest-xdist: their base temp folders'
    parent), else this session's base temp folder."""
    base = tmp_path_factory.getbasetemp()
    return base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base


def _once(tmp_path_factory, name: str, make):
    """``make()`` once per run: the first worker to ask makes it and pickles it into
    :func:`run_folder`, the others wait for it (a file lock) and read the pickle. A value
    that does not pickle (or without cloudpickle) is made by each worker."""
    root = run_folder(tmp_path_factory)
    path = root / f"once-{name}.pickle"
    with open(root / f"once-{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if path.exists():
            return pickle.loads(path.read_bytes())
        value = make()
        try:  # cloudpickle (dask's) pickles a line plan's closures by value
            import cloudpickle

            data = cloudpickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:  # no cloudpickle, or something in it does not pickle
            return value
        part = path.with_suffix(".part")
        part.write_bytes(data)
        part.replace(path)
        return value


# --- the inputs ---------------------------------------------------------------------------
@pytest.fixture(scope="session")
def act():
    """examples/actuators.toml."""
    import pollard_pin as pp

    return pp.load_actuators(EXAMPLES / "actuators.toml")


@pytest.fixture(scope="session")
def job():
    """examples/paint.toml: a still panel."""
    import pollard_pin as pp

    return pp.load_job(EXAMPLES / "paint.toml")


@pytest.fixture(scope="session")
def line_job():
    """examples/line.toml: a strip longer than the reach on a line (docs/model.md §24)."""
    import pollard_pin as pp

    return pp.load_job(EXAMPLES / "line.toml")


@pytest.fixture(scope="session")
def line_part_job(tmp_path_factory):
    """A [part] on a [line] (docs/model.md §24): tests/line_parts.py's small strip."""
    from line_parts import write_line_part

    import pollard_pin as pp

    # one file for the run: its path is the job's source, in the plans the workers read
    return pp.load_job(_once(tmp_path_factory, "line_part_job",
                             lambda: write_line_part(tmp_path_factory.mktemp("line_part"))))


@pytest.fixture(scope="session")
def line_part_example_job():
    """examples/line_part.toml: the 0.90 m strip on a line."""
    import pollard_pin as pp

    return pp.load_job(EXAMPLES / "line_part.toml")


@pytest.fixture(scope="session")
def curved_job():
    """examples/parts/curved_panel.toml: a still part."""
    import pollard_pin as pp

    return pp.load_job(EXAMPLES / "parts" / "curved_panel.toml")


# --- plans and films, in this process -----------------------------------------------------
@pytest.fixture(scope="session")
def plan(robot, job, act, tmp_path_factory):
    """examples/paint.toml planned (plan_paint)."""
    from pollard_pin.painting.plan import plan_paint

    return _read_only(_once(tmp_path_factory, "plan", lambda: plan_paint(robot, job, act)))


@pytest.fixture(scope="session")
def film(plan, tmp_path_factory):
    """(U, V, points, Film) of :func:`plan` at the default grid (plan_film)."""
    from pollard_pin.painting.film import plan_film

    return _read_only(_once(tmp_path_factory, "film", lambda: plan_film(plan)))


@pytest.fixture(scope="session")
def line_plan(robot, line_job, act, tmp_path_factory):
    """examples/line.toml planned at its line speed (plan_line)."""
    from pollard_pin.painting.line.panel import plan_line

    return _read_only(_once(tmp_path_factory, "line_plan",
                            lambda: plan_line(robot, line_job, act)))


@pytest.fixture(scope="session")
def slow_plan(robot, line_job, act, tmp_path_factory):
    """examples/line.toml at 0.01 m/s, a third of its speed (plan_line, clearance not
    checked): refused before the dwell, it now waits at each turnaround (docs/model.md
    §24.1)."""
    from pollard_pin.painting.line.panel import plan_line

    return _read_only(_once(tmp_path_factory, "slow_plan", lambda: plan_line(
        robot, line_job, act, 0.01, clearance=False)))


@pytest.fixture(scope="session")
def line_plan_film(line_plan, tmp_path_factory):
    """(U, V, points, Film) of :func:`line_plan` at the default grid (line_film)."""
    from pollard_pin.painting.film.line import line_film

    return _read_only(_once(tmp_path_factory, "line_plan_film", lambda: line_film(line_plan)))


@pytest.fixture(scope="session")
def line_cell(robot, line_job, act, tmp_path_factory):
    """examples/line.toml as a cell of one robot at the origin (plan_cell)."""
    from pollard_pin.painting.cell.plan import plan_cell
    from pollard_pin.painting.cell.robots import CellRobot

    return _read_only(_once(tmp_path_factory, "line_cell", lambda: plan_cell(
        robot, replace(line_job, robots=(CellRobot("only"),)), act)))


@pytest.fixture(scope="session")
def line_part_plan(robot, line_part_job, act, tmp_path_factory):
    """:func:`line_part_job` planned at its line speed (plan_line), its strokes across the
    travel (``auto`` keeps along for this short strip: a shorter cycle, docs/model.md §24.2;
    a cell, and so a cell of one robot, strokes across)."""
    from pollard_pin.painting.line.panel import plan_line
    from pollard_pin.painting.policy import PlannerPolicy

    return _read_only(_once(tmp_path_factory, "line_part_plan", lambda: plan_line(
        robot, line_part_job, act, policy=PlannerPolicy(strokes="across"))))


@pytest.fixture(scope="session")
def line_part_film(line_part_plan, tmp_path_factory):
    """surface_film of :func:`line_part_plan` seen from the part, at the default spacing."""
    from pollard_pin.painting.film.part import surface_film

    return _read_only(_once(tmp_path_factory, "line_part_film",
                            lambda: surface_film(line_part_plan.in_part_frame())))


@pytest.fixture(scope="session")
def line_part_cell(robot, line_part_job, act, tmp_path_factory):
    """:func:`line_part_job` as a cell of one robot at the origin (plan_cell_job) and its
    film (cell_part_film): (job, plan, (points, film, painted mask, transfer efficiency))."""
    from pollard_pin.painting.cell.plan import plan_cell_job
    from pollard_pin.painting.cell.robots import CellRobot
    from pollard_pin.painting.film.cell import cell_part_film
    from pollard_pin.painting.spray.occlusion import load_painted_part

    job = replace(line_part_job, robots=(CellRobot("only"),))

    def make():
        cell = plan_cell_job(robot, job, act, load_painted_part(line_part_job))
        return cell, cell_part_film(cell)

    return (job, *_read_only(_once(tmp_path_factory, "line_part_cell", make)))


@pytest.fixture(scope="session")
def line_part_example_plan(robot, line_part_example_job, act, tmp_path_factory):
    """examples/line_part.toml planned at its line speed (plan_line)."""
    from pollard_pin.painting.line.panel import plan_line

    return _read_only(_once(tmp_path_factory, "line_part_example_plan",
                            lambda: plan_line(robot, line_part_example_job, act)))


@pytest.fixture(scope="session")
def curved_plan(robot, curved_job, act, tmp_path_factory):
    """examples/parts/curved_panel.toml planned (plan_surface)."""
    from pollard_pin.painting.plan.part import plan_surface

    return _read_only(_once(tmp_path_factory, "curved_plan",
                            lambda: plan_surface(robot, curved_job, act)))


@pytest.fixture(scope="session")
def ribbed_plan(robot, act, tmp_path_factory):
    """examples/parts/ribbed_plate.toml planned (plan_surface)."""
    import pollard_pin as pp
    from pollard_pin.painting.plan.part import plan_surface

    job = pp.load_job(EXAMPLES / "parts" / "ribbed_plate.toml")
    return _read_only(_once(tmp_path_factory, "ribbed_plan",
                            lambda: plan_surface(robot, job, act)))


@pytest.fixture(scope="session")
def panel_part_plan(robot, job, act, tmp_path_factory):
    """examples/paint.toml's panel as a two-triangle mesh (panel_part) planned by the surface
    planner (plan_surface); the part is ``plan.part``."""
    from pollard_pin.painting.job import PartJob
    from pollard_pin.painting.plan.part import plan_surface
    from pollard_pin.painting.workpiece.mesh import panel_part

    part = panel_part(job)
    pj = PartJob(mesh="<panel>", position=(0.0, 0.0, 0.0), standoff=job.standoff,
                 sigma=job.sigma, flow=job.flow, thickness=job.thickness, source="panel")
    return _read_only(_once(tmp_path_factory, "panel_part_plan",
                            lambda: plan_surface(robot, pj, act, part)))


@pytest.fixture(scope="session")
def panel_result(robot, job, act, tmp_path_factory):
    """examples/paint.toml painted with examples/actuators.toml (pp.paint, its default
    options)."""
    import pollard_pin as pp

    return _read_only(_once(tmp_path_factory, "panel_result", lambda: pp.paint(robot, job, act)))


@pytest.fixture(scope="session")
def figure8_sized(robot, tmp_path_factory):
    """examples/figure8.csv and its sizing with examples/actuators.toml
    (``actuator_sizing(robot, run_pipeline(robot, traj), act)``: its ``timing`` is
    ``time_optimal_path``'s of it): (traj, Sizing). (The actuators read here: a module may
    have its own ``act`` fixture.)"""
    import pollard_pin as pp
    from pollard_pin.dynamics.sizing import actuator_sizing

    def size():
        traj = pp.from_csv(EXAMPLES / "figure8.csv")
        act = pp.load_actuators(EXAMPLES / "actuators.toml")
        return traj, actuator_sizing(robot, pp.run_pipeline(robot, traj), act)

    return _read_only(_once(tmp_path_factory, "figure8_sized", size))


# --- the CLI's output folders -------------------------------------------------------------
THESIS_SAMPLES = 801


@pytest.fixture(scope="session")
def thesis_sized(tmp_path_factory):
    """`pollard-pin size --samples 801 --quiet --actuators examples/actuators.toml --retime
    DIR/fast.csv --format json --out DIR/r.json --plot DIR/fig` (every output of the sizing:
    the JSON report, the retimed file, the figures): (exit code, standard error, DIR)."""
    yield from _size(tmp_path_factory, "thesis_sized", [
        "--samples", THESIS_SAMPLES, "--quiet", "--actuators", EXAMPLES / "actuators.toml"],
        retime="fast.csv", out="r.json", plot="fig")


def _size(tmp_path_factory, name: str, args: list, **outputs):
    """`pollard-pin size ARGS --format json` with its ``outputs`` (``retime``, ``out``,
    ``plot``: file names) in a folder DIR, once per run (:func:`_once`), DIR checked
    unchanged at the session's end: yields (exit code, standard error, DIR)."""
    import contextlib
    import io

    from cli_run import check_refusal

    from pollard_pin.cli import main

    def size():
        folder = tmp_path_factory.mktemp(name)
        given = [x for k, v in outputs.items() for x in (f"--{k}", folder / v)]
        stdout, stderr = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
            code = main([str(a) for a in ("size", *args, "--format", "json", *given)])
        check_refusal(stderr.getvalue())
        return code, stderr.getvalue(), folder

    code, err, folder = _once(tmp_path_factory, name, size)
    for same in _unchanged(folder):
        yield code, err, same


@pytest.fixture(scope="session")
def panel_painted(tmp_path_factory):
    """`pollard-pin paint --job examples/paint.toml --out DIR`: DIR."""
    from pollard_pin.cli import main

    def paint():
        out = tmp_path_factory.mktemp("paint") / "out"
        assert main(["paint", "--job", str(EXAMPLES / "paint.toml"), "--out", str(out)]) == 0
        return out

    yield from _unchanged(_once(tmp_path_factory, "panel_painted", paint))


@pytest.fixture(scope="session")
def panel_sized(panel_painted, tmp_path_factory):
    """`pollard-pin size --trajectory P/path.csv --quiet --actuators examples/actuators.toml
    --retime DIR/rt.csv --format json --out DIR/r.json` of :func:`panel_painted`'s program P:
    (exit code, standard error, DIR)."""
    yield from _size(tmp_path_factory, "panel_sized", [
        "--trajectory", panel_painted / "path.csv", "--quiet", "--actuators",
        EXAMPLES / "actuators.toml"], retime="rt.csv", out="r.json")
