"""Loads in every joint: the wrench each bearing, pin and U-joint cross carries
(docs/model.md §17).

For every tree joint, the force and the moment that the parent body exerts on the child body
through the joint, about the URDF joint origin, in world axes. They follow from the recursive
Newton–Euler algorithm (RNEA, Featherstone ch. 5) with the closure forces of the inverse
dynamics (docs/model.md §13) applied to the bodies they act on: +λ_i on ``link_i``, −λ_i on
the platform, each at its side of the ball joint (docs/model.md §4).

Two implementations of the same recursion, on Pinocchio's model tree (placements, inertias,
gravity):

* :func:`joint_loads` (production): the forward (kinematics) and backward (forces) passes
  stacked over samples in numpy — no Python loop over samples;
* :func:`joint_loads_rnea` (reference): Pinocchio's own ``rnea`` with the closure forces as
  external forces, sample by sample, reading the joint forces ``data.f`` (local joint frames)
  and rotating them into world axes. The tests hold the two equal to round-off.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..checks import instance
from ..errors import InputError
from ..kinematics.ik import IKResult
from ..kinematics.tree import AXES, cross, joint_motion, matvec
from ..model.build import Robot, check_robot
from ..timing import Stopwatch
from .averages import cubic_mean
from .inverse import DynamicsResult


@dataclass
class JointLoads:
    """Joint wrenches along a trajectory (docs/model.md §17), from
    :func:`~pollard_pin.joint_loads`. Arrays have one row per sample; joints in ``joints``
    order (the tree order of docs/model.md §2).

    Attributes
    ----------
    t : ndarray
        Times (N,) [s].
    joints : tuple of str
        The 12 tree joints.
    force, moment : ndarray
        (N, 12, 3): the force [N] of the parent on the child through each joint and its
        moment [N·m] about the joint origin, world axes.
    axis : ndarray
        (N, 12, 3): each joint's unit axis, world axes.
    closure_forces : ndarray
        (N, 2, 3): the ball-joint force on each leg [N], world axes.

    The properties ``axial``, ``radial`` [N], ``torque`` and ``bending`` [N·m] (each
    (N, 12)) are frame-invariant; :meth:`bearing_table` gives their peaks and ISO 281
    equivalent loads.
    """

    t: np.ndarray
    joints: tuple[str, ...]
    force: np.ndarray  # (N, 12, 3) force of the parent on the child [N], world axes
    moment: np.ndarray  # (N, 12, 3) its moment about the joint origin [N·m], world axes
    axis: np.ndarray  # (N, 12, 3) unit joint axis, world axes
    closure_forces: np.ndarray  # (N, 2, 3) ball-joint force λ_i on link_i [N], world axes

    @property
    def axial(self) -> np.ndarray:
        """Force along the joint axis [N], (N, 12), signed."""
        return np.einsum("nji,nji->nj", self.force, self.axis)

    @property
    def radial(self) -> np.ndarray:
        """Force perpendicular to the joint axis [N], (N, 12), magnitude."""
        f = self.force - self.axial[..., None] * self.axis
        return np.linalg.norm(f, axis=-1)

    @property
    def torque(self) -> np.ndarray:
        """Moment along the joint axis [N·m], (N, 12): the actuator torque for the actuated
        joints, zero for the passive ones."""
        return np.einsum("nji,nji->nj", self.moment, self.axis)

    @property
    def bending(self) -> np.ndarray:
        """Moment perpendicular to the joint axis [N·m], (N, 12), magnitude."""
        m = self.moment - self.torque[..., None] * self.axis
        return np.linalg.norm(m, axis=-1)

    def columns(self) -> dict[str, np.ndarray]:
        """``F_<joint>_x/y/z`` [N] and ``M_<joint>_x/y/z`` [N·m] per tree joint (world axes)."""
        cols = {}
        for j, name in enumerate(self.joints):
            for prefix, arr in (("F", self.force), ("M", self.moment)):
                cols.update({f"{prefix}_{name}_{c}": arr[:, j, i] for i, c in enumerate("xyz")})
        return cols

    def bearing_table(self) -> dict:
        """Per joint: peak axial, radial [N], bending, axis torque [N·m] and the ISO 281 cubic
        means of the radial and axial force (time-weighted) [N]; per ball joint: peak and cubic
        mean of |λ_i| [N]."""
        ax, rad = np.abs(self.axial), self.radial
        peaks = {"peak_axial": ax.max(0), "peak_radial": rad.max(0),
                 "peak_bending": self.bending.max(0), "peak_torque": np.abs(self.torque).max(0),
                 "equivalent_radial": cubic_mean(self.t, rad),
                 "equivalent_axial": cubic_mean(self.t, ax)}
        lam = np.linalg.norm(self.closure_forces, axis=-1)
        joints = {n: {k: float(v[j]) for k, v in peaks.items()}
                  for j, n in enumerate(self.joints)}
        balls = {f"leg {i + 1}": {"peak_force": float(lam[:, i].max()),
                                  "equivalent_force": float(cubic_mean(self.t, lam[:, i]))}
                 for i in range(lam.shape[1])}
        return {"joints": joints, "spherical": balls}



@dataclass(frozen=True)
class _Tree:
    """What the recursion needs from Pinocchio's model, once per robot."""

    parents: tuple[int, ...]
    axes: tuple[int, ...]
    offset: tuple[bool, ...]  # joint origin away from its parent's (not a U joint or wrist)
    masses: tuple[float, ...]
    levers: tuple[np.ndarray, ...]  # CoG in the joint frame
    inertias: tuple[np.ndarray, ...]  # about the CoG, joint frame
    gravity: np.ndarray
    # closure i: (joint, point in its frame) for the leg side A and the platform side B
    closure_points: tuple[tuple[tuple[int, np.ndarray], tuple[int, np.ndarray]], ...]


