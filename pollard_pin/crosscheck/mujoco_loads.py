"""Joint loads from MuJoCo, the peer engine (docs/model.md §17).

No Pinocchio. At each sample, after ``mj_inverse``, the connect-equality rows of ``efc_force``
are set to the closure forces and ``mj_rnePostConstraint`` fills ``cfrc_int``: the wrench the
parent exerts on each body, (moment, force) in world axes about the centre of mass of the
body's kinematic subtree root (``subtree_com[body_rootid]``). Shifted to the joint anchor
(``xanchor``), it is the joint load. MuJoCo has no bodies for the massless U-joint crosses
(their hinges sit in the child body, see :mod:`pollard_pin.crosscheck.mujoco`), so both hinges
of a cross read the one wrench of the child body — the statement "the two joints of a
massless cross carry the same wrench" in MuJoCo's own terms.
"""
from __future__ import annotations

import numpy as np

from ..io.mjcf import require_mujoco
from .mujoco import JOINTS, cached_model, inverse_dynamics_mujoco


def joint_loads_mujoco(q, v, a, closure_forces=None, urdf_path=None, built=None) -> dict:
    """Loads of the 12 tree joints at samples (N, 12) in :data:`JOINTS` order.

    ``closure_forces`` (N, 2, 3): force of the platform on link_i [N], world axes; default:
    MuJoCo's own, from :func:`~pollard_pin.crosscheck.mujoco.inverse_dynamics_mujoco`.
    Returns a dict of ``force``, ``moment`` (about the joint anchor), ``axis``, each
    (N, 12, 3), world axes, and the ``closure_forces`` used.
    """
    mujoco = require_mujoco()

    model, data, info = built if built is not None else cached_model(urdf_path)
    q, v, a = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (q, v, a))
    n = len(q)
    if closure_forces is None:
        closure_forces = inverse_dynamics_mujoco(q, v, a, built=(model, data, info))[
            "closure_forces"]
    lam = np.asarray(closure_forces, dtype=float).reshape(n, 2, 3)
    # efc rows are s·(J_A − J_B) (checked when built): the row force is s·λ (force on link_i).
    efc = (lam * info["efc_sign"][None, :, None]).reshape(n, 6)
    rows = info["efc_rows"].reshape(-1)
    jid = np.array([model.joint(name).id for name in JOINTS])
    body = model.jnt_bodyid[jid]
    root = model.body_rootid[body]
    qadr, dadr = info["qpos_adr"], info["dof_adr"]
    force, moment, axis = (np.empty((n, 12, 3)) for _ in range(3))
    for k in range(n):
        data.qpos[qadr], data.qvel[dadr], data.qacc[dadr] = q[k], v[k], a[k]
        mujoco.mj_inverse(model, data)
        data.efc_force[rows] = efc[k]
        mujoco.mj_rnePostConstraint(model, data)
        w = data.cfrc_int[body]
        f = w[:, 3:]
        force[k] = f
        # moment about the anchor = moment about the subtree CoM + (com − anchor) × f
        moment[k] = w[:, :3] + np.cross(data.subtree_com[root] - data.xanchor[jid], f)
        axis[k] = data.xaxis[jid]
    return {"force": force, "moment": moment, "axis": axis, "closure_forces": lam,
            "joints": JOINTS}


__all__ = ["joint_loads_mujoco"]
