"""Constrained kinematics along trajectories (kinematics/ik.py), checked against independent
numbers.

- Pinocchio IK (Newton on the closures + tool pose) against the thesis' closed form of
  docs/model.md §7 (``pollard_pin.analytic.closed_form``, numpy only, exact jet derivatives),
  on the default trajectory, smooth random trajectories and isolated random reachable poses;
- velocities and accelerations against central finite differences of the IK positions;
- every error path of the IK and of the CSV reader.

Forward kinematics and closures: tests/kinematics/test_closure.py; task-space conventions:
tests/analytic/test_taskspace.py; ``pollard-pin run``: tests/cli/test_run.py.
"""
import math
import re
import warnings

import numpy as np
import pytest
from ik_runs import RUN_NAMES, solve, wrap
from poses import path_to_wrist_singularity, wrist_singular_pose  # tests/poses.py
from rotations import Rx, Ry, Rz

import pollard_pin as pp
from pollard_pin.analytic import closed_form as T
from pollard_pin.errors import InputError
from pollard_pin.io.trajectory import from_csv, to_csv
from pollard_pin.kinematics.errors import (
    KinematicsError,
    KinematicsInputError,
    SingularityError,
    UnreachablePoseError,
)
from pollard_pin.kinematics.singularity import WRIST_MARGIN
from pollard_pin.model import constraint_jacobian
from pollard_pin.names import SPHERICAL
from pollard_pin.paths.curves import smooth_random_trajectory, thesis_trajectory
from pollard_pin.paths.trajectory import TrajectoryError

TASK = ("x", "y", "z", "psi", "theta", "phi")
HEADER = "t,x,y,z,psi,theta,phi"

# Pinocchio IK against the closed form: it achieves 3.6e-15 rad, 2.1e-14 rad/s, 2.5e-13 rad/s²
# (thesis curve, random curves and poses); the tolerances are about 100× that.
POS_TOL, VEL_TOL, ACC_TOL = 5e-13, 5e-12, 5e-11  # rad, rad/s, rad/s²


def thesis_reference(robot, poses, d_poses, dd_poses):
    """Closed-form (q, qd, qdd) split into tree joints (robot.joint_names order) and the six
    spherical angles (SPHERICAL order)."""
    q, qd, qdd = T.inverse_kinematics(robot.params, poses, d_poses, dd_poses)
    tree = [T.JOINTS.index(n) for n in robot.joint_names]
    sph = [T.JOINTS.index(n) for n in SPHERICAL]
    return {"q": q[:, tree], "v": qd[:, tree], "a": qdd[:, tree],
            "sph": q[:, sph], "dsph": qd[:, sph]}


def write_text(path, header, rows):
    path.write_text(header + "\n" + "\n".join(",".join(str(c) for c in r) for r in rows) + "\n")
    return path


def write_poses_csv(path, t, poses):
    np.savetxt(path, np.column_stack([t, poses]), delimiter=",", header=HEADER, comments="",
               fmt="%.17g")
    return path


# --- Pinocchio IK vs the thesis closed form -----------------------------------------------------
@pytest.mark.parametrize("name", RUN_NAMES)
def test_ik_matches_thesis_closed_form_along_trajectory(robot, runs, name):
    traj, ik = runs[name]
    ref = thesis_reference(robot, traj.poses, traj.d_poses, traj.dd_poses)
    assert ik.q.shape == ik.v.shape == ik.a.shape == (len(traj), 12)
    assert ik.spherical.shape == ik.d_spherical.shape == (len(traj), 6)
    assert tuple(ik.joint_names) == tuple(robot.joint_names)
    # The joints really move (the comparison is not between two constants).
    assert np.ptp(ref["q"], axis=0).max() > 0.1 and np.abs(ref["a"]).max() > 1.0
    assert np.abs(wrap(ik.q - ref["q"])).max() <= POS_TOL
    assert np.abs(ik.v - ref["v"]).max() <= VEL_TOL
    assert np.abs(ik.a - ref["a"]).max() <= ACC_TOL
    assert np.abs(wrap(ik.spherical - ref["sph"])).max() <= POS_TOL
    assert np.abs(ik.d_spherical - ref["dsph"]).max() <= VEL_TOL


