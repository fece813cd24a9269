"""pollard_pin.paint (painting/api.py): one entry point for every job kind, the kind looked up
in the table (each kind's film and report against its own planner's:
tests/painting/kinds/test_<kind>.py); a job it cannot paint is a PollardError naming the
kind; hostile parts; every example keeps the report's invariants."""
import importlib
from pathlib import Path

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.errors import InputError, PollardError
from pollard_pin.painting.errors import JobKindError
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.plan import plan_paint


def test_a_job_of_another_kind_is_named(robot, act, job):
    """Anything but a paint job: a PollardError naming its type, before any planning;
    plan_paint, the still panel's planner, refuses a part and a line by their kind."""
    with pytest.raises(JobKindError, match="cannot paint a dict") as info:
        pp.paint(robot, {"panel": {}}, act)
    assert isinstance(info.value, PollardError) and "\n" not in str(info.value)
    root = Path(__file__).resolve().parents[2]
    part = pp.load_job(root / "examples" / "parts" / "curved_panel.toml")
    with pytest.raises(JobKindError, match="not a part"):
        plan_paint(robot, part, act)
    line = pp.load_job(root / "examples" / "line.toml")
    with pytest.raises(JobKindError, match="not a line panel"):
        plan_paint(robot, line, act)
    with pytest.raises(InputError, match="no \\[line\\]"):
        pp.paint(robot, job, act, PaintOptions(max_line_speed=True))
    with pytest.raises(InputError, match="speeds: the panel job has no \\[line\\]"):
        pp.paint(robot, job, act, PaintOptions(speeds=True))


@pytest.mark.parametrize("knobs, named", [
    ({"seams": (0.1,)}, "PlannerPolicy.seams: a cell's"),
    ({"seam_run": 0.0, "smoothing": 0.05}, "PlannerPolicy.seam_run, smoothing: a cell's"),
])
def test_a_cells_knobs_on_one_robot_are_refused(robot, act, job, knobs, named):
    """A cell's knobs of the policy, which only the cell's planner reads, on a job of one
    robot: one line naming them, before any planning (not silently dropped)."""
    from pollard_pin.painting.policy import PlannerPolicy

    policy = PlannerPolicy(**knobs)
    assert policy.cell_knobs() == tuple(knobs) and PlannerPolicy().cell_knobs() == ()
    with pytest.raises(InputError, match=named) as info:
        pp.paint(robot, job, act, PaintOptions(policy=policy))
    assert "the panel job has one robot" in str(info.value) and "\n" not in str(info.value)


def test_paint_is_a_plain_function():
    """pp.paint is a plain function (outputs/result.py: painting.api.paint_job's result as one
    that writes itself); the subpackage is pollard_pin.painting, not callable."""
    import types

    import pollard_pin.outputs.result as result

    assert pp.paint is result.paint and isinstance(pp.paint, types.FunctionType)
    assert not callable(importlib.import_module("pollard_pin.painting"))


def test_every_example_job_has_a_kind():
    """The shipped jobs: each a kind pp.paint dispatches on (the CLI tests paint them)."""
    from pollard_pin.painting.job import job_kind

    root = Path(__file__).resolve().parents[2] / "examples"
    kinds = {p.name: job_kind(pp.load_job(p)) for p in
             [root / "paint.toml", root / "line.toml", root / "line_part.toml",
              *sorted((root / "parts").glob("*.toml"))]}
    assert kinds["paint.toml"] == "panel" and kinds["line.toml"] == "line panel"
    assert kinds["line_part.toml"] == "line part"
    assert {kinds[k] for k in kinds if k.endswith("plate.toml") or k == "curved_panel.toml"
            } == {"part"}


# --- hostile parts: a duplicated mesh, faces hidden, a table top ------------------------------
def _plate_obj(x=0.70, n=4, half=0.06, zc=0.16, normal_x=-1.0):
    """An n × n grid of squares (2n² triangles) in the plane x = ``x``, 2·half wide,
    centred at (x, 0, zc), outward normal (normal_x, 0, 0): OBJ text without faces, faces."""
    ys = np.linspace(-half, half, n + 1)
    zs = np.linspace(zc - half, zc + half, n + 1)
    verts = "".join(f"v {x} {y} {z}\n" for z in zs for y in ys)
    faces = []
    for i in range(n):
        for j in range(n):
            a = i * (n + 1) + j
            b, c, e = a + 1, a + n + 1, a + n + 2
            faces += [(a, c, b), (b, c, e)] if normal_x < 0 else [(a, b, c), (b, e, c)]
    return verts, faces


def _part_job(tmp_path, name, text, facing=(-1.0, 0.0, 0.0)):
    (tmp_path / name).write_text(text)
    job = tmp_path / f"{name}.toml"
    job.write_text(f'[part]\nmesh = "{name}"\nposition = [0.0, 0.0, 0.0]\n'
                   f"facing = {list(facing)}\n[gun]\n"
                   "standoff = 0.15\nsigma = 0.010\nflow = 1.5e-7\n[job]\nthickness = 25e-6\n")
    return pp.load_job(job)


