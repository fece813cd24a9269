"""pollard_pin.place: the placement with the most reach margin, checked against the reach
rule itself at every gun pose of the passes (not the sampled ones place checks), against
numpy's rotation of the mesh, and by painting the placed job."""
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from refusals import WRONG, refused

from pollard_pin.errors import PollardError
from pollard_pin.outputs import paint
from pollard_pin.painting.errors import PlaceError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.layout.place import PlaceOptions, place
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.passes.program import pass_poses
from pollard_pin.painting.passes.surface import surface_layout
from pollard_pin.painting.policy import DEFAULT_POLICY
from pollard_pin.painting.workpiece.mesh import load_job_part
from pollard_pin.workspace.reach import evaluate

ROOT = Path(__file__).resolve().parents[3]
CURVED = ROOT / "examples" / "parts" / "curved_panel.toml"


def _reach_share(robot, job, shift=(0.0, 0.0, 0.0)) -> float:
    """The share of every pass pose of the job's part (moved by ``shift``) the reach rule
    passes."""
    poses = np.concatenate(pass_poses(surface_layout(load_job_part(job), job)))
    poses[:, :3] += shift
    return float(evaluate(robot, poses)["reachable"].mean())


@pytest.fixture(scope="module")
def placed(robot):
    # the example part moved 0.25 m up and 0.3 m aside: out of reach as it stands
    job = replace(load_job(CURVED), position=(0.0, 0.3, 0.25))
    return job, place(robot, job, PlaceOptions(max_turn=0.0))


def test_moved_part_is_brought_back_with_its_margin(robot, placed):
    job, result = placed
    assert _reach_share(robot, job) < 0.5
    assert result.turn == 0.0 and result.job.rotation == (0.0, 0.0, 0.0)
    assert _reach_share(robot, result.job) == 1.0  # every pose, not only the sampled ones
    m = result.margin
    assert 0.03 < m < 0.2, m  # curved_panel: 75 mm (the example's own place is 0.06 off)
    for k in range(3):  # within the margin along every axis, every pose stays reachable
        for s in (-1, 1):
            assert _reach_share(robot, result.job, 0.95 * m * s * np.eye(3)[k]) == 1.0
    # along the binding axis, a little beyond the margin (the centring's tolerance 2.5 mm)
    # some pose fails, on one side or the other
    beyond = [_reach_share(robot, result.job, (m + 0.006) * s * np.eye(3)[k])
              for k in range(3) for s in (-1, 1)]
    assert min(beyond) < 1.0


def test_line_job_keeps_its_start_along_the_line(robot, placed):
    """On a line (along +y) the placement moves the part across the line only: x and z as
    the still placement's, y the job's own start."""
    from pollard_pin.painting.line.conveyor import Line

    job, still = placed
    on_line = replace(job, position=(0.0, -0.6, 0.25), line=Line(0.03, (0.0, 1.0, 0.0)))
    result = place(robot, on_line, PlaceOptions(max_turn=0.0))
    x, y, z = result.job.position
    assert y == -0.6 and result.job.line == on_line.line
    assert abs(x - still.job.position[0]) < 1e-6 and abs(z - still.job.position[2]) < 1e-6


def test_placed_job_paints(robot, placed, tmp_path):
    """The written job is read back as is and painted: the film within ±5 % of target."""
    _, result = placed
    (tmp_path / "sub").mkdir()
    path = result.write(tmp_path / "sub" / "placed.toml")
    job = load_job(path)
    assert job.position == result.job.position and Path(job.mesh).samefile(
        load_job(CURVED).mesh)
    res = paint(robot, job, options=PaintOptions(resolution=0.01, compliance=False))
    th = res.report.thickness
    assert abs(th["mean"] / job.thickness - 1) < 0.05, th


def test_turn_composes_with_the_job_rotation(robot, tmp_path):
    """A plate 0.45 m tall and 0.2 m wide is taller than the reach (some 0.32 m at the
    passes' 0.26 m width): refused with how much it misses; allowed to turn, it lies on its
    side. The placed rotation moves the file's vertices as numpy's rotation about the
    facing axis does after the job's own."""
    h, w = 0.45, 0.2
    (tmp_path / "tall.obj").write_text(
        f"v 0 {-w / 2} {-h / 2}\nv 0 {w / 2} {-h / 2}\nv 0 {w / 2} {h / 2}\nv 0 {-w / 2} {h / 2}\n"
        "f 1 3 2\nf 1 4 3\n")
    (tmp_path / "tall.toml").write_text(
        '[part]\nmesh = "tall.obj"\nposition = [0.6, 0.0, 0.1]\nrotation = [10.0, 0.0, 0.0]\n'
        "[gun]\nstandoff = 0.15\nsigma = 0.01\nflow = 1.5e-7\n[job]\nthickness = 25e-6\n")
    job = load_job(tmp_path / "tall.toml")
    with pytest.raises(PlaceError) as exc:
        place(robot, job, PlaceOptions(max_turn=0.0))
    msg = str(exc.value)
    assert "taller than the reach by" in msg and "a line or a cell" in msg, msg
    assert len(msg) <= 250 and "\n" not in msg and isinstance(exc.value, PollardError)
    by = float(msg.split("reach by ")[1].split(" mm")[0])
    # 0.49 m of passes against the 0.32 m tallest reachable rectangle 0.26 m wide: 170 mm
    assert 100 < by < 250, msg
    result = place(robot, job, PlaceOptions(max_turn=90.0, turn_step=90.0))
    assert abs(result.turn) == 90.0 and result.margin > 0.01, result.turns
    assert _reach_share(robot, result.job) == 1.0
    # the placed vertices: Rx(10°) then the turn about facing (−x), then the position
    a, t = math.radians(10.0), math.radians(result.turn)
    rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    # a turn by t about −x is a turn by −t about x
    rt = np.array([[1, 0, 0], [0, math.cos(t), math.sin(t)], [0, -math.sin(t), math.cos(t)]])
    v = np.array([[0, -w / 2, -h / 2], [0, w / 2, -h / 2], [0, w / 2, h / 2], [0, -w / 2, h / 2]])
    want = v @ (rt @ rx).T + result.job.position
    got = load_job_part(result.job).vertices
    assert np.abs(got - want).max() < 1e-9  # achieved ~1e-16 (angles written to 1e-9°)