def test_ik_matches_thesis_closed_form_at_random_reachable_poses(robot):
    """Isolated poses (each its own one-sample problem, Newton from the SRDF home posture) with
    arbitrary pose rates and accelerations: the solution must be the spec-§9 branch of the closed
    form, including the wrist branch θ1716 > 0."""
    rng = np.random.default_rng(0)
    home = np.asarray(robot.params.home_pose)
    amp = np.array([0.08, 0.10, 0.08, 0.4, 0.4, 0.6])
    checked, failures = 0, []
    for k in range(60):
        x = home + amp * rng.uniform(-1.0, 1.0, 6)
        xd, xdd = 0.3 * rng.normal(size=6), rng.normal(size=6)
        try:  # reachable and away from the wrist singularity, by the closed form
            T.position_ik(robot.params, x, wrist_margin=2 * WRIST_MARGIN)
        except T.UnreachableError:
            continue
        ik = pp.inverse_kinematics(robot, x[None], xd[None], xdd[None])
        ref = thesis_reference(robot, x[None], xd[None], xdd[None])
        errs = (np.abs(wrap(ik.q - ref["q"])).max(), np.abs(ik.v - ref["v"]).max(),
                np.abs(ik.a - ref["a"]).max(), np.abs(wrap(ik.spherical - ref["sph"])).max(),
                np.abs(ik.d_spherical - ref["dsph"]).max())
        checked += 1
        if not (errs[0] <= POS_TOL and errs[1] <= VEL_TOL and errs[2] <= ACC_TOL
                and errs[3] <= POS_TOL and errs[4] <= VEL_TOL):
            failures.append((k, np.round(x, 6).tolist(), errs))
    assert checked >= 40
    assert not failures, failures


def test_newton_from_home_posture_matches_closed_form_near_home(robot):
    """With ``q_start`` = the SRDF home posture the positions come from Pinocchio's Newton alone
    (no closed-form start); near home it must land on the same branches as the closed form."""
    rng = np.random.default_rng(7)
    home = np.asarray(robot.params.home_pose)
    amp = np.array([0.04, 0.06, 0.05, 0.2, 0.2, 0.3])
    for _ in range(30):
        x = home + amp * rng.uniform(-1.0, 1.0, 6)
        xd, xdd = 0.3 * rng.normal(size=6), rng.normal(size=6)
        ik = pp.inverse_kinematics(robot, x[None], xd[None], xdd[None],
                                   q_start=robot.q_reference)
        ref = thesis_reference(robot, x[None], xd[None], xdd[None])
        assert np.abs(wrap(ik.q - ref["q"])).max() <= POS_TOL, x
        assert np.abs(ik.v - ref["v"]).max() <= VEL_TOL, x
        assert np.abs(ik.a - ref["a"]).max() <= ACC_TOL, x
        assert np.abs(wrap(ik.spherical - ref["sph"])).max() <= POS_TOL, x
        assert np.abs(ik.d_spherical - ref["dsph"]).max() <= VEL_TOL, x


# --- finite differences along the trajectory ---------------------------------------------------
def _fd_errors(q, v, a, h, s):
    """Max |central difference − analytic| per column with step s·h (v from q, a from q)."""
    H = s * h
    ev = np.abs((q[2 * s:] - q[:-2 * s]) / (2 * H) - v[s:-s]).max(axis=0)
    ea = None if a is None else \
        np.abs((q[2 * s:] - 2 * q[s:-s] + q[:-2 * s]) / H**2 - a[s:-s]).max(axis=0)
    return ev, ea


