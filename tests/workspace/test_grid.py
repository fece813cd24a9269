"""Workspace maps (docs/model.md §22) against the per-sample solvers and direct computations.

Achieved errors (this machine): map margins vs the IK's columns ≤ 4e-14 (tolerance 4e-12);
conditioning index vs a per-point SVD of J_tool·N ≤ 1e-14 relative (1e-12); payload capacity:
the per-point motor utilisation (Pinocchio RNEA with the mass added to the gun, through
the motor model of dynamics/motors.py at rest) at the
capacity is 1 within 1.3e-15 (1e-13).
"""
import math

import numpy as np
import pytest
from poses import wrist_singular_pose  # tests/poses.py

import pollard_pin as pp
from pollard_pin.analytic import closed_form
from pollard_pin.dynamics.inverse import inverse_dynamics_sample
from pollard_pin.dynamics.motors import load_actuators, motor_torque
from pollard_pin.dynamics.plant import ModelMismatch, perturbed_robot
from pollard_pin.kinematics.errors import KinematicsError
from pollard_pin.kinematics.limits import limit_violations
from pollard_pin.kinematics.margins import Margins
from pollard_pin.kinematics.singularity import actuator_velocity_map
from pollard_pin.model.build import constraint_jacobian
from pollard_pin.model.names import TREE_JOINTS
from pollard_pin.model.params import load_params
from pollard_pin.workspace.grid import WorkspaceError, largest_panel, map_workspace
from pollard_pin.workspace.reach import REASONS, ReachOptions, evaluate
from pollard_pin.workspace.rectangle import boundary_points, largest_rectangle

ACTUATORS = __file__.rsplit("/tests/", 1)[0] + "/examples/actuators.toml"


@pytest.fixture(scope="module")
def wide():
    """The shipped model with every joint limit one full turn: only reach and the margins
    bound the workspace (``run`` does not check joint limits)."""
    ov = {f"limits.{j}.{k}": v for j in TREE_JOINTS for k, v in (("lower", -180.0),
                                                                 ("upper", 180.0))}
    return pp.load(load_params(overrides=ov))


def line(a, b, n=801):
    """Poses along the straight segment a → b (positions), default orientation."""
    s = np.linspace(0.0, 1.0, n)[:, None]
    pts = np.asarray(a) + s * (np.asarray(b) - np.asarray(a))
    return np.concatenate([pts, np.zeros((n, 3))], axis=1)


def first_unreachable(robot, poses):
    cols = evaluate(robot, poses)
    bad = np.flatnonzero(cols["reachable"] == 0)
    return (int(bad[0]) if len(bad) else None), cols


# --- against run's per-sample solver ----------------------------------------------------------
INSIDE = (0.55, 0.0, 0.1)


@pytest.mark.parametrize("end, reason", [
    ((0.55, -0.5, 0.05), "chain 0 out of reach"),
    ((0.55, -0.3, 0.4), "leg 2 out of reach"),
    ((0.55, 0.3, 0.4), "leg 1 out of reach"),
    ((0.55, 0.45, -0.3), "parallel margin"),  # crosses a parallel singularity curve
    ((0.90, 0.0, 0.1), "leg 1 out of reach"),
    ("wrist", "wrist margin"),  # towards θ1716 = 0 (tests/poses.py)
    ((0.30, 0.0, 0.1), None)])  # stays inside
def test_run_fails_exactly_where_the_map_says(wide, end, reason):
    """From a reachable point outwards: ``run``'s IK solves every sample before the first
    the map marks unreachable (same margins), and fails at that sample, naming its chain."""
    if end == "wrist":
        s = np.linspace(0.0, 1.0, 1001)[:, None]
        home = np.asarray(wide.params.home_pose)
        poses = home + s * (wrist_singular_pose(wide.params) - home)
    else:
        poses = line(INSIDE, end, 1001)
    t = np.arange(len(poses)) * 0.01
    k, cols = first_unreachable(wide, poses)
    n = len(poses) if k is None else k
    ik = pp.inverse_kinematics(wide, poses[:n], t=t[:n])
    for name in ("wrist_margin", "sigma_parallel", "sigma_serial"):
        np.testing.assert_allclose(cols[name][:n], getattr(ik, name), rtol=0, atol=4e-12)
    if reason is None:
        assert k is None
        return
    assert REASONS[cols["reason"][k]] == reason
    with pytest.raises(KinematicsError) as err:
        pp.inverse_kinematics(wide, poses[:k + 1], t=t[:k + 1])
    assert err.value.sample == k, str(err.value)
    assert err.value.chain == reason.replace(" out of reach", "").replace(" margin", "")


