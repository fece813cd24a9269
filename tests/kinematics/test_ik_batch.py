"""The batched pipeline equals the sample-by-sample one to 1e-12."""
import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.dynamics.inverse import inverse_dynamics
from pollard_pin.kinematics import UnreachablePoseError
from pollard_pin.kinematics.ik import inverse_kinematics_batch, inverse_kinematics_newton
from pollard_pin.paths import smooth_random_trajectory

FIELDS = ("q", "v", "a", "spherical", "d_spherical", "wrist_margin", "sigma_parallel",
          "sigma_serial")


@pytest.fixture(scope="module")
def robot():
    return pp.load()


@pytest.mark.parametrize("traj", [pp.thesis_trajectory(samples=801),
                                  smooth_random_trajectory(5, samples=301)],
                         ids=["thesis", "random"])
def test_batch_equals_newton(robot, traj):
    args = (traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    ref = inverse_kinematics_newton(robot, *args)
    fast = inverse_kinematics_batch(robot, *args)
    # odd block boundaries
    chunked = inverse_kinematics_batch(robot, *args, options=pp.IkOptions(chunk=97))
    for f in FIELDS:
        scale = max(1.0, np.abs(getattr(ref, f)).max())
        assert np.abs(getattr(fast, f) - getattr(ref, f)).max() <= 1e-12 * scale, f
        assert np.array_equal(getattr(chunked, f), getattr(fast, f)), f
    # Achieved: closure 5.8e-16 m, tool 1.6e-15 m.
    assert fast.closure_residual.max() <= 1e-13 and fast.tool_error.max() <= 2e-13
    # Dynamics: reusing the IK's constraint Jacobians vs recomputing them per sample.
    d_fast = inverse_dynamics(robot, fast)
    ref.constraint_jacobian = None
    d_ref = inverse_dynamics(robot, ref)
    peak = np.abs(d_ref.tau).max()
    assert np.abs(d_fast.tau - d_ref.tau).max() <= 1e-12 * peak
    # Achieved 1.5e-14 × the peak torque.
    assert np.abs(d_fast.closure_forces - d_ref.closure_forces).max() <= 2e-12 * peak



def test_batch_reports_first_bad_sample_across_chunks(robot):
    traj = pp.thesis_trajectory(samples=401)
    poses = traj.poses.copy()
    poses[250:, 0] += 0.5  # out of reach from sample 250 on
    with pytest.raises(UnreachablePoseError) as ei:
        inverse_kinematics_batch(robot, poses, traj.d_poses, traj.dd_poses, traj.t,
                                 options=pp.IkOptions(chunk=100))
    assert ei.value.sample == 250 and ei.value.time == pytest.approx(traj.t[250])



def test_compiled_K_and_drifts_equal_pinocchios(robot):
    # The batched path's K = [Jc; J_tool], its drifts K̇v and the bodies' angular velocities
    # (compiled kernels over the placements) against Pinocchio's constraint and frame
    # Jacobians, classical accelerations and data.v, sample by sample at random states.
    from pollard_pin.kinematics.ik_batch import layout, point_drifts, point_rows
    from pollard_pin.kinematics.ik_common import KinematicFrames
    from pollard_pin.kinematics.ik_newton import frame_drifts, kinematic_matrix

    rng = np.random.default_rng(3)
    m, d = robot.model, robot.data
    Q = rng.uniform(-np.pi, np.pi, (25, m.nq))
    V = rng.normal(0.0, 2.0, (25, m.nv))
    lay = layout(robot)
    assert len(lay.joints) == m.njoints - 1  # every joint's column is filled
    R, o = lay.tree.placements(Q)
    K, pos = point_rows(lay, R, o, m.nv)
    drift, omega = point_drifts(lay, R, o, V, pos)
    fr = KinematicFrames.of(robot)
    for k in range(len(Q)):
        ref = kinematic_matrix(m, d, robot.constraint_models, robot.constraint_datas, fr, Q[k])
        assert np.abs(K[k] - ref).max() <= 1e-14
        ref_drift = frame_drifts(m, d, fr, Q[k], V[k])  # also runs forwardKinematics(q, v, 0)
        assert np.abs(drift[k] - ref_drift).max() <= 1e-13 * max(1.0, np.abs(ref_drift).max())
        for j, i in lay.tree.slot.items():
            w = d.oMi[j].rotation @ d.v[j].angular
            assert np.abs(omega[i, k] - w).max() <= 1e-13 * max(1.0, np.abs(w).max())



def test_stacked_energies_equal_pinocchios(robot):
    # The inverse dynamics' energies (one numpy pass over the tree) against Pinocchio's
    # computeKineticEnergy / computePotentialEnergy, sample by sample.
    import pinocchio as pin

    from pollard_pin.dynamics.inverse import stacked_energies

    rng = np.random.default_rng(11)
    m = robot.model
    Q = rng.uniform(-np.pi, np.pi, (30, m.nq))
    V = rng.normal(0.0, 2.0, (30, m.nv))
    K, U = stacked_energies(m, Q, V)
    for k in range(len(Q)):
        pin.forwardKinematics(m, robot.data, Q[k], V[k])
        assert K[k] == pytest.approx(pin.computeKineticEnergy(m, robot.data), rel=1e-13)
        assert U[k] == pytest.approx(pin.computePotentialEnergy(m, robot.data, Q[k]),
                                     rel=1e-13, abs=1e-15)


def test_reachable_sequences_judge_each_sequence_as_alone(robot):
    # 240 copies of the thesis path moved and turned at random, half of them far: each is
    # judged by inverse_kinematics + check_joint_limits alone (the brute force), and stacked
    # (the survivors of the screen fill more than one batch of BATCH_CHUNK samples).
    from collections import Counter

    from pollard_pin.kinematics import KinematicsError
    from pollard_pin.kinematics.ik import inverse_kinematics
    from pollard_pin.kinematics.ik_batch import reachable_sequences
    from pollard_pin.kinematics.limits import check_joint_limits

    base = pp.thesis_trajectory(samples=61).poses
    rng = np.random.default_rng(3)
    seqs = []
    for k in range(240):
        s = 0.25 if k % 2 else 1.0
        p = base.copy()
        p[:, :3] += rng.normal(0.0, 0.12 * s, 3)
        p[:, 3:] += rng.normal(0.0, 0.5 * s, 3)
        seqs.append(p)
    seqs = np.array(seqs)
    ref, why = [], Counter()
    for p in seqs:
        try:
            check_joint_limits(robot, inverse_kinematics(robot, p).q)
            ref.append(True)
        except KinematicsError as exc:
            ref.append(False)
            why[type(exc).__name__] += 1
    # every kind of failure is among them, and enough pass to fill more than one batch
    assert set(why) == {"UnreachablePoseError", "SingularityError", "JointLimitError"}
    assert sum(ref) * len(base) > 4096
    assert np.array_equal(reachable_sequences(robot, seqs), ref)
    assert np.array_equal(reachable_sequences(robot, seqs[::-1]), ref[::-1])
    # a non-finite pose: the input error of its sequence alone
    from pollard_pin.kinematics import KinematicsInputError

    seqs[5:, 7, 2] = np.nan
    with pytest.raises(KinematicsInputError) as alone:
        inverse_kinematics(robot, seqs[5])
    with pytest.raises(KinematicsInputError) as stacked:
        reachable_sequences(robot, seqs)
    assert str(stacked.value) == str(alone.value) and stacked.value.sample == 7


def test_the_solved_screen_fails_only_what_the_whole_solve_fails(robot):
    # reachable_sequences' second screen (SCREEN samples of each sequence through every
    # rule, from the whole sequence's unwrapped angles) against the whole solve of every
    # sequence (no screen): the same answers, and the screen alone fails some of those the
    # whole solve fails (the point of it: 93 % of them in a line plan's shift scans)
    from pollard_pin.kinematics.ik_batch import (
        SCREEN,
        _closed_form_passes,
        _rules_hold,
        _solved_pass,
        continuous_sequences,
    )
    from pollard_pin.kinematics.margins import Margins

    base = pp.thesis_trajectory(samples=41).poses
    rng = np.random.default_rng(8)
    seqs = np.repeat(base[None], 120, axis=0)
    seqs[:, :, :3] += rng.normal(0.0, 0.05, (120, 1, 3))
    seqs[:, :, 3:] += rng.normal(0.0, 0.25, (120, 1, 3))
    margins = Margins()
    passes, q18 = _closed_form_passes(robot, seqs, margins)
    alive = passes.all(axis=1)
    seqs, q18 = seqs[alive], q18[alive]
    q0 = continuous_sequences(q18[:, :, :12])
    whole = _rules_hold(robot, seqs, q0, margins)
    at = np.linspace(0, len(base) - 1, SCREEN).astype(int)
    screened = _rules_hold(robot, seqs[:, at], q0[:, at], margins)
    assert np.array_equal(_solved_pass(robot, seqs, q18, margins), whole)
    assert not (screened < whole).any() and 10 <= whole.sum() <= len(whole) - 10
    assert (~screened).sum() >= 3


def test_a_block_at_rest_is_the_block_with_zero_rates(robot):
    # _batch_block at_rest (no drifts) against the same block given zero rates: every
    # figure the same to the bit, the rates, accelerations and spherical rates zero or not
    # finite alike (a pose singular by construction among them: a wrist at θ1716 = 0)
    from pollard_pin.analytic import closed_form
    from pollard_pin.kinematics.ik_batch import _batch_block, continuous_sequences
    from pollard_pin.kinematics.ik_common import IK_TOL
    from pollard_pin.timing import Stopwatch

    rng = np.random.default_rng(9)
    poses = pp.thesis_trajectory(samples=200).poses.copy()
    poses[:, :3] += rng.normal(0.0, 0.08, (200, 3))
    poses[:, 3:] += rng.normal(0.0, 0.6, (200, 3))
    q18, failed = closed_form.position_ik_masked(robot.params, poses)
    fine = ~np.logical_or.reduce(list(failed.values()))
    poses = poses[fine]
    q0 = continuous_sequences(q18[fine][None, :, :12])[0]
    q0[5, robot.joint_names.index("theta1716")] = 0.0  # a wrist singular by construction
    zero, t = np.zeros_like(poses), np.arange(len(poses), dtype=float)
    args = (robot, q0, (poses, zero, zero, t), IK_TOL, 0, Stopwatch(None))
    moving, rest = _batch_block(*args, strict=False), _batch_block(*args, strict=False,
                                                                   at_rest=True)
    for f in ("q", "spherical", "closure_residual", "tool_error", "wrist_margin",
              "sigma_parallel", "sigma_serial", "sigma_parallel_max", "sigma_serial_max",
              "constraint_jacobian"):
        assert getattr(rest, f).tobytes() == getattr(moving, f).tobytes(), f
    for f in ("v", "a", "d_spherical"):
        m, r = getattr(moving, f), getattr(rest, f)
        assert np.array_equal(np.isfinite(m), np.isfinite(r)), f
        assert (m[np.isfinite(m)] == 0).all() and (r[np.isfinite(r)] == 0).all(), f
    assert not np.isfinite(moving.v).all() or not np.isfinite(moving.d_spherical).all()


def test_gather_equals_the_blocks_concatenated(robot):
    # The blocks written in place into one result: bit for bit the old path's concatenation
    # of the blocks' fields (every sample, every field, the arrays' shapes and dtypes).
    from dataclasses import fields

    from pollard_pin.kinematics.ik_batch import gather

    traj = smooth_random_trajectory(4, samples=250)
    args = (traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    cuts = [0, 97, 194, 250]
    parts = [inverse_kinematics_batch(robot, *(x[a:b] for x in args))
             for a, b in zip(cuts, cuts[1:])]
    result = None
    for (a, b), part in zip(zip(cuts, cuts[1:]), parts):
        result = gather(result, part, slice(a, b), traj.poses, traj.t)
    for f in fields(result):
        got = getattr(result, f.name)
        if f.name == "joint_names":
            assert got == robot.joint_names
            continue
        want = np.concatenate([getattr(p, f.name) for p in parts])
        assert got.shape == want.shape and got.dtype == want.dtype, f.name
        assert got.tobytes() == want.tobytes(), f.name


def test_continuous_sequences_equal_each_sequence_alone():
    # One call over S sequences side by side: bit for bit make_continuous of each alone (the
    # old path), with whole turns to take off the first sample and wraps to unwrap.
    from pollard_pin.analytic.closed_form import make_continuous
    from pollard_pin.kinematics.ik_batch import continuous_sequences

    rng = np.random.default_rng(5)
    q = np.cumsum(rng.normal(0.0, 1.2, (7, 40, 12)), axis=1) + rng.normal(0.0, 9.0, (7, 1, 12))
    want = np.stack([make_continuous(s) for s in q])
    got = continuous_sequences(q)
    assert got.shape == want.shape and got.tobytes() == np.ascontiguousarray(want).tobytes()
    assert not np.array_equal(want, q)  # turns and wraps were taken off