@pytest.mark.parametrize("name", RUN_NAMES)
def test_rates_match_central_differences_of_positions(runs, name):
    """Central differences of the IK positions have error h²/6·q''' (velocity) and h²/12·q''''
    (acceleration); the derivative bounds come from 5-point differences of the positions alone.
    Doubling h must multiply the error by 4 (the IK rates carry no O(1) bias)."""
    traj, ik = runs[name]
    h = traj.t[1] - traj.t[0]
    assert np.allclose(np.diff(traj.t), h, rtol=1e-12, atol=0)  # uniform (achieves 2e-13)

    for q, v, a in ((np.unwrap(ik.q, axis=0), ik.v, ik.a),
                    (np.unwrap(ik.spherical, axis=0), ik.d_spherical, None)):
        d3 = (q[4:] - 2 * q[3:-1] + 2 * q[1:-3] - q[:-4]) / (2 * h**3)
        d4 = (q[4:] - 4 * q[3:-1] + 6 * q[2:-2] - 4 * q[1:-3] + q[:-4]) / h**4
        ev1, ea1 = _fd_errors(q, v, a, h, 1)
        ev2, ea2 = _fd_errors(q, v, a, h, 2)
        tol_v = 2.0 * h**2 / 6 * np.abs(d3).max(axis=0) + 1e-8
        assert np.all(ev1 <= tol_v), (ev1, tol_v)
        big = ev1 > 1e-6  # well above rounding noise
        assert big.sum() >= 3
        # Doubling h multiplies the error by 4 up to O(h²): achieves 3.92–4.00.
        assert np.all(np.abs(ev2[big] / ev1[big] - 4.0) < 0.2), ev2 / ev1
        if a is not None:
            tol_a = 2.0 * h**2 / 12 * np.abs(d4).max(axis=0) + 1e-5
            assert np.all(ea1 <= tol_a), (ea1, tol_a)
            big = ea1 > 1e-5
            assert big.sum() >= 3
            assert np.all(np.abs(ea2[big] / ea1[big] - 4.0) < 0.2), ea2 / ea1  # 3.89–4.00

            # Accelerations also against central differences of the velocities.
            eav = np.abs((v[2:] - v[:-2]) / (2 * h) - a[1:-1]).max(axis=0)
            assert np.all(eav <= 4.0 * tol_a + 1e-5)


def test_ik_diagnostics_are_reported_per_sample(runs):
    traj, ik = runs["thesis"]
    q1716 = ik.q[:, list(ik.joint_names).index("theta1716")]
    assert np.allclose(ik.wrist_margin, np.abs(np.sin(q1716)), rtol=0, atol=1e-15)
    # docs/model.md §9: θ1716 stays between about 15° and 47° along the default trajectory
    # (14.5725° and 46.9934° at its 2001 samples).
    deg = np.degrees(np.arcsin(ik.wrist_margin))
    assert deg.min() == pytest.approx(14.5725, abs=1e-4) and \
        deg.max() == pytest.approx(46.9934, abs=1e-4)
    # Smallest singular values along it: 0.084757 and 0.073214.
    assert ik.sigma_parallel.min() == pytest.approx(0.084757, abs=1e-6)
    assert ik.sigma_serial.min() == pytest.approx(0.073214, abs=1e-6)


# --- error paths ----------------------------------------------------------------------------------
def _chain0_shortfall(params, pose):
    """Distance [m] by which the wrist centre lies beyond the reach of chain 0: the nearest
    point of the elbow circle (radius x32 in the xz plane at height z10) is further than L."""
    R = Rx(pose[4]) @ Ry(pose[3]) @ Rz(pose[5])
    P15 = pose[:3] - params.x1918 * R[:, 0]
    d = P15 - np.array([0.0, 0.0, params.z10])
    rho = math.hypot(d[0], d[2])
    return math.hypot(rho - params.x32, d[1]) - (params.x65 + params.x1514)


def test_unreachable_single_pose(robot):
    pose = np.asarray(robot.params.home_pose, dtype=float).copy()
    pose[0] = 2.0  # tool 1.45 m further than home: far out of reach
    with pytest.raises(UnreachablePoseError) as ei:
        pp.inverse_kinematics(robot, pose[None])
    e = ei.value
    assert isinstance(e, KinematicsError)
    assert e.chain == "chain 0" and e.sample == 0 and e.time == 0.0
    msg = str(e)
    assert "chain 0" in msg and "sample 0" in msg and "t = 0" in msg
    want = _chain0_shortfall(robot.params, pose)
    assert want > 1.0
    assert e.amount > 0 and abs(e.amount - want) <= 1e-14  # achieves 0


