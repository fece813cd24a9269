"""Closing the loops: the passive angles for given actuator angles (forward kinematics),
by Newton on the cut spherical joints' residual (docs/model.md §4)."""
from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from ..analytic.taskspace import pose_from_se3
from ..checks import float_array, shorten
from ..errors import say_less
from ..model.build import Robot, check_robot, constraint_residual_jacobian
from .errors import ClosureError, ClosureSingularError, KinematicsInputError
from .singularity import SIGMA_FLOOR, sigma_range, solve_small

CLOSURE_TOL = 1e-12  # m, closure residual reached by Newton
MAX_ITER = 50


def _leg_residuals(r: np.ndarray) -> np.ndarray:
    return np.linalg.norm(r.reshape(2, 3), axis=1)


def solve_closure(robot: Robot, actuated: np.ndarray, q_guess: np.ndarray | None = None,
                  tol: float = CLOSURE_TOL, max_iter: int = MAX_ITER) -> np.ndarray:
    """The full configuration with the six actuator angles fixed and the loops closed.

    Newton on the six passive angles with the constraint Jacobian (docs/model.md §4),
    warm-started at ``q_guess``.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    actuated : ndarray
        The six actuator angles (6,) [rad], :attr:`Robot.actuated` order.
    q_guess : ndarray or None, optional
        A configuration (12,) [rad] to start from; None: the home posture.
    tol : float, optional
        The closure residual to reach [m] (default 1e-12).
    max_iter : int, optional
        Newton steps at most (default 50).

    Returns
    -------
    ndarray
        The configuration (12,) [rad], :attr:`Robot.joint_names` order.

    Raises
    ------
    ClosureError
        The loops cannot be closed (a leg cannot reach its attachment point); the message
        names the leg and the residual reached.
    SingularityError
        The loops close only on a parallel singularity (docs/model.md §12), where the
        passive angles are not locally unique.
    ValueError
        ``actuated`` is not six finite numbers, or ``q_guess`` not twelve.

    Examples
    --------
    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> from pollard_pin.kinematics import solve_closure
    >>> robot = pp.load()
    >>> home = robot.home()
    >>> q = solve_closure(robot, home[robot.actuated_v])
    >>> bool(np.allclose(q, home, atol=1e-9))
    True
    """
    return close_loops(robot, actuated, q_guess, tol, max_iter)[0]


def close_loops(robot: Robot, actuated: np.ndarray, q_guess: np.ndarray | None = None,
                tol: float = CLOSURE_TOL, max_iter: int = MAX_ITER
                ) -> tuple[np.ndarray, np.ndarray]:
    """(q (12,), Jc (6 × 12) at q): the full configuration with the six actuator angles fixed
    and the loops closed, and the constraint Jacobian there (computed anyway: Newton's last
    pass), for the velocity map and the dynamics at q.

    Newton on the passive angles with the constraint Jacobian, warm-started at ``q_guess``
    (default: the home posture). Raises :class:`ClosureError` naming the leg and the residual
    reached when the actuator set cannot be assembled, and :class:`ClosureSingularError` (also
    a :class:`SingularityError`, chain "parallel", with σ) when the loops close on a parallel
    singularity, where the passive angles are not locally unique (docs/model.md §12).
    """
    act = np.asarray(actuated, dtype=float).reshape(-1)
    # a finite sum means every entry is finite (one reduction: this runs every control tick)
    if act.shape != (6,) or not math.isfinite(act.sum()):
        raise KinematicsInputError(f"actuator angles must be 6 finite numbers "
                                   f"({', '.join(robot.actuated)}), got "
                                   f"{shorten(act.tolist())}", chain="actuated")
    q = (robot.q_reference if q_guess is None else np.asarray(q_guess, dtype=float)).copy()
    if q.shape != (robot.model.nq,) or not math.isfinite(q.sum()):
        raise KinematicsInputError(f"q_guess must be {robot.model.nq} finite joint angles, "
                                   f"got {shorten(q.tolist())}", chain="q_guess")
    ia, ip = robot.actuated_v, robot.passive_v
    q[ia] = act
    r, Jc = constraint_residual_jacobian(robot, q)
    for _ in range(max_iter):
        if np.abs(r).max() <= tol:
            return _check_regular(robot, q, act, Jc[:, ip]), Jc
        try:
            step = solve_small(Jc[:, ip], r)
        except np.linalg.LinAlgError:  # exactly singular Jp: least squares survives it
            step = np.linalg.lstsq(Jc[:, ip], r, rcond=None)[0]
        # Damped step: never move a passive angle by more than 0.5 rad at once.
        q[ip] -= step * min(1.0, 0.5 / max(np.abs(step).max(), 1e-300))
        r, Jc = constraint_residual_jacobian(robot, q)
    legs = _leg_residuals(r)
    leg = int(np.argmax(legs)) + 1
    angles = dict(zip(robot.actuated, act.round(6).tolist()))
    raise ClosureError(
        f"cannot close the loops for actuator angles {angles} "
        f"(rad): after {max_iter} Newton steps the residual is {legs[0]*1e3:.4g} mm on leg 1 and "
        f"{legs[1]*1e3:.4g} mm on leg 2 (tolerance {tol:g} m); leg {leg} cannot reach its "
        f"attachment point", leg=leg, residual=float(legs.max()))