def _tree(robot: Robot) -> _Tree:
    model = robot.model
    parents, axes, offset, masses, levers, inertias = [0], [0], [False], [0.0], [None], [None]
    for j in range(1, model.njoints):
        axis = AXES.get(model.joints[j].shortname())
        if axis is None:
            raise NotImplementedError(f"joint loads: joint {model.names[j]} is a "
                                      f"{model.joints[j].shortname()}, not RX/RY/RZ")
        M, Y = model.jointPlacements[j], model.inertias[j]
        parents.append(int(model.parents[j]))
        axes.append(axis)
        offset.append(bool(np.any(M.translation)))
        masses.append(float(Y.mass))
        levers.append(np.array(Y.lever))
        inertias.append(np.array(Y.inertia))

    def point(frame):
        f = model.frames[robot.frame_id(frame)]
        return int(f.parentJoint), np.array(f.placement.translation)

    closures = tuple((point(c.frame_a), point(c.frame_b)) for c in robot.closures)
    return _Tree(tuple(parents), tuple(axes), tuple(offset), tuple(masses), tuple(levers),
                 tuple(inertias), np.array(model.gravity.linear), closures)


def _passes(model, tree: _Tree, Q, V, A, lam):
    """RNEA stacked over samples (world axes): the forward pass of :func:`.tree.joint_motion`,
    then the backward force pass. Returns force, moment about each joint origin, joint axis,
    each (N, njoints − 1, 3)."""
    n, nj = len(Q), len(tree.parents)
    zero = np.zeros((n, 3))
    mo = joint_motion(model, Q, V, A)
    R, o, w, al, acc = mo.R, mo.o, mo.w, mo.alpha, mo.ao
    F = [zero.copy() for _ in range(nj)]
    M = [zero.copy() for _ in range(nj)]
    for i, ends in enumerate(tree.closure_points):  # +λ on link_i (A), −λ on the platform (B)
        for (j, local), sign in zip(ends, (1.0, -1.0)):
            f = sign * lam[:, i]
            F[j] -= f
            M[j] -= cross(R[j] @ local, f)
    for j in range(nj - 1, 0, -1):
        m = tree.masses[j]
        if m > 0.0:  # massless U-joint crosses carry nothing of their own
            r = R[j] @ tree.levers[j]
            a_c = acc[j] + cross(al[j], r) + cross(w[j], cross(w[j], r))
            f = m * (a_c - tree.gravity)
            Rt = np.swapaxes(R[j], -1, -2)
            wb, ab = matvec(Rt, w[j]), matvec(Rt, al[j])  # body axes: I is constant there
            Iw = wb @ tree.inertias[j]  # I symmetric: (I ω)ᵀ = ωᵀ I
            F[j] += f
            M[j] += matvec(R[j], ab @ tree.inertias[j] + cross(wb, Iw)) + cross(r, f)
        p = tree.parents[j]
        if p:
            F[p] += F[j]
            M[p] += M[j] + cross(o[j] - o[p], F[j]) if tree.offset[j] else M[j]
    return (np.stack(F[1:], axis=1), np.stack(M[1:], axis=1),
            np.stack([R[j][:, :, tree.axes[j]] for j in range(1, nj)], axis=1))