@pytest.mark.parametrize("shift, too_close", [(1.0, False), (-0.5, True)])
def test_unreachable_part_of_trajectory(robot, shift, too_close):
    traj = thesis_trajectory(samples=201)
    poses = traj.poses.copy()
    poses[150:, 0] += shift
    with pytest.raises(UnreachablePoseError) as ei:
        pp.inverse_kinematics(robot, poses, traj.d_poses, traj.dd_poses, traj.t)
    e = ei.value
    assert (e.sample, e.time, e.chain) == (150, 15.0, "chain 0")
    msg = str(e)
    assert "sample 150" in msg and "t = 15" in msg and "chain 0" in msg
    assert e.amount > 0
    if not too_close:
        assert abs(e.amount - _chain0_shortfall(robot.params, poses[150])) <= 1e-14  # 1.1e-16
    else:
        assert "too close" in msg


def test_unreachable_leg(robot):
    pose = np.asarray(robot.params.home_pose, dtype=float).copy()
    pose[0] = 0.75  # chain 0 still reaches the wrist centre; leg 1 falls short by ~6 mm
    with pytest.raises(T.UnreachableError) as ref:
        T.position_ik(robot.params, pose)
    with pytest.raises(UnreachablePoseError) as ei:
        pp.inverse_kinematics(robot, pose[None])
    e = ei.value
    assert e.chain == ref.value.chain and e.chain.startswith("leg")
    assert e.chain in str(e) and "sample 0" in str(e)
    assert e.amount == pytest.approx(ref.value.shortfall, abs=1e-14)  # 5.75 mm, to round-off



def test_wrist_singular_pose_raises_singularity_error(robot):
    pose = wrist_singular_pose(robot.params)
    with pytest.raises(T.WristSingularError):  # the closed form agrees it is singular
        T.position_ik(robot.params, pose)
    with pytest.raises(SingularityError) as ei:
        pp.inverse_kinematics(robot, pose[None])
    e = ei.value
    assert e.chain == "wrist" and "wrist" in str(e) and e.sample == 0
    assert abs(e.amount - WRIST_MARGIN) <= 1e-14  # (achieves 0) margin − |sin θ1716|, θ1716 = 0


def test_trajectory_approaching_wrist_singularity(robot):
    n = 201
    t, poses, d = path_to_wrist_singularity(robot.params, 0.99, n, 2.0)
    sin1716 = np.abs(np.sin(T.position_ik(robot.params, poses)[:, T.JOINTS.index("theta1716")]))
    first = int(np.argmax(sin1716 < WRIST_MARGIN))
    assert 0 < first < n - 1
    with pytest.raises(SingularityError) as ei:
        pp.inverse_kinematics(robot, poses, d, np.zeros_like(poses), t)
    e = ei.value
    assert (e.sample, e.chain) == (first, "wrist")
    assert e.time == pytest.approx(t[first], abs=1e-12)
    assert "wrist" in str(e) and f"sample {first}" in str(e)
    assert abs(e.amount - (WRIST_MARGIN - sin1716[first])) <= 1e-14  # achieves 3.3e-16


def test_wrist_margin_above_trajectory_minimum(robot, runs):
    traj, ik = runs["thesis"]
    sin1716 = np.abs(np.sin(T.position_ik(robot.params, traj.poses)[:, T.JOINTS.index(
        "theta1716")]))
    margin = 0.5 * (sin1716.min() + sin1716.max())
    first = int(np.argmax(sin1716 < margin))
    with pytest.raises(SingularityError) as ei:
        solve(robot, traj, margins=pp.Margins(wrist=margin))
    e = ei.value
    assert (e.sample, e.chain) == (first, "wrist") and e.time == traj.t[first]
    assert f"sample {first}" in str(e) and "wrist" in str(e)
    assert abs(e.amount - (margin - sin1716[first])) <= 1e-14  # achieves 0


def _first_violation(ik, margin):
    """(sample, chain) of the first parallel/serial margin violation, parallel checked first."""
    for k in range(len(ik)):
        if ik.sigma_parallel[k] < margin:
            return k, "parallel"
        if ik.sigma_serial[k] < margin:
            return k, "serial"
    return None


