"""The engine comparisons of the report (docs/model.md §7, §8, §13, §17): Pinocchio's run
against the thesis' closed form and Euler–Lagrange torques, the free-body Newton–Euler joint
loads and the MuJoCo peer, as max/RMS agreement figures."""
from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np


def agreement(ours, ref) -> dict:
    """How closely ``ours`` matches ``ref``.

    Parameters
    ----------
    ours, ref : ndarray
        Arrays of one shape.

    Returns
    -------
    dict
        ``max_abs_diff`` (the largest ``|ours − ref|``), ``reference_peak`` (the largest
        ``|ref|``) and ``relative`` (their ratio; NaN when ``ref`` is all zero).

    Examples
    --------
    >>> from pollard_pin.crosscheck.compare import agreement
    >>> agreement([1.0, 2.0], [1.0, 2.5])
    {'max_abs_diff': 0.5, 'reference_peak': 2.5, 'relative': 0.2}
    """
    ours, ref = np.asarray(ours, dtype=float), np.asarray(ref, dtype=float)
    diff = float(np.max(np.abs(ours - ref)))
    scale = float(np.max(np.abs(ref)))
    return {"max_abs_diff": diff, "reference_peak": scale,
            "relative": diff / scale if scale > 0 else float("nan")}


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def result_loads(robot, result):
    """The run's joint loads (docs/model.md §17), computed here if the run did not keep them."""
    if getattr(result, "loads", None) is not None:
        return result.loads
    from ..dynamics.loads import joint_loads

    return joint_loads(robot, result.ik, result.dynamics)


def cross_check_thesis(robot, result) -> dict:
    """Pinocchio vs the thesis' closed-form IK and Euler–Lagrange torques, and the joint loads
    vs free-body Newton–Euler (the ``thesis`` column of ``pollard-pin report``).

    Parameters
    ----------
    robot : Robot
        The model.
    result : RunResult
        :func:`~pollard_pin.run_pipeline`'s result.

    Returns
    -------
    dict
        :func:`agreement` figures for the joint positions [rad], velocities, accelerations
        and, with dynamics, the torques [N·m], joint forces [N] and moments [N·m].
    """
    from ..analytic import closed_form as ik_mod
    from . import euler_lagrange as lagrange

    traj, ik, dyn = result.trajectory, result.ik, result.dynamics
    q_th, v_th, a_th = ik_mod.inverse_kinematics(robot.params, traj.poses, traj.d_poses,
                                                 traj.dd_poses)
    cols = [ik_mod.JOINTS.index(n) for n in ik.joint_names]
    out = {
        "joint_position_rad": {"max_abs_diff": float(np.max(np.abs(_wrap(ik.q - q_th[:, cols]))))},
        "joint_velocity": agreement(ik.v, v_th[:, cols]),
        "joint_acceleration": agreement(ik.a, a_th[:, cols]),
    }
    if dyn is not None:
        tau_th = lagrange.inverse_dynamics(robot.params, traj.poses, traj.d_poses,
                                           traj.dd_poses)["tau"]
        out["torque"] = agreement(dyn.tau, tau_th)
        from . import newton_euler

        ne, loads = newton_euler.joint_loads(robot.params, traj.poses, traj.d_poses,
                                             traj.dd_poses), result_loads(robot, result)
        out["joint_force"] = agreement(loads.force, ne["force"])
        out["joint_moment"] = agreement(loads.moment, ne["moment"])
    return out


def cross_check_mujoco(robot, result) -> dict:
    """Pinocchio vs MuJoCo: actuator torques, closure forces and joint loads (the ``mujoco``
    column of ``pollard-pin report``).

    Parameters
    ----------
    robot : Robot
        The model (its URDF is the one MuJoCo reads).
    result : RunResult
        :func:`~pollard_pin.run_pipeline`'s result, with its dynamics.

    Returns
    -------
    dict
        ``available`` and, when MuJoCo is installed, :func:`agreement` figures for the
        torques [N·m], closure forces and joint forces [N], joint moments [N·m] and MuJoCo's
        own loop residual [m]; otherwise the ``reason`` it was skipped.
    """
    try:
        import mujoco  # noqa: F401
    except ImportError as exc:
        return {"available": False,
                "reason": f"MuJoCo is not installed ({exc}); pip install mujoco to compare"}
    from . import mujoco as peer

    ik, dyn = result.ik, result.dynamics
    cols = [list(ik.joint_names).index(n) for n in peer.JOINTS]
    with tempfile.TemporaryDirectory() as tmp:
        urdf = Path(tmp) / "pollard.urdf"
        urdf.write_text(robot.urdf)  # the model actually used, whatever its parameters
        mj = peer.inverse_dynamics_mujoco(ik.q[:, cols], ik.v[:, cols], ik.a[:, cols],
                                          urdf_path=urdf)
        from .mujoco_loads import joint_loads_mujoco

        mjl = joint_loads_mujoco(ik.q[:, cols], ik.v[:, cols], ik.a[:, cols],
                                 mj["closure_forces"], built=peer.cached_model(urdf))
    act = [list(peer.ACTUATED).index(n) for n in robot.actuated]
    loads, back = result_loads(robot, result), [list(peer.JOINTS).index(n) for n in ik.joint_names]
    return {"available": True,
            "torque": agreement(dyn.tau, mj["tau"][:, act]),
            "closure_force": agreement(dyn.closure_forces, mj["closure_forces"]),
            "joint_force": agreement(loads.force, mjl["force"][:, back]),
            "joint_moment": agreement(loads.moment, mjl["moment"][:, back]),
            "mujoco_closure_residual_m": float(np.max(mj["residual"]))}


__all__ = ["agreement", "cross_check_thesis", "cross_check_mujoco"]