def test_a_path_through_the_map_solves_and_leaves_at_a_joint_limit(robot):
    """The shipped limits: a path inside the map solves; where it leaves at a joint limit
    (not an error in run), the IK's own angles, taken modulo 2π, cross that limit there."""
    poses = line((0.55, 0.0, 0.1), (0.55, 0.45, 0.1), 901)
    k, cols = first_unreachable(robot, poses)
    reason = REASONS[cols["reason"][k]]
    joint, side = reason.split()[0], reason.split()[3]
    ik = pp.inverse_kinematics(robot, poses[:k + 1], t=np.arange(k + 1) * 0.01)
    j = robot.joint_names.index(joint)
    lim = robot.params.joint_limits(joint)
    turns = np.arange(-3, 4) * 2 * np.pi
    inside = [bool(np.any((lim.lower <= q + turns) & (q + turns <= lim.upper)))
              for q in ik.q[:, j]]
    assert all(inside[:k]) and not inside[k]
    q_k = ik.q[k, j] + turns
    assert side == ("upper" if np.min(np.abs(q_k - lim.upper)) < np.min(np.abs(q_k - lim.lower))
                    else "lower")


# --- each reason on a constructed point -------------------------------------------------------
def reason_at(robot, pose, **margins):
    opts = ReachOptions(Margins(**margins))
    return REASONS[int(evaluate(robot, np.atleast_2d(pose), opts)["reason"][0])]


def test_reasons_on_constructed_points(robot):
    home = np.asarray(robot.params.home_pose)
    assert reason_at(robot, home) == "reachable"
    assert reason_at(robot, home + [2.0, 0, 0, 0, 0, 0]) == "chain 0 out of reach"
    # σ at home: parallel 0.165, serial 0.130 (docs/model.md §12)
    assert reason_at(robot, home, singularity=0.15) == "serial margin"
    assert reason_at(robot, home, singularity=0.2) == "parallel margin"
    assert reason_at(robot, home, wrist=0.5) == "wrist margin"  # |sin θ1716| = 0.452
    assert reason_at(robot, wrist_singular_pose(robot.params)) == "wrist margin"