@pytest.mark.parametrize("which", ["parallel", "serial"])
def test_parallel_and_serial_singularity_margins(robot, which):
    traj = thesis_trajectory(samples=201)
    base = solve(robot, traj)
    # Independent σ_parallel at sample 0: smallest singular value of ∂(closure)/∂passive.
    Jc = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                                robot.constraint_datas, base.q[0])
    s0 = np.linalg.svd(Jc[:, robot.passive_v], compute_uv=False)[-1]
    assert abs(s0 - base.sigma_parallel[0]) <= 1e-14  # achieves 5.6e-17
    # A margin whose first violation is of the requested kind.
    grid = np.linspace(min(base.sigma_parallel.min(), base.sigma_serial.min()),
                       max(base.sigma_parallel.max(), base.sigma_serial.max()), 400)[1:]
    margin = next(m for m in grid if (_first_violation(base, m) or (0, ""))[1] == which)
    k, chain = _first_violation(base, margin)
    with pytest.raises(SingularityError) as ei:
        solve(robot, traj, margins=pp.Margins(singularity=margin))
    e = ei.value
    assert (e.sample, e.chain, e.time) == (k, chain, traj.t[k])
    assert which in str(e) and f"sample {k}" in str(e)
    sigma = base.sigma_parallel[k] if which == "parallel" else base.sigma_serial[k]
    assert abs(e.amount - (margin - sigma)) <= 1e-14  # achieves 0


@pytest.mark.parametrize("method", ["batch", "newton"])
def test_sparse_sampling_keeps_the_branch(robot, method):
    # 1 s between samples. The old check compared each step with a trapezoid prediction from
    # the rates (BRANCH_TOL = 0.05 rad) and called this a branch flip; the assembly mode is a
    # choice of branch signs, so the sparse solution must be the dense one at shared times.
    sparse, dense = thesis_trajectory(samples=21), thesis_trajectory(samples=201)
    q_start = None if method == "batch" else solve(robot, dense).q[0]
    ik = pp.inverse_kinematics(robot, sparse.poses, sparse.d_poses, sparse.dd_poses, sparse.t,
                               q_start=q_start, options=pp.IkOptions(method=method))
    ref = solve(robot, dense)
    for name in ("q", "v", "a"):
        assert np.abs(getattr(ik, name) - getattr(ref, name)[::10]).max() <= 1e-12, name


@pytest.mark.parametrize("method", ["batch", "newton"])
def test_jump_in_poses_is_not_a_branch_flip(robot, method):
    # A 5 cm step the pose rates know nothing about used to raise BranchFlipError (trapezoid
    # check). It does not change any branch sign: each sample is solved on the same branches,
    # and equals the closed form of docs/model.md §7 at its own pose.
    traj = thesis_trajectory(samples=201)
    poses = traj.poses.copy()
    poses[100:, 1] += 0.05
    ik = pp.inverse_kinematics(robot, poses, traj.d_poses, traj.dd_poses, traj.t,
                               options=pp.IkOptions(method=method))
    ref = thesis_reference(robot, poses, traj.d_poses, traj.dd_poses)
    assert np.abs(wrap(ik.q - ref["q"])).max() <= POS_TOL
    assert np.abs(ik.v - ref["v"]).max() <= VEL_TOL
    assert np.abs(ik.a - ref["a"]).max() <= ACC_TOL


@pytest.mark.parametrize("which, k, c, bad", [("poses", 77, 4, np.nan), ("d_poses", 12, 1, np.inf),
                                              ("dd_poses", 150, 0, -np.inf)])
def test_non_finite_input_names_the_sample(robot, which, k, c, bad):
    traj = thesis_trajectory(samples=201)
    arrays = {n: getattr(traj, n).copy() for n in ("poses", "d_poses", "dd_poses")}
    arrays[which][k, c] = bad
    with pytest.raises(KinematicsInputError) as ei:  # bad input, said where (errors.py's rule)
        pp.inverse_kinematics(robot, arrays["poses"], arrays["d_poses"], arrays["dd_poses"],
                              traj.t)
    e = ei.value
    assert isinstance(e, InputError) and not isinstance(e, KinematicsError)
    assert e.sample == k and e.time == traj.t[k]
    assert f"sample {k}" in str(e) and str(bad) in str(e)