def _obj(verts, faces, first=1):
    return verts + "".join(f"f {a + first} {b + first} {c + first}\n" for a, b, c in faces)


@pytest.fixture(scope="module")
def plates(robot, act, tmp_path_factory):
    """The plate clean, and with every face written again (corners rotated): painted at
    film spacing σ."""
    tmp = tmp_path_factory.mktemp("plates")
    verts, faces = _plate_obj()
    twice = faces + [(b, c, a) for a, b, c in faces]
    opts = PaintOptions(resolution=0.01)
    clean = pp.paint(robot, _part_job(tmp, "clean.obj", _obj(verts, faces)), act, opts)
    with pytest.warns(UserWarning, match="dropped 32 repeated faces"):
        dup = pp.paint(robot, _part_job(tmp, "dup.obj", _obj(verts, twice)), act, opts)
    return clean, dup


def test_a_duplicated_mesh_paints_as_the_clean_one(plates):
    """Every face twice: the same film, area and efficiency (to 1e-12: achieved exactly),
    where painting each copy doubled the area and read 110 % efficiency."""
    clean, dup = plates
    assert abs(dup.plan.part.painted_area - clean.plan.part.painted_area) <= 1e-12
    assert abs(clean.plan.part.painted_area - 0.12 ** 2) < 1e-12  # the plate, by hand
    assert np.abs(dup.film.thickness - clean.film.thickness).max() <= 1e-12 * 25e-6
    assert abs(dup.film.efficiency - clean.film.efficiency) <= 1e-12


def test_reports_keep_their_invariants(plates):
    """Lower bound ≤ cycle and transfer efficiency ≤ 100 % (the clean plate reads 49 %, its
    lower bound 2.4 s = 0.0144 m² × 25 µm / 1.5e-7 m³/s by hand, cycle 5.7 s)."""
    for r in plates:
        rep = r.report.data
        assert abs(rep["lower_bound"] - 0.0144 * 25e-6 / 1.5e-7) < 1e-9
        assert rep["lower_bound"] <= rep["cycle_time"] and 0 < rep["transfer_efficiency"] <= 1


def test_a_plate_behind_another_is_not_painted(robot, act, tmp_path):
    """The plate 0.1 m behind a larger sheet that faces away from the robot: nothing the gun
    can see, one line (it painted 7e-11 m and exited 0)."""
    verts, faces = _plate_obj()
    sheet = "v 0.6 -0.2 0.0\nv 0.6 0.2 0.0\nv 0.6 0.2 0.4\nv 0.6 -0.2 0.4\n"
    k = len(verts.splitlines())
    text = _obj(verts, faces) + sheet + f"f {k + 1} {k + 2} {k + 3}\nf {k + 1} {k + 3} {k + 4}\n"
    with pytest.raises(PollardError, match="all 32 faces within 45° of facing are hidden"):
        pp.paint(robot, _part_job(tmp_path, "hidden.obj", text), act)


@pytest.mark.parametrize("z, normal", [(0.0, 1.0), (0.32, -1.0)])
def test_a_table_top_paints_or_is_one_line(robot, act, tmp_path, z, normal):
    """A horizontal plate (facing ±z: the gun frame's reference was world z, a division by
    zero): a film within the target, or one line naming the reach."""
    half, x = 0.06, 0.45
    v = "".join(f"v {x + a} {b} {z}\n" for a, b in
                [(-half, -half), (half, -half), (half, half), (-half, half)])
    f = "f 1 2 3\nf 1 3 4\n" if normal > 0 else "f 1 3 2\nf 1 4 3\n"
    job = _part_job(tmp_path, "table.obj", v + f, (0.0, 0.0, normal))
    try:
        r = pp.paint(robot, job, act, PaintOptions(resolution=0.01))
    except PollardError as exc:
        msg = str(exc)
        assert "outside its limits" in msg and "\n" not in msg and len(msg) <= 250, msg
        return
    assert r.report.thickness["within_10pct"] > 0.9, r.report.thickness


EXAMPLE_JOBS = ["paint.toml", "line.toml", "line_part.toml", "parts/bent_plate.toml",
                "parts/curved_panel.toml", "parts/ribbed_plate.toml"]


@pytest.mark.slow  # ~45 s for the six at film spacing σ
@pytest.mark.parametrize("name", EXAMPLE_JOBS)
def test_every_example_keeps_the_report_invariants(robot, name):
    """Lower bound ≤ cycle and transfer efficiency ≤ 100 % on every shipped job (measured:
    cycles 8.0–42 s over bounds 4.0–15 s, efficiencies 55–60 %)."""
    root = Path(__file__).resolve().parents[2] / "examples"
    job = pp.load_job(root / name)
    rep = pp.paint(robot, job, options=PaintOptions(resolution=job.sigma)).report.data
    assert 0 < rep["lower_bound"] <= rep["cycle_time"]
    eff = rep.get("transfer_efficiency")
    assert eff is None or 0 < eff <= 1