def _check_regular(robot: Robot, q: np.ndarray, act: np.ndarray, Jp: np.ndarray
                   ) -> np.ndarray:
    """q, unless Jc_p (``Jp``, at q) is singular there (σ_min < SIGMA_FLOOR σ_max): the loops
    then close on a parallel singularity and the passive angles are not locally unique."""
    smin, smax = (float(x) for x in sigma_range(Jp))
    if smin >= SIGMA_FLOOR * smax:
        return q
    angles = dict(zip(robot.actuated, act.round(6).tolist()))
    why = (f"the passive-joint constraint Jacobian's smallest singular value {smin:.3g} is "
           f"below the numerical floor {SIGMA_FLOOR:g} × σ_max (docs/model.md §12)")
    raise ClosureSingularError(say_less(
        f"the loops close for actuator angles {angles} (rad) only on a parallel singularity: "
        f"{why}, so the passive angles are not unique there",
        f"the loops close for these actuator angles only on a parallel singularity: {why}"),
        chain="parallel", sigma=smin,
        amount=SIGMA_FLOOR * smax - smin)


def closure_drift(robot: Robot, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """γ_c = J̇c(q, v)·v (6,): the closures' acceleration drift, a_A⁰ − a_B⁰ per closure at
    q̈ = 0 (classical point accelerations, world axes), so that a motion on the loops has
    Jc·q̈ = −γ_c (docs/model.md §11)."""
    model, data = robot.model, robot.data
    pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
    lwa = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    return np.concatenate([
        pin.getFrameClassicalAcceleration(model, data, a, lwa).linear
        - pin.getFrameClassicalAcceleration(model, data, b, lwa).linear
        for a, b in robot.closure_frame_ids])


def tool_pose(robot: Robot, q: np.ndarray) -> pin.SE3:
    """The world placement of the tool tip (the ``tip`` frame) at a configuration.

    Parameters
    ----------
    robot : Robot
        The model; its ``data`` frames are updated here.
    q : ndarray
        A configuration (12,) [rad], :attr:`Robot.joint_names` order.

    Returns
    -------
    pinocchio.SE3
        The tip's rotation and position [m] in the world frame.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> from pollard_pin.kinematics import tool_pose
    >>> robot = pp.load()
    >>> tool_pose(robot, robot.home()).translation.round(3).tolist()  # docs/model.md §9
    [0.55, 0.0, 0.16]
    """
    if np.shape(q) != (robot.model.nq,):  # Pinocchio's own check is a multi-line C++ error
        raise KinematicsInputError(f"q has shape {np.shape(q)}, expected ({robot.model.nq},) "
                                   "(the joint angles, Robot.joint_names order)", chain="q")
    pin.framesForwardKinematics(robot.model, robot.data, q)
    return pin.SE3(robot.data.oMf[robot.tip_frame])


def forward_kinematics(robot: Robot, actuated: np.ndarray, q_guess: np.ndarray | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Forward kinematics: actuator angles to full configurations and tool poses.

    Each sample closes the loops (:func:`~pollard_pin.kinematics.solve_closure`) warm-started
    from the previous one, so a trajectory stays on one assembly branch.

    Parameters
    ----------
    robot : Robot
        The model.
    actuated : ndarray
        Actuator angles (N, 6) or (6,) [rad], :attr:`Robot.actuated` order.
    q_guess : ndarray or None, optional
        A configuration (12,) [rad] the first sample starts from; None: the home posture.

    Returns
    -------
    q : ndarray
        Configurations (N, 12) [rad], :attr:`Robot.joint_names` order.
    poses : ndarray
        Tool poses (N, 6): x, y, z [m] and the ZYZ angles ψ, θ, φ [rad].

    Raises
    ------
    ClosureError
        A sample's loops cannot be closed (the message names the sample, the leg and the
        residual).
    SingularityError
        A sample closes only on a parallel singularity.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> q, poses = pp.forward_kinematics(robot, robot.home()[robot.actuated_v])
    >>> poses.round(3).tolist()
    [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]]
    """
    check_robot(robot)
    act = np.atleast_2d(float_array(actuated, "actuated", error=KinematicsInputError))
    if act.ndim != 2 or act.shape[1] != 6:
        raise KinematicsInputError(f"actuator angles have shape {np.shape(actuated)}, expected "
                                   f"(N, 6) or (6,) ({', '.join(robot.actuated)})")
    if q_guess is not None:
        q_guess = float_array(q_guess, "q_guess", error=KinematicsInputError)
    qs = np.empty((len(act), robot.model.nq))
    poses = np.empty((len(act), 6))
    q = q_guess
    for k, a in enumerate(act):
        try:
            q = solve_closure(robot, a, q_guess=q)
        except ClosureSingularError as exc:
            raise ClosureSingularError(exc.detail, sample=k, chain=exc.chain, sigma=exc.sigma,
                                       amount=exc.amount) from None
        except ClosureError as exc:
            raise ClosureError(f"sample {k}: {exc}", exc.leg, exc.residual) from None
        qs[k] = q
        poses[k] = pose_from_se3(tool_pose(robot, q))
    return qs, poses