# --- CSV input ------------------------------------------------------------------------------------
def _good_rows(n=8):
    traj = thesis_trajectory(samples=n)
    return [[f"{v:.12g}" for v in row] for row in np.column_stack([traj.t, traj.poses])]


def _edit(rows, r, c, value):
    rows = [list(x) for x in rows]
    rows[r][c] = value
    return rows


@pytest.mark.parametrize("header, rows, pattern", [
    # Row numbers are file lines (header = line 1), so data row index i is line i + 2.
    (HEADER, _edit(_good_rows(), 2, 2, "0.1x"), r"row 4, column 'y'.*'0\.1x' is not a number"),
    (HEADER, _edit(_good_rows(), 5, 3, "nan"), r"row 7, column 'z'.*not finite"),
    (HEADER, _edit(_good_rows(), 1, 6, "inf"), r"row 3, column 'phi'.*not finite"),
    (HEADER, _edit(_good_rows(), 3, 0, "-1"), r"row 5, column 't'.*decreasing"),
    (HEADER, _edit(_good_rows(), 4, 0, _good_rows()[3][0]), r"row 6, column 't'.*duplicate"),
    (HEADER, _edit(_good_rows(), 0, 4, "30"), r"row 2, column 'psi'.*degrees"),
    (HEADER, _edit(_good_rows(), 6, 5, "-45.0"), r"row 8, column 'theta'.*degrees"),
    (HEADER, _edit(_good_rows(), 3, 1, "550"), r"row 5, column 'x'.*millimetres"),
    ("t,x,y,z,psi,theta", [r[:6] for r in _good_rows()], r"missing column.*phi"),
    ("t,x,y,z,psi,thetta,phi", _good_rows(), r"unknown column 'thetta'.*did you mean 'theta'"),
    ("time,x,y,z,psi,theta,phi", _good_rows(), r"unknown column 'time'"),
    (HEADER, _edit(_good_rows(), 2, 6, "0.0,1.0"), r"row 4 has 8 fields"),
])
def test_malformed_csv_names_row_and_column(tmp_path, header, rows, pattern):
    path = write_text(tmp_path / "bad.csv", header, rows)
    with pytest.raises(TrajectoryError, match=pattern):
        from_csv(path)


def test_csv_file_with_all_units_scaled_looks_like_mm_and_degrees(tmp_path):
    traj = thesis_trajectory(samples=50)
    mm = traj.poses.copy()
    mm[:, :3] *= 1e3
    with pytest.raises(TrajectoryError, match=r"row 2, column 'x'.*millimetres"):
        from_csv(write_poses_csv(tmp_path / "mm.csv", traj.t, mm))
    deg = smooth_random_trajectory(4, samples=50).poses.copy()
    deg[:, 3:] = np.degrees(deg[:, 3:]) + 20.0
    with pytest.raises(TrajectoryError, match=r"column 'psi'.*degrees"):
        from_csv(write_poses_csv(tmp_path / "deg.csv", traj.t, deg))


@pytest.mark.parametrize("r, c, value", [(2, 2, "oops"), (4, 0, "0.0"), (5, 1, "550"),
                                         (3, 6, "1e400"), (6, 4, "0.1,0.2")])
def test_csv_row_numbers_are_file_lines_with_comments(tmp_path, r, c, value):
    """A user looking up "row N" in the file must find the offending value on line N, also
    when comment and blank lines precede it."""
    rows = [",".join(x) for x in _edit(_good_rows(), r, c, value)]
    text = "\n".join(["# exported by a test", "", HEADER, *rows[:2], "# a comment", *rows[2:]])
    path = tmp_path / "commented.csv"
    path.write_text(text + "\n")
    lines = text.splitlines()
    with pytest.raises(TrajectoryError) as ei:
        from_csv(path)
    n = int(re.search(r"row (\d+)", str(ei.value)).group(1))
    assert lines[n - 1] == rows[r], (str(ei.value), n)


