"""Forward recursions over Pinocchio's model tree, stacked over samples (docs/model.md §11,
§13, §17): the one home of joint placements, body velocities and accelerations. The inverse
kinematics, the energies and the joint loads all take their kinematics from here; placements,
point Jacobians and drifts run in the compiled kernels (:mod:`.kernels`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import kernels

AXES = {"JointModelRX": 0, "JointModelRY": 1, "JointModelRZ": 2}


@dataclass(frozen=True, eq=False)  # hashed by identity: a key for its world position
class Point:
    """A point fixed in joint ``joint``'s frame (``local``), moved by the v-columns ``cols``."""

    joint: int
    local: np.ndarray
    cols: np.ndarray


@dataclass(frozen=True, eq=False)
class TreeArrays:
    """The layout as flat arrays (slot 0 = the base, then ``joints`` in order) for
    :mod:`.kernels`: placements, K rows of the points, drifts."""

    slot: dict  # joint id → slot
    parent: np.ndarray  # (S,) parent slot
    axis: np.ndarray  # (S,) revolute axis 0/1/2
    idx_q: np.ndarray  # (S,) configuration index
    col: np.ndarray  # (S,) velocity index
    rot: np.ndarray  # (S, 3, 3) joint placement rotation in the parent
    trans: np.ndarray  # (S, 3) joint placement translation in the parent
    pt_slot: np.ndarray  # (P,) points: closure A/B pairs, then the tip
    pt_local: np.ndarray  # (P, 3)
    pt_support: np.ndarray  # (P, depth) slots of the joints moving each point, −1 padded
    pt_row: np.ndarray  # (P,) first row of the point's block of K
    pt_sign: np.ndarray  # (P,) +1 for A and the tip, −1 for B

    @property
    def tool(self) -> tuple[int, int]:
        """The tip (the last point) and the first of the tool's angular rows (after its
        linear ones): K's last three rows."""
        return len(self.pt_slot) - 1, int(self.pt_row[-1]) + 3

    def placements(self, Q: np.ndarray):
        """World rotations (S, N, 3, 3) and origins (S, N, 3) at configurations Q (N, nq)."""
        Q = np.ascontiguousarray(Q, dtype=float)
        return kernels.tree_placements(np.cos(Q), np.sin(Q), self.parent[1:], self.axis[1:],
                                       self.idx_q[1:], self.rot[1:], self.trans[1:])


def tree_arrays(model, joints, points, rows, signs) -> TreeArrays:
    """The compiled kernels' arrays for ``joints`` (parents first) and ``points`` (:class:`Point`)
    with their first rows in K and signs."""
    joints = tuple(joints)
    slot = {0: 0, **{j: i + 1 for i, j in enumerate(joints)}}
    for j in joints:
        if model.joints[j].shortname() not in AXES:
            raise NotImplementedError(f"batched kinematics: joint {model.names[j]} is a "
                                      f"{model.joints[j].shortname()}, not RX/RY/RZ")
        if slot.get(model.parents[j], len(slot)) > slot[j]:
            raise ValueError(f"batched kinematics: the parent of {model.names[j]} must be "
                             "listed before it")
    every = (0,) + joints
    ints = lambda xs: np.array(xs, dtype=np.int64)  # noqa: E731
    support = [[slot[j] for j in model.supports[p.joint][1:]] for p in points]
    depth = max((len(x) for x in support), default=1)
    return TreeArrays(
        slot=slot, parent=ints([0] + [slot[model.parents[j]] for j in joints]),
        axis=ints([0] + [AXES[model.joints[j].shortname()] for j in joints]),
        idx_q=ints([0] + [model.joints[j].idx_q for j in joints]),
        col=ints([0] + [model.joints[j].idx_v for j in joints]),
        rot=np.array([np.eye(3) if j == 0 else model.jointPlacements[j].rotation
                      for j in every]).reshape(-1, 3, 3),
        trans=np.array([np.zeros(3) if j == 0 else model.jointPlacements[j].translation
                        for j in every]).reshape(-1, 3),
        pt_slot=ints([slot[p.joint] for p in points]),
        pt_local=np.array([p.local for p in points]).reshape(-1, 3),
        pt_support=ints([x + [-1] * (depth - len(x)) for x in support]),
        pt_row=ints(rows), pt_sign=np.array(signs, dtype=float))


def support_cols(model, joint: int) -> np.ndarray:
    """Velocity indices of the joints that move ``joint`` (its support, base excluded)."""
    return np.array([model.joints[j].idx_v for j in model.supports[joint][1:]])


def joint_placements(model, Q: np.ndarray, joints) -> dict:
    """World rotation (N, 3, 3) and origin (N, 3) of each listed joint frame at every sample
    (dict by joint, 0 = the base); the parent of each listed joint must be listed before it.
    One compiled pass over the tree (:func:`.kernels.tree_placements`)."""
    tree = tree_arrays(model, joints, (), (), ())
    R, o = tree.placements(Q)
    return {j: (R[i], o[i]) for j, i in tree.slot.items()}


@dataclass(frozen=True)
class TreeMotion:
    """World-axes motion of each listed joint's body, dicts by joint id (0 = the base):
    rotation ``R`` (N, 3, 3), origin ``o``, angular velocity ``w``, origin velocity ``vo``
    and, when accelerations were given, angular acceleration ``alpha`` and origin acceleration
    ``ao`` (each (N, 3))."""

    R: dict
    o: dict
    w: dict
    vo: dict
    alpha: dict | None = None
    ao: dict | None = None


def joint_motion(model, Q: np.ndarray, V: np.ndarray, A: np.ndarray | None = None,
                 joints=None) -> TreeMotion:
    """The forward recursion of docs/model.md §13/§17 at configurations Q, rates V and
    (optionally) accelerations A, each (N, nv); ``joints`` default every joint, parents first.
    With d = o_j − o_parent and z_j the joint axis:
    ω_j = ω_p + z_j q̇_j, ȯ_j = ȯ_p + ω_p × d, α_j = α_p + ω_p × z_j q̇_j + z_j q̈_j,
    ö_j = ö_p + α_p × d + ω_p × (ω_p × d). Placements come from :func:`joint_placements`."""
    joints = tuple(range(1, model.njoints)) if joints is None else tuple(joints)
    pl = joint_placements(model, Q, joints)
    zero = np.zeros((len(Q), 3))
    w, vo = {0: zero}, {0: zero}
    alpha, ao = ({0: zero}, {0: zero}) if A is not None else (None, None)
    for j in joints:
        p, jm = model.parents[j], model.joints[j]
        d = pl[j][1] - pl[p][1]
        u = pl[j][0][:, :, AXES[jm.shortname()]]
        wq = u * V[:, jm.idx_v, None]
        vo[j] = vo[p] + cross(w[p], d)
        w[j] = w[p] + wq
        if A is not None:
            ao[j] = ao[p] + cross(alpha[p], d) + cross(w[p], cross(w[p], d))
            alpha[j] = alpha[p] + cross(w[p], wq) + u * A[:, jm.idx_v, None]
    return TreeMotion(R={j: x[0] for j, x in pl.items()}, o={j: x[1] for j, x in pl.items()},
                      w=w, vo=vo, alpha=alpha, ao=ao)


def cross(a, b):
    """Cross product along the last axis, broadcasting the rest; cheaper than np.cross."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def matvec(A, x):
    return (A @ x[..., None])[..., 0]