def test_vertical_passes_suggested_where_they_paint(robot):
    """The example part 5 cm back, 10 cm right and 5 cm down: its horizontal passes' run-on
    takes theta54 past its limit, and the refusal says vertical passes paint it, as they
    do."""
    from pollard_pin.painting.api import default_actuators
    from pollard_pin.painting.errors import ReachError
    from pollard_pin.painting.plan.part import plan_surface

    job = replace(load_job(CURVED), position=(-0.05, -0.1, -0.05))
    act = default_actuators(job)
    with pytest.raises(ReachError) as exc:
        plan_surface(robot, job, act)
    msg = str(exc.value)
    assert 'direction = "vertical" paints it as placed' in msg and len(msg) <= 250, msg
    plan = plan_surface(robot, replace(job, direction="vertical"), act)
    assert plan.ratios["peak_torque"].max() <= 1.0


@pytest.mark.parametrize("options, fragment", [
    (dict(step=0.0), "PlaceOptions.step = 0.0"),
    (dict(max_turn=-1.0), "PlaceOptions.max_turn = -1.0"),
    (dict(samples=3), "PlaceOptions.samples = 3"),
    (dict(step=10**400), "PlaceOptions.step = 1e"),  # shown short, not OverflowError
    (dict(samples=10**400), "PlaceOptions.samples = 1e"),  # not 401 digits echoed
], ids=["step 0", "max_turn -1", "samples 3", "step 1e400", "samples 1e400"])
def test_bad_options(options, fragment):
    with pytest.raises(PollardError, match=fragment.replace(".", r"\.")):
        PlaceOptions(**options)


def test_panel_job_refused(robot):
    with pytest.raises(PollardError, match="expected a part's job"):
        place(robot, load_job(ROOT / "examples" / "paint.toml"))


def test_a_side_longer_than_the_reach_is_said_alone(robot):
    """The long strip (1.0 m of passes along y, 0.13 m across): wider than the reach's widest
    extent, so no height would make it fit. The refusal says by how much the width exceeds
    the reach, never the whole height as if the reach were nothing (it said "taller by 127 mm
    (or wider by 390 mm)", the strip's full height)."""
    job = replace(load_job(ROOT / "examples" / "line_part.toml"), line=None)
    with pytest.raises(PlaceError) as exc:
        place(robot, job, PlaceOptions(max_turn=0.0))
    msg = str(exc.value)
    assert "wider than the reach by" in msg and "taller" not in msg, msg
    assert len(msg) <= 250 and "\n" not in msg
    by = float(msg.split("reach by ")[1].split(" mm")[0])
    width = float(msg.split("passes ")[1].split(" ×")[0])
    reach = float(msg.split("reach at most ")[1].split(" ×")[0])
    assert abs(by / 1e3 - (width - reach)) <= 0.01, msg  # said as the difference, ±1 cell
    assert 0.1 < reach < width - 0.1, msg  # a reach, neither nothing nor the strip


@pytest.mark.parametrize("arg", ["robot", "job", "options", "policy"])
@pytest.mark.parametrize("wrong", WRONG, ids=repr)
def test_place_refuses_a_wrong_argument(robot, arg, wrong):
    """place's robot, job, options and policy: None (where it is not the default), the wrong
    types and NaN are one line naming the argument, before anything is solved."""
    if wrong is None and arg in ("options", "policy"):
        return
    args = {"robot": robot, "job": load_job(CURVED), "options": None,
            "policy": DEFAULT_POLICY, arg: wrong}
    refused(lambda: place(args["robot"], args["job"], args["options"], args["policy"]), arg)


@pytest.mark.parametrize("path", [v for v in WRONG if not isinstance(v, str)], ids=repr)
def test_write_refuses_what_is_not_a_path(placed, path):
    refused(lambda: placed[1].write(path), "path")