def test_csv_without_derivatives_uses_spline_that_matches_analytic_derivatives(tmp_path):
    traj = smooth_random_trajectory(3, samples=201)
    path = write_poses_csv(tmp_path / "smooth.csv", traj.t, traj.poses)
    with pytest.warns(UserWarning, match="spline"):
        got = from_csv(path)
    assert got.derivatives != "file columns"
    assert np.array_equal(got.t, traj.t) and np.array_equal(got.poses, traj.poses)
    d_scale, dd_scale = np.abs(traj.d_poses).max(), np.abs(traj.dd_poses).max()
    assert np.abs(got.d_poses - traj.d_poses).max() <= 1e-6 * d_scale
    assert np.abs(got.dd_poses - traj.dd_poses).max() <= 1e-4 * dd_scale
    assert np.abs(got.d_poses - traj.d_poses)[10:-10].max() <= 1e-10 * d_scale  # interior


def test_csv_with_derivative_columns_is_exact(tmp_path):
    traj = smooth_random_trajectory(2, samples=101)
    path = tmp_path / "exact.csv"
    to_csv(traj, path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = from_csv(path)
    assert got.derivatives == "file columns"
    for name in ("t", "poses", "d_poses", "dd_poses"):
        assert np.array_equal(getattr(got, name), getattr(traj, name)), name
    # Columns may come in any order.
    cols = ["dd_phi", "t"] + list(TASK) + [f"d_{n}" for n in TASK] + \
        [f"dd_{n}" for n in TASK[:-1]]
    data = {"t": traj.t, **{n: traj.poses[:, i] for i, n in enumerate(TASK)},
            **{f"d_{n}": traj.d_poses[:, i] for i, n in enumerate(TASK)},
            **{f"dd_{n}": traj.dd_poses[:, i] for i, n in enumerate(TASK)}}
    shuffled = tmp_path / "shuffled.csv"
    np.savetxt(shuffled, np.column_stack([data[c] for c in cols]), delimiter=",",
               header=",".join(cols), comments="", fmt="%.17g")
    got = from_csv(shuffled)
    assert np.array_equal(got.dd_poses, traj.dd_poses) and np.array_equal(got.poses, traj.poses)


def test_csv_partial_derivative_columns_rejected(tmp_path):
    traj = smooth_random_trajectory(2, samples=20)
    cols = list(HEADER.split(",")) + ["d_x", "d_y"]
    arr = np.column_stack([traj.t, traj.poses, traj.d_poses[:, :2]])
    path = tmp_path / "partial.csv"
    np.savetxt(path, arr, delimiter=",", header=",".join(cols), comments="", fmt="%.17g")
    with pytest.raises(TrajectoryError, match="d_z"):
        from_csv(path)


def test_csv_spray_column_is_read_and_range_checked(tmp_path):
    """paint's trigger column: accepted in [0, 1] (the motion ignores it), refused outside."""
    rows = [r + ["1" if i % 2 else "0"] for i, r in enumerate(_good_rows())]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # no derivative columns: the spline
        traj = from_csv(write_text(tmp_path / "ok.csv", HEADER + ",spray", rows))
    assert len(traj) == len(rows)
    with pytest.raises(TrajectoryError, match=r"row 4, column 'spray'.*outside \[0, 1\]"):
        from_csv(write_text(tmp_path / "bad.csv", HEADER + ",spray",
                            _edit(rows, 2, 7, "1.5")))


@pytest.mark.parametrize("method", ["batch", "newton"])
def test_ik_refuses_what_is_not_a_robot_or_a_start(robot, method):
    """None for the robot, a string for q_start: one InputError line, not an AttributeError or
    numpy's ValueError from inside."""
    pose = [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]]
    with pytest.raises(InputError, match="robot = None: expected a Robot"):
        pp.inverse_kinematics(None, pose, options=pp.IkOptions(method=method))
    if method == "newton":
        with pytest.raises(KinematicsInputError, match="q_start = 'x': expected an array"):
            pp.inverse_kinematics(robot, pose, q_start="x")


def test_ik_refuses_a_progress_that_is_no_function(robot):
    with pytest.raises(KinematicsInputError, match="^progress = 'x': expected a function"):
        pp.inverse_kinematics(robot, [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]], progress="x")