def _closure_forces(robot: Robot, ik: IKResult, dyn) -> np.ndarray:
    check_robot(robot)
    instance(ik, "ik", IKResult, "an IKResult (pollard_pin.inverse_kinematics)")
    instance(dyn, "dyn", DynamicsResult, "a DynamicsResult (pollard_pin.inverse_dynamics)")
    lam = np.asarray(dyn.closure_forces, dtype=float)
    if lam.shape != (len(ik), len(robot.closures), 3):
        raise InputError(f"closure forces of shape {lam.shape} do not match the IK result's "
                         f"{len(ik)} samples × {len(robot.closures)} closures × 3")
    return lam


def joint_loads(robot: Robot, ik: IKResult, dyn, timings: dict | None = None) -> JointLoads:
    """Joint loads along an IK result and its inverse dynamics (``dyn``, for the closure forces),
    stacked over samples (docs/model.md §17).

    Ideal joints, as ``run``: with ``JointLosses`` in ``dyn`` the axis moment is τ minus the
    loss torque of the joint, not τ.

    Parameters
    ----------
    robot : Robot
        The model.
    ik : IKResult
        The joint motion (:func:`pollard_pin.inverse_kinematics`).
    dyn : pollard_pin.dynamics.inverse.DynamicsResult
        Its inverse dynamics (:func:`pollard_pin.inverse_dynamics`).
    timings : dict or None, optional
        Accumulates the seconds spent.

    Returns
    -------
    JointLoads
        The force and moment through every tree joint at every sample.

    Examples
    --------
    The moment along an actuated joint's axis is its actuator torque:

    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> traj = pp.thesis_trajectory(duration=20.0, samples=51)
    >>> ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    >>> dyn = pp.inverse_dynamics(robot, ik)
    >>> loads = pp.joint_loads(robot, ik, dyn)
    >>> bool(np.allclose(loads.torque[:, robot.actuated_v], dyn.tau, atol=1e-10))
    True
    """
    clock = Stopwatch(timings)
    lam = _closure_forces(robot, ik, dyn)
    F, M, U = _passes(robot.model, _tree(robot), ik.q, ik.v, ik.a, lam)
    clock.lap("loads")
    return JointLoads(t=ik.t, joints=robot.joint_names, force=F, moment=M, axis=U,
                      closure_forces=lam)


def joint_loads_rnea(robot: Robot, ik: IKResult, dyn) -> JointLoads:
    """The same loads from Pinocchio's ``rnea`` with the closure forces as external forces,
    sample by sample: ``data.f[j]`` is the force of joint j's parent on its child, in the local
    joint frame at the joint origin."""
    model, data = robot.model, robot.data
    n, nj = len(ik), model.njoints
    lam = _closure_forces(robot, ik, dyn)
    points = [tuple((model.frames[robot.frame_id(f)].parentJoint,
                     np.array(model.frames[robot.frame_id(f)].placement.translation))
                    for f in (c.frame_a, c.frame_b)) for c in robot.closures]
    axes = [AXES[model.joints[j].shortname()] for j in range(1, nj)]
    F, M, U = (np.empty((n, nj - 1, 3)) for _ in range(3))
    for k in range(n):
        pin.forwardKinematics(model, data, ik.q[k])
        fext = pin.StdVec_Force()
        for _ in range(nj):
            fext.append(pin.Force.Zero())
        for i, ends in enumerate(points):
            for (j, local), sign in zip(ends, (1.0, -1.0)):
                Rj = data.oMi[j].rotation
                f_local = Rj.T @ (sign * lam[k, i])  # local axes, applied at ``local``
                fext[j] = fext[j] + pin.Force(f_local, np.cross(local, f_local))
        pin.rnea(model, data, ik.q[k], ik.v[k], ik.a[k], fext)
        for j in range(1, nj):
            Rj = data.oMi[j].rotation
            F[k, j - 1] = Rj @ data.f[j].linear
            M[k, j - 1] = Rj @ data.f[j].angular
            U[k, j - 1] = Rj[:, axes[j - 1]]
    return JointLoads(t=ik.t, joints=robot.joint_names, force=F, moment=M, axis=U,
                      closure_forces=lam)


__all__ = ["JointLoads", "joint_loads", "joint_loads_rnea", "cubic_mean"]