def test_leg_reasons_agree_with_the_closed_form(wide):
    """Points the map puts out of a leg's reach: the raising closed form names that leg."""
    ws = map_workspace(wide, "x=0.55", resolution=0.02)
    c = ws.columns
    for chain in ("leg 1", "leg 2"):
        idx = np.flatnonzero(c["reason"] == REASONS.index(f"{chain} out of reach"))
        assert len(idx)
        for k in idx[:: max(1, len(idx) // 5)]:
            pose = [c[n][k] for n in ("x", "y", "z", "psi", "theta", "phi")]
            with pytest.raises(closed_form.UnreachableError) as err:
                closed_form.position_ik(wide.params, pose)
            assert err.value.chain == chain


@pytest.mark.parametrize("joint, limits, expect", [
    ("theta21", (-105.0, -80.0), "theta21 above its upper limit"),  # home θ21 = −77.6°
    ("theta21", (-75.0, -35.0), "theta21 below its lower limit"),
    ("theta1615", (440.0, 460.0), "reachable"),  # home θ1615 = 90° = 450° − 360°
    ("theta1615", (100.0, 300.0), "theta1615 below its lower limit")])
def test_joint_limit_reasons(joint, limits, expect):
    params = load_params(overrides={f"limits.{joint}.lower": limits[0],
                                    f"limits.{joint}.upper": limits[1]})
    robot = pp.load(params)
    assert reason_at(robot, np.asarray(params.home_pose)) == expect


def test_limit_violations_modulo_two_pi():
    params = load_params()
    lim = params.joint_limits("theta21")  # [−105°, −35°]
    q = np.radians([[-70.0], [-70.0 + 360.0], [-30.0], [-110.0], [-70.0 - 720.0], [np.nan]])
    side, excess = limit_violations(params, q, ("theta21",))
    assert side[:, 0].tolist() == [0, 0, 1, -1, 0, 0]
    np.testing.assert_allclose(excess[:, 0], np.radians([0, 0, 5, 5, 0, 0]), atol=1e-12)
    assert lim.lower < lim.upper


# --- the grid and its figures -----------------------------------------------------------------
def test_area_converges_on_finer_grids(robot):
    """Refining the grid (the coarse points are a subset of the fine ones): the area's error
    against the finest grid shrinks with h, within half a perimeter's worth of boundary cells
    (seen: 0.0051, 0.0018, 0.0004, 0.0003 m² at h = 20, 10, 5, 2.5 mm)."""
    bounds = {"y": (-0.4, 0.4), "z": (-0.15, 0.35)}
    steps = (0.02, 0.01, 0.005, 0.0025)
    areas = {h: map_workspace(robot, "x=0.55", resolution=h, bounds=bounds).summary["area"]
             for h in steps + (0.00125,)}
    errs = [abs(areas[h] - areas[0.00125]) for h in steps]
    perimeter = 2 * (0.6 + 0.34)  # m, of the region (its bounding box)
    for h, e in zip(steps, errs):
        assert e <= 0.5 * perimeter * h, (h, e)
    assert errs == sorted(errs, reverse=True)


def test_volume_streams_and_equals_the_stacked_planes(robot):
    """A coarse volume, streamed chunk by chunk: its volume is the sum over its x-slices of
    the plane maps' areas times the step (the grids coincide point for point)."""
    h = 0.04
    chunks = []
    vol = map_workspace(robot, volume=True, resolution=h, sink=chunks.append, chunk=5000)
    assert vol.columns is None and len(chunks) > 1
    assert sum(len(c["x"]) for c in chunks) == vol.grid.size
    xs = vol.grid.coordinates(0)
    total = 0.0
    for x in xs:
        try:
            ws = map_workspace(robot, ("x", float(x)), resolution=h)
        except WorkspaceError:
            continue  # plane with no reachable point
        total += ws.summary["area"] * h
    assert math.isclose(total, vol.summary["volume"], rel_tol=1e-12)


@pytest.mark.parametrize("orientation", [(0.0, 0.0, 0.0), (0.35, -0.35, 0.5)])
def test_default_bounds_hold_the_whole_reach(wide, orientation):
    """With every joint limit a full turn (the largest reach), the reachable points of a
    default volume grid stay at least two cells inside its bounds: nothing is cut off."""
    h = 0.04
    vol = map_workspace(wide, volume=True, resolution=h, orientation=orientation)
    g = vol.grid.as_dict()
    lo, hi = (np.asarray(vol.summary["bounding_box"][k]) for k in ("low", "high"))
    assert (lo >= np.asarray(g["start"]) + 2 * h - 1e-9).all()
    assert (hi <= np.asarray(g["stop"]) - 2 * h + 1e-9).all()


def brute_rectangle(mask):
    best = 0
    rows, cols = mask.shape
    for r0 in range(rows):
        for r1 in range(r0 + 1, rows + 1):
            for c0 in range(cols):
                for c1 in range(c0 + 1, cols + 1):
                    if mask[r0:r1, c0:c1].all():
                        best = max(best, (r1 - r0) * (c1 - c0))
    return best


def test_largest_rectangle_against_brute_force():
    rng = np.random.default_rng(1)
    for _ in range(60):
        mask = rng.random((rng.integers(1, 9), rng.integers(1, 9))) < rng.uniform(0.3, 0.95)
        found = largest_rectangle(mask)
        best = brute_rectangle(mask)
        if best == 0:
            assert found is None
            continue
        r0, r1, c0, c1 = found
        assert mask[r0:r1, c0:c1].all() and (r1 - r0) * (c1 - c0) == best


def test_boundary_points_against_brute_force():
    rng = np.random.default_rng(2)
    for _ in range(30):
        mask = rng.random((rng.integers(1, 8), rng.integers(1, 8))) < 0.6
        rows, cols = mask.shape
        count = 0
        for r in range(rows):
            for c in range(cols):
                near = [mask[i, j] if 0 <= i < rows and 0 <= j < cols else False
                        for i in (r - 1, r, r + 1) for j in (c - 1, c, c + 1)]
                count += any(near) and not all(near)
        assert boundary_points(mask) == count


def test_largest_panel_is_reachable_and_maximal(robot):
    rect = largest_panel(robot, "x=0.55", resolution=0.01)
    ys = np.arange(rect.low[1], rect.high[1] + 1e-9, 0.01)
    zs = np.arange(rect.low[2], rect.high[2] + 1e-9, 0.01)
    Y, Z = np.meshgrid(ys, zs)
    poses = np.zeros((Y.size, 6))
    poses[:, 0], poses[:, 1], poses[:, 2] = 0.55, Y.ravel(), Z.ravel()
    assert (evaluate(robot, poses)["reachable"] == 1).all()
    assert rect.points == (len(ys), len(zs))


@pytest.mark.parametrize("h", [0.005, 0.01, 0.02])
def test_the_reported_rectangle_has_reachable_corners_and_edges(robot, h):
    """The panel the map reports, ``size`` about ``centre``, re-checked at 7 samples per grid
    step along its four edges (corners included): all reachable. Its size was points × h,
    half a cell past the corner points on each side (at 5 mm its top corners were out of a
    leg's reach); it is now (points − 1) × h, corner point to corner point."""
    rect = largest_panel(robot, "x=0.55", resolution=h)
    assert rect.axes == ("y", "z")
    assert rect.size == pytest.approx(tuple((n - 1) * h for n in rect.points), abs=1e-9)
    (y0, z0), (sy, sz) = rect.centre[1:], rect.size
    ys = y0 + sy * np.linspace(-0.5, 0.5, 7 * (rect.points[0] - 1) + 1)
    zs = z0 + sz * np.linspace(-0.5, 0.5, 7 * (rect.points[1] - 1) + 1)
    edge = np.concatenate([np.column_stack([ys, np.full_like(ys, z)]) for z in zs[[0, -1]]]
                          + [np.column_stack([np.full_like(zs, y), zs]) for y in ys[[0, -1]]])
    poses = np.zeros((len(edge), 6))
    poses[:, 0], poses[:, 1:3] = 0.55, edge
    cols = evaluate(robot, poses)
    bad = cols["reason"] != 0
    assert not bad.any(), (edge[bad][:3], [REASONS[r] for r in cols["reason"][bad][:3]])


def test_a_coarse_map_states_what_it_does_not_know(robot):
    """At a 10 m resolution one point is reachable: the rectangle is that point (0 × 0 m, it
    was 10 × 10 m) and the area, 100 m² as one cell, carries a bound larger than itself."""
    ws = map_workspace(robot, "x=0.55", resolution=10.0)
    assert ws.summary["reachable_points"] == 1
    assert ws.rectangle.size == (0.0, 0.0) and ws.rectangle.points == (1, 1)
    assert ws.summary["area"] == 100.0 and ws.summary["area_bound"] >= 100.0


def test_the_area_bound_holds_against_a_fine_grid(robot):
    """area ± area_bound (the cells of points with a mixed neighbourhood) holds the area of a
    grid 8-16× finer (seen: errors 6.5 % and 4.6 % of the bound at h = 20 and 10 mm)."""
    bounds = {"y": (-0.4, 0.4), "z": (-0.15, 0.35)}
    fine = map_workspace(robot, "x=0.55", resolution=0.00125, bounds=bounds).summary["area"]
    for h in (0.02, 0.01):
        s = map_workspace(robot, "x=0.55", resolution=h, bounds=bounds).summary
        assert abs(s["area"] - fine) <= s["area_bound"], (h, s["area"], fine, s["area_bound"])
        assert s["area_bound"] < 0.5 * s["area"]


# --- conditioning index and payload, point by point -------------------------------------------
def per_point_serial_map(robot, q):
    m, d = robot.model, robot.data
    import pinocchio as pin

    Jc = constraint_jacobian(m, d, robot.constraint_models, robot.constraint_datas, q)
    pin.computeJointJacobians(m, d, q)
    pin.updateFramePlacements(m, d)
    Jt = pin.getFrameJacobian(m, d, robot.tip_frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return Jt @ actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)


def test_conditioning_and_payload_per_point(robot):
    act = load_actuators(ACTUATORS)
    ws = map_workspace(robot, "x=0.55", resolution=0.03, actuators=act)
    c = ws.columns
    idx = np.flatnonzero(c["reachable"] == 1)
    assert len(idx) > 20
    L = robot.params.x65 + robot.params.x1514 + robot.params.x1918
    worst = worst_util = 0.0
    for k in idx[:: max(1, len(idx) // 12)]:
        pose = np.array([c[n][k] for n in ("x", "y", "z", "psi", "theta", "phi")])
        q = pp.inverse_kinematics(robot, pose[None]).q[0]
        A = per_point_serial_map(robot, q)
        s = np.linalg.svd(A * np.array([1 / L] * 3 + [1.0] * 3)[:, None], compute_uv=False)
        worst = max(worst, abs(s[-1] / s[0] - c["conditioning"][k]) / (s[-1] / s[0]))
        cap = c["payload_capacity"][k]
        assert 0 < cap < np.inf

        def utilisation(m, q=q):
            heavy = perturbed_robot(robot, ModelMismatch(payload=m))
            tau = inverse_dynamics_sample(heavy, q, np.zeros(12), np.zeros(12))[0]
            zero = np.zeros(6)  # at rest: the motor model counts Coulomb as breakaway ±c
            return np.max(np.abs(motor_torque(act, tau, zero, zero)) / act.column("peak_torque"))

        worst_util = max(worst_util, abs(utilisation(cap) - 1.0))
        assert utilisation(cap * (1 - 1e-6)) < 1.0
    assert worst <= 1e-12
    assert worst_util <= 1e-13


# --- bad input --------------------------------------------------------------------------------
@pytest.mark.parametrize("kw, words", [
    ({"plane": "x=2.5"}, ["misses the robot", "reachable region spans"]),
    ({"plane": "x=0.55", "resolution": 0.0}, ["resolution", "> 0"]),
    ({"plane": "x=0.55", "resolution": -1}, ["resolution", "> 0"]),
    ({"plane": "x=0.55", "resolution": 1e-5}, ["would need", "GiB", "at least"]),
    ({"volume": True, "resolution": 1e-3}, ["would need", "at least"]),
    ({"plane": "w=0.5"}, ["x, y or z"]),
    ({"plane": "x0.5"}, ["AXIS=VALUE"]),
    ({"plane": "x=abc"}, ["not a number"]),
    ({"plane": "x=0.55", "orientation": (0, 0)}, ["three"]),
    ({"plane": "x=0.55", "orientation": (0, math.nan, 0)}, ["finite"]),
    ({"plane": "x=0.55", "orientation": (0, 0, 1e7)}, ["phi = 1e+07 rad is absurd"]),
    ({"plane": "x=1e9"}, ["plane x = 1e+09 m misses the robot", "reachable region spans"]),
    ({"plane": "x=nan"}, ["finite"]),
    ({"plane": "x=0.55", "bounds": {"y": (0.3, -0.3)}}, ["below the upper bound"]),
    ({"plane": "x=0.55", "bounds": {"x": (0, 1)}}, ["other two axes"]),
    ({"plane": "x=0.55", "bounds": {"y": (1.0, 2.0)}}, ["no point", "reachable region"]),
    ({"plane": "x=0.55", "length_scale": -1}, ["length_scale = -1: must be > 0 [m]"]),
    ({}, ["either a plane"])])
def test_bad_input(robot, kw, words):
    with pytest.raises(WorkspaceError) as err:
        map_workspace(robot, **kw)
    msg = str(err.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg
