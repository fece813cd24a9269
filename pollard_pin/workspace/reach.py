"""Is the tool pose reachable, and how well? Per-point rules of the workspace maps
(docs/model.md §22), stacked over points with no Python loop per point: the closed form on the
configured branches, the joint limits, the wrist and singularity margins with the numerical
floors of ``run`` (docs/model.md §12), the local conditioning index and the static payload
capacity."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytic import closed_form
from ..dynamics.drives.stiffness import MAX_TURN, stiffness_at
from ..dynamics.inverse import batched_rnea, split_tree_torques
from ..dynamics.motors import Actuators
from ..kinematics.ik_batch import kinematic_inverse, layout, point_rows
from ..kinematics.limits import limit_violations
from ..kinematics.margins import CHECKS, Margins
from ..kinematics.singularity import conditioning, sigma_range
from ..names import CHAINS, JOINTS, TREE_JOINTS

# Reason codes (the ``reason`` column): 0 reachable, then in the order they are checked; a
# point gets the first that applies (docs/model.md §22).
REASONS = (("reachable",)
           + tuple(f"{c} out of reach" for c in CHAINS)
           + tuple(f"{j} {side}" for j in TREE_JOINTS
                   for side in ("below its lower limit", "above its upper limit"))
           + ("wrist margin", "parallel margin", "serial margin",
              "spherical joint 1 at gimbal lock", "spherical joint 2 at gimbal lock"))
_REACH = 1  # first reach code
_LIMIT = _REACH + len(CHAINS)  # first joint-limit code
_MARGIN = _LIMIT + 2 * len(TREE_JOINTS)  # wrist, parallel, serial, spherical 1, 2
FLOORS_ONLY = Margins(0.0, 0.0)


@dataclass(frozen=True)
class ReachOptions:
    """The rules of docs/model.md §22: the margins, judged as ``run`` judges them (§12,
    :meth:`Margins.violations`), the conditioning index's length scale [m] (None: the
    platform arm from its U joint to the tip, x65 + x1514 + x1918) and, optionally, the
    actuators for the payload capacity."""

    margins: Margins = Margins()
    length_scale: float | None = None
    actuators: Actuators | None = None


def length_scale(params, options: ReachOptions) -> float:
    """The conditioning index's length [m] (docs/model.md §22)."""
    if options.length_scale is not None:
        return float(options.length_scale)
    return params.x65 + params.x1514 + params.x1918


def evaluate(robot, poses: np.ndarray, options: ReachOptions = ReachOptions()) -> dict:
    """Columns (each (N,)) of the workspace table at the tool poses (N, 6): reachable (0/1),
    reason (code into :data:`REASONS`), wrist_margin, sigma_parallel, sigma_serial,
    conditioning and, with actuators, payload_capacity [kg] (and, when they have stiffnesses,
    kmin, f1 and sag at the reachable points: :func:`stiffness_columns`). Margins are NaN
    where the closed form has no solution; the index and the capacity where, in addition, K is
    singular."""
    n = len(poses)
    params = robot.params
    q18, failed = closed_form.position_ik_masked(params, poses)
    q = q18[:, :12]
    reason = np.zeros(n, dtype=np.int64)
    nan = np.full(n, np.nan)
    out = {"wrist_margin": nan.copy(), "sigma_parallel": nan.copy(),
           "sigma_serial": nan.copy(), "conditioning": nan.copy()}

    def assign(mask, code):  # first reason wins
        reason[(reason == 0) & mask] = code

    for i, chain in enumerate(CHAINS):
        assign(failed[chain], _REACH + i)
    solved = np.flatnonzero(np.isfinite(q).all(axis=1))
    qs = q[solved]
    side, _ = limit_violations(params, qs, TREE_JOINTS)
    sub = np.zeros(len(solved), dtype=np.int64)
    for j in range(len(TREE_JOINTS)):  # joint order, lower before upper
        for s, code in ((-1, _LIMIT + 2 * j), (1, _LIMIT + 2 * j + 1)):
            sub[(sub == 0) & (side[:, j] == s)] = code
    wrist = np.abs(np.sin(qs[:, TREE_JOINTS.index("theta1716")]))
    K, K_inv = kinematic_matrices(robot, qs)
    sp, ss, sp_max, ss_max = conditioning(K, robot.actuated_v, robot.passive_v, full=True,
                                          K_inv=K_inv)
    sph = [np.abs(np.sin(q18[solved, JOINTS.index(f"theta109_{i}")]))
           for i in (1, 2)]
    # run's rule, margins raised to their numerical floors (docs/model.md §12).
    bad = options.margins.violations(wrist=wrist, parallel=sp, serial=ss, parallel_max=sp_max,
                                     serial_max=ss_max, spherical=sph)
    for k, check in enumerate(CHECKS):
        sub[(sub == 0) & bad[check]] = _MARGIN + k
    reason[solved] = sub
    out["wrist_margin"][solved], out["sigma_parallel"][solved] = wrist, sp
    out["sigma_serial"][solved] = ss
    out["conditioning"][solved] = local_conditioning(robot, K_inv, length_scale(params,
                                                                                options))
    out = {"reachable": (reason == 0).astype(float), "reason": reason, **out}
    if options.actuators is not None:
        cap = nan.copy()
        # Jc_p invertible (the parallel floor alone): torques exist
        ok = ~FLOORS_ONLY.violations(parallel=sp, parallel_max=sp_max)["parallel"]
        cap[solved[ok]] = payload_capacity(robot, options.actuators, qs[ok], K[ok])
        out["payload_capacity"] = cap
        if has_stiffness(options.actuators):
            out.update(stiffness_columns(robot, options.actuators.stiffness(), q,
                                         reason == 0))
    return out


STIFFNESS_COLUMNS = ("kmin", "f1", "sag")


def has_stiffness(act: Actuators) -> bool:
    """Whether every drive has a stiffness (the stiffness columns are then mapped); some but
    not all is an :class:`~pollard_pin.dynamics.motors.ActuatorError` naming the first
    without."""
    given = [u.stiffness is not None for u in act.units]
    if any(given) and not all(given):
        act.stiffness()  # raises, naming it
    return all(given)


def stiffness_columns(robot, k, q: np.ndarray, ok: np.ndarray) -> dict:
    """kmin [N/m], f1 [Hz] and sag [m] (the tip's displacement under the weight, |d|) at the
    points ``ok`` of the closed-form configurations q (N, 12), NaN elsewhere; the sag is NaN
    too where a drive turns beyond the linear model's bound, ``MAX_TURN`` (docs/model.md
    §27.2, §27.6): a map flags it rather than refusing."""
    cols = {c: np.full(len(q), np.nan) for c in STIFFNESS_COLUMNS}
    if ok.any():
        r = stiffness_at(robot, q[ok], k)
        cols["kmin"][ok], cols["f1"][ok] = r.kmin, r.frequencies[:, 0]
        linear = r.turn <= MAX_TURN
        sag = np.full(len(r), np.nan)
        sag[linear] = np.linalg.norm(r.deflection[linear, :3], axis=1)
        cols["sag"][ok] = sag
    return cols


def kinematic_matrices(robot, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """K = [Jc; J_tool] (N, 12, nv) and K⁻¹ (NaN where singular) at configurations q (N, nq),
    as the batched IK forms them (docs/model.md §11)."""
    lay = layout(robot)
    R, o = lay.tree.placements(q)
    K = point_rows(lay, R, o, robot.model.nv)[0]
    return K, kinematic_inverse(K, lay)


def local_conditioning(robot, K_inv: np.ndarray, length: float) -> np.ndarray:
    """Inverse condition number σ_min/σ_max of the actuator-rate → tool-twist map with the
    twist's linear part divided by ``length`` (docs/model.md §22), from K⁻¹ (N, 12, 12):
    that map's inverse is K⁻¹[actuated, 6:] (docs/model.md §12), whose singular values are the
    reciprocals, so the ratio is the same. 0 where K is singular."""
    scale = np.array([length, length, length, 1.0, 1.0, 1.0])
    lo, hi = sigma_range(K_inv[:, robot.actuated_v, 6:] * scale)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(np.isfinite(lo), lo / hi, 0.0)


def holding_torques(robot, q: np.ndarray, K: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Static actuator torques (N, 6) [N·m], docs/model.md §6 order: the robot's own weight,
    and per kilogram of a point mass at the tool tip. Both are tree torques split by the
    closure (docs/model.md §13): gravity from RNEA at rest; the payload's ∂U/∂q =
    −J_tipᵀ·g (J_tip = K's tip-point rows)."""
    model = robot.model
    zero = np.zeros_like(q)
    tree_g = batched_rnea(model, q, zero, zero)
    g = np.asarray(model.gravity.linear)
    tree_u = -np.einsum("nrj,r->nj", K[:, 6:9, :], g)
    Jc = K[:, :6, :]
    both = split_tree_torques(robot, np.concatenate([Jc, Jc]),
                              np.concatenate([tree_g, tree_u]))[0]
    return both[:len(q)], both[len(q):]


def payload_capacity(robot, act: Actuators, q: np.ndarray, K: np.ndarray) -> np.ndarray:
    """Largest point mass [kg] at the tool tip held at rest before a motor reaches its peak
    torque (docs/model.md §22): the motor model of docs/model.md §19 at rest, τm = τ/N with
    Coulomb friction as breakaway ±c, so |τm| = |(τ_g + m·τ_u)/N| + c ≤ peak for every
    motor. 0 where the robot's own weight already breaks that; inf if no motor carries the
    payload."""
    tau_g, tau_u = holding_torques(robot, q, K)
    n = act.column("gear_ratio")
    m_g, m_u = tau_g / n, tau_u / n
    room = act.column("peak_torque") - act.column("coulomb")
    with np.errstate(divide="ignore", invalid="ignore"):
        # |m_g + m·m_u| ≤ room: m ≤ (room − m_g)/m_u for m_u > 0, (room + m_g)/(−m_u) below.
        per = np.where(m_u > 0, (room - m_g) / m_u,
                       np.where(m_u < 0, (room + m_g) / -m_u, np.inf))
    cap = per.min(axis=1)
    return np.where((np.abs(m_g) <= room).all(axis=1), np.maximum(cap, 0.0), 0.0)
