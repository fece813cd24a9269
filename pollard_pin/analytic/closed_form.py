"""Closed-form inverse kinematics of the thesis (docs/model.md §7), its exact time derivatives, and
the
numpy forward chain of docs/model.md §3 used to check it.

Poses are (x, y, z, ψ, θ, φ) in the thesis order (docs/model.md §2): tip frame Tx(x)Ty(y)Tz(z)·R
with
R = Rx(θ)Ry(ψ)Rz(φ). Velocities and accelerations come from running the same closed forms on
:class:`~pollard_pin.analytic.jet.Jet` inputs, i.e. by the chain rule, never finite differences.
"""
from __future__ import annotations

import numpy as np

from ..checks import real
from ..errors import SolveError
from ..names import ACTUATED, BODIES, CHAINS, JOINTS, SPHERICAL, TREE_JOINTS  # noqa: F401
from . import jet as J
from .jet import Jet, value
from .taskspace import TaskInputError, check_task_array

ACTUATED_INDEX = tuple(JOINTS.index(n) for n in ACTUATED)
_CHAIN_OF = {**{n: "chain 0" for n in JOINTS[:3]}, **{n: "wrist" for n in JOINTS[3:6]},
             **{n: f"leg {n[-1]}" for n in JOINTS[6:12]},
             **{n: f"spherical joint {n[-1]}" for n in SPHERICAL}}
# Round-off tolerance of every arccos/arcsin argument (docs/model.md §7): a ratio within
# ROUNDOFF·scale of ±1 is on the boundary and taken as ±1 exactly; beyond 1 + ROUNDOFF·scale
# there is no solution. ``scale`` is the size of the terms the ratio was formed from, relative
# to its denominator (1 for entries of unit vectors and rotation matrices): each of the ~10
# roundings on the way costs ≤ ε of that size, so 16 ε bounds the error with room to spare,
# yet is 1e-14 of a reach of ~1 m — far below anything physical.
ROUNDOFF = 16 * np.finfo(float).eps
_TARGETS = {"chain 0": "the wrist centre", "leg 1": "its attachment point",
            "leg 2": "its attachment point"}


class UnreachableError(SolveError, ValueError):
    """The closed form of docs/model.md §7 has no solution (``kind == "unreachable"``) or the wrist
    is singular (``kind == "singular"``, subclass :class:`WristSingularError`).

    A :class:`~pollard_pin.errors.SolveError`, as the kinematics'
    :class:`~pollard_pin.kinematics.errors.UnreachablePoseError` is: the pose is a valid request
    the robot cannot meet (the rule in :mod:`pollard_pin.errors`). Also a :class:`ValueError`,
    as it was when it counted as bad input, so code catching that still catches it.

    Attributes: ``chain`` ("chain 0", "leg 1", "leg 2" or "wrist"), ``sample`` (first bad sample
    index), ``count`` (number of bad samples), ``ratio`` and ``shortfall``:

    - unreachable: ``ratio`` = |−C/R| of the equation C + A cos + B sin = 0 (> 1 when there is no
      solution); ``shortfall`` [m] = distance by which the target lies outside the reachable
      shell of the arm + link pair (``too_close`` tells whether it is inside the inner radius);
    - singular: ``ratio`` = |sin θ1716|; ``shortfall`` = wrist_margin − |sin θ1716| (≥ 0).
    """

    kind = "unreachable"

    def __init__(self, chain: str, sample: int, shortfall: float, ratio: float,
                 count: int = 1, too_close: bool = False, message: str | None = None):
        self.chain, self.sample, self.shortfall, self.ratio = chain, sample, shortfall, ratio
        self.count, self.too_close = count, too_close
        if message is None:
            how = "target too close by" if too_close else "short by"
            # Just past the boundary, 6 digits would print "1": show the excess instead.
            shown = f"1 + {ratio - 1.0:.3g}" if 0.0 < ratio - 1.0 < 1e-5 else f"{ratio:.6g}"
            message = (f"{chain} cannot reach {_TARGETS.get(chain, 'its target')} at sample "
                       f"{sample}: |−C/R| = {shown} ({how} {shortfall * 1e3:.4g} mm)")
            if count > 1:
                message += f"; {count} samples fail in all"
        super().__init__(message)


class WristSingularError(UnreachableError):
    """θ1716 at 0 or π, or |sin θ1716| below ``wrist_margin`` (docs/model.md §12): the XZX
    wrist loses a DOF (docs/model.md §3)."""

    kind = "singular"

    def __init__(self, sample: int, sin1716: float, margin: float, count: int = 1):
        below = "is 0" if sin1716 == 0.0 else f"< wrist_margin = {margin:.6g}"
        msg = (f"wrist is singular at sample {sample}: |sin θ1716| = {sin1716:.6g} {below} "
               "(spray axis parallel to the platform arm)")
        if count > 1:
            msg += f"; {count} samples fail in all"
        super().__init__("wrist", sample, margin - sin1716, sin1716, count=count, message=msg)


class SingularPoseError(UnreachableError):
    """A pose exactly on a singularity (an arccos/arcsin argument at ±1, docs/model.md §7, §12):
    the angles exist but their rates do not. ``kind == "singular"``; ``chain`` as for
    :class:`UnreachableError`, ``joint`` the first angle whose derivative is not finite."""

    kind = "singular"

    def __init__(self, chain: str, sample: int, joint: str, count: int = 1):
        self.joint = joint
        msg = (f"{chain} is exactly at a singularity at sample {sample}: the rate of {joint} "
               "is not finite (on a reach boundary, or a joint at its gimbal angle)")
        if count > 1:
            msg += f"; {count} samples fail in all"
        super().__init__(chain, sample, 0.0, 1.0, count=count, message=msg)


def _per_sample(mask: np.ndarray) -> np.ndarray:
    return mask.reshape(mask.shape[0], -1).any(axis=1)


def _unit(c, scale=1.0):
    """(c clipped into [−1, 1], values within ROUNDOFF·scale of ±1 set to ±1 exactly; mask of
    |c| beyond 1 + ROUNDOFF·scale or NaN). Jets keep their derivatives. Entries of unit
    vectors and rotation matrices (scale 1) leave [−1, 1] only by round-off (|u| = |w| = 1
    once the circle equations are solved), so those call sites need no mask."""
    cv = value(c)
    tol = ROUNDOFF * scale
    with np.errstate(invalid="ignore"):
        a = np.abs(cv)
        near = np.abs(a - 1.0) <= tol
        beyond = ~(a <= 1.0 + tol)
        cv = np.clip(np.where(near, np.sign(cv), cv), -1.0, 1.0)
    return (Jet._make(cv, c.d, c.dd) if isinstance(c, Jet) else cv), beyond


def _circle_angle(A, B, C, branch, chain, rho, off, r, L, failures=None):
    """Solve C + A cos t + B sin t = 0: t = atan2(B, A) + branch·acos(−C/√(A²+B²)) (docs/model.md
    §7).

    rho, off: in-plane / out-of-plane distance of the target from the circle the elbow
    describes (radius r); L is the second link. Used for the tolerance and the shortfall.
    With a ``failures`` dict, no error: the samples without a solution get NaN and
    ``failures[chain]`` their mask.
    """
    Rn = J.sqrt(A * A + B * B)
    Rv, rh, of = value(Rn), value(rho), value(off)
    # C = ρ² + off² + r² − L² rounds at the size of its terms (tolerance scale, see ROUNDOFF).
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.where(Rv > 0.0, (rh * rh + of * of + r * r + L * L) / Rv, 0.0)
        c = -C / Rn
    ratio = value(c)
    c, bad = _unit(c, scale)
    if failures is not None:
        failures[chain] = bad
        return J.atan2(B, A) + branch * J.acos(np.where(bad, np.nan, c))
    if bad.any():
        rows = _per_sample(bad)
        idx = np.unravel_index(np.argmax(bad), bad.shape)  # C order: first bad sample
        k = int(idx[0])
        cv, Rk, rk, ok_ = float(ratio[idx]), float(Rv[idx]), float(rh[idx]), float(of[idx])
        too_close = bool(cv > 1.0)
        if Rk > 0.0:
            # Distance from the target to the nearest (farthest) point of the reachable shell,
            # from the same ratio that failed: d² − L² = R (|c| − 1), so it is > 0 here.
            d = np.hypot(rk + r, ok_) if too_close else np.hypot(rk - r, ok_)
            short = Rk * (abs(cv) - 1.0) / (d + L)
            raise UnreachableError(chain, k, float(short), abs(cv), int(rows.sum()), too_close)
        d = float(np.hypot(r, ok_))  # target on the axis of the base joint: R = 0
        if d != L:
            raise UnreachableError(chain, k, abs(d - L), abs(cv), int(rows.sum()), d < L)
        raise UnreachableError(chain, k, 0.0, abs(cv), int(rows.sum()), message=(
            f"{chain} cannot place {_TARGETS.get(chain, 'its target')} at sample {k}: the "
            "target lies on the axis of its base joint at exactly the link length, so the "
            "base angle is undetermined (singular)"))
    return J.atan2(B, A) + branch * J.acos(c)


def _solve(p, pose, wrist_margin=0.0, spherical=True, frames=None, failures=None):
    """Closed-form angles (docs/model.md §7) as a name → angle dict; pose is an (..., 6) array or
    jet.
    The six spherical-joint angles are skipped unless ``spherical``. If ``frames`` is a dict,
    it receives the world (R, origin) of the 9 moving bodies (as :func:`forward_frames`, but
    reusing the rotations already built here). If ``failures`` is a dict, nothing raises: it
    receives each chain's mask of samples without a solution (whose angles are NaN), and the
    wrist margin is not checked.

    Rotation products use J.rot / J.rot_left (two-column mixes) for speed.
    """
    x, y, z, psi, th, phi = (pose[..., k] for k in range(6))
    R = J.rot(J.rot(J.Rx(th), 1, psi), 2, phi)
    L = p.x65 + p.x1514
    P15 = J.stack([x, y, z]) - p.x1918 * R[..., :, 0]

    # Chain 0, (2.8)-(2.23): the wrist centre lies at L from the elbow circle (radius x32, xz).
    dx, dy, dz = P15[..., 0], P15[..., 1], P15[..., 2] - p.z10
    A, B = -2.0 * p.x32 * dx, 2.0 * p.x32 * dz
    C = dx * dx + dy * dy + dz * dz + (p.x32 ** 2 - L ** 2)
    q = {"theta21": _circle_angle(A, B, C, p.branches[0], "chain 0",
                                  J.sqrt(dx * dx + dz * dz), dy, p.x32, L, failures)}
    E = J.stack([p.x32 * J.cos(q["theta21"]), 0.0, p.z10 - p.x32 * J.sin(q["theta21"])])
    u = (P15 - E) / L
    a = J.atan2(-u[..., 2], u[..., 0])  # θ21 + θ43
    q["theta43"] = a - q["theta21"]
    q["theta54"] = J.asin(_unit(u[..., 1])[0])
    Rp = J.rot(J.Ry(a), 2, q["theta54"])

    # Wrist (2.34)-(2.47): XZX Euler angles of Rpᵀ R = Rz(−θ54) Ry(−a) R.
    M = J.rot_left(2, -q["theta54"], J.rot_left(1, -a, R))
    c1716 = _unit(M[..., 0, 0])[0]
    s1716 = np.sqrt(1.0 - value(c1716) ** 2)
    # The margin rule of docs/model.md §12 (equal passes), and an exactly singular wrist never.
    bad = (s1716 < wrist_margin) | (s1716 == 0.0)
    if failures is None and bad.any():
        rows = _per_sample(bad)
        k = int(np.argmax(rows))
        raise WristSingularError(k, float(s1716[k].min()), float(wrist_margin), int(rows.sum()))
    q["theta1615"] = J.atan2(M[..., 2, 0], M[..., 1, 0])
    q["theta1716"] = J.acos(c1716)
    q["theta1817"] = J.atan2(M[..., 0, 2], -M[..., 0, 1])
    if frames is not None:
        frames["arm0"] = (J.Ry(q["theta21"]), np.array([0.0, 0.0, p.z10]))
        frames["platform"] = (Rp, E)
        frames["wrist1"] = (J.rot(Rp, 0, q["theta1615"]), P15)
        frames["wrist2"] = (J.rot(frames["wrist1"][0], 2, q["theta1716"]), P15)
        frames["gun"] = (R, P15)

    # Legs (2.89)-(2.105): the attachment point lies at x87 from the elbow circle (radius x43, xy).
    for i, leg in enumerate(p.legs):
        s = f"_{i + 1}"
        Aw = E + J.matvec(Rp, p.attachment(i))
        c = np.array([0.0, leg.side * leg.y10, -leg.z32])
        px, py, pz = Aw[..., 0] - c[0], Aw[..., 1] - c[1], Aw[..., 2] - c[2]
        A, B = -2.0 * leg.x43 * px, -2.0 * leg.x43 * py
        C = px * px + py * py + pz * pz + (leg.x43 ** 2 - leg.x87 ** 2)
        t21 = _circle_angle(A, B, C, p.branches[i + 1], CHAINS[i + 1],
                            J.sqrt(px * px + py * py), pz, leg.x43, leg.x87, failures)
        elbow = J.stack([leg.x43 * J.cos(t21), c[1] + leg.x43 * J.sin(t21), c[2]])
        Ra = J.Rz(t21)
        Rc = J.rot(Ra, 0, np.asarray(leg.beta54))
        w = J.matvec(J.transpose(Rc), Aw - elbow) / leg.x87
        q["theta21" + s] = t21
        q["theta65" + s] = J.atan2(-w[..., 2], w[..., 0])
        q["theta76" + s] = J.asin(_unit(w[..., 1])[0])
        if frames is not None:
            frames["arm" + s] = (Ra, np.array([0.0, c[1], 0.0]))
            frames["link" + s] = (J.rot(J.rot(Rc, 1, q["theta65" + s]), 2, q["theta76" + s]),
                                  elbow)
        if not spherical:
            continue
        # Spherical joint, docs/model.md §4: ZYZ of R_linkᵀ Rp Rz(−β1413), θ109 in [0, π], with
        # R_linkᵀ = Rz(−θ76) Ry(−θ65) Rx(−β54) Rz(−θ21i).
        Ms = Rp
        for axis, ang in ((2, -t21), (0, np.asarray(-leg.beta54)), (1, -q["theta65" + s]),
                          (2, -q["theta76" + s])):
            Ms = J.rot_left(axis, ang, Ms)
        Ms = J.rot(Ms, 2, np.asarray(-leg.beta1413))
        q["theta98" + s] = J.atan2(Ms[..., 1, 2], Ms[..., 0, 2])
        q["theta109" + s] = J.acos(_unit(Ms[..., 2, 2])[0])
        q["theta1110" + s] = J.atan2(Ms[..., 2, 1], -Ms[..., 2, 0])
    return q


def as_poses(poses, prefix: str = "") -> np.ndarray:
    """(N, 6) float array, checked: N ≥ 1, every entry finite and within MAX_ABS_TASK (the
    error names the column, e.g. ``d_psi``, and the sample)."""
    what = {"": "poses", "d_": "pose rates", "dd_": "pose accelerations"}[prefix]
    a = np.asarray(poses, dtype=float)
    a = a[None, :] if a.ndim == 1 else a
    if a.ndim != 2 or a.shape[1] != 6:
        raise TaskInputError(f"{what} must have shape (N, 6) or (6,) (x, y, z, psi, "
                             f"theta, phi), got {np.shape(poses)}")
    if len(a) == 0:
        raise TaskInputError(f"no {what}: the array is empty (shape {a.shape}); give at "
                             "least one sample (x, y, z, psi, theta, phi)")
    check_task_array(a, prefix)
    return a


def _check_wrist_margin(wrist_margin) -> float:
    return real(wrist_margin, "wrist_margin", 0.0, 1.0,
                why=" (the smallest |sin θ1716| allowed, in [0, 1])",
                error=lambda msg: TaskInputError(msg, column="wrist_margin"))


def _check_rates(q: Jet, names) -> None:
    """Derivatives are infinite exactly on a singularity (an arccos/arcsin at ±1): say where
    instead of returning them."""
    for part in (q.d, q.dd):
        if part is None:
            continue
        bad = ~np.isfinite(part)
        if bad.any():
            rows = _per_sample(bad)
            k = int(np.argmax(rows))
            j = int(np.argmax(bad[k].reshape(-1, len(names)).any(axis=0)))
            raise SingularPoseError(_CHAIN_OF.get(names[j], names[j]), k, names[j],
                                    int(rows.sum()))


def _wrap(a):
    """Into (−π, π]."""
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi)


def make_continuous(q: np.ndarray, reference=None) -> np.ndarray:
    """Shift sample 0 by 2πk into (−π, π] (or nearest ``reference``), then unwrap along axis 0."""
    q = np.asarray(q, dtype=float)
    ref = np.zeros(q.shape[1]) if reference is None else np.asarray(reference, dtype=float)
    # Whole turns: an angle already in place is left bit for bit, so every caller of the
    # closed form sees the same |sin θ1716| (the margin rule, docs/model.md §12).
    turns = np.round((ref + _wrap(q[0] - ref) - q[0]) / (2.0 * np.pi))
    return np.unwrap(q + 2.0 * np.pi * turns, axis=0)


def position_ik(params, poses, reference=None, wrist_margin: float = 0.0) -> np.ndarray:
    """(N, 18) joint angles in :data:`JOINTS` order for (N, 6) poses (docs/model.md §7).

    Raises :class:`UnreachableError` (chain, sample, shortfall) or :class:`WristSingularError`.
    The spherical-joint angles (last six) are a ZYZ decomposition: at θ109 = 0 or π only
    θ98 ± θ1110 is defined, and their derivatives from :func:`inverse_kinematics` are then
    not finite.

    Parameters
    ----------
    params : Params
        The robot's parameters (:func:`pollard_pin.load_params`).
    poses : ArrayLike
        Tool poses (x, y, z [m], ψ, θ, φ [rad]; docs/model.md §2), (N, 6) or one (6,).
    reference : ArrayLike, optional
        (18,) angles the first sample is brought nearest to by whole turns (default: into
        (−π, π]); the samples after it are unwrapped along the trajectory.
    wrist_margin : float, optional
        The smallest |sin θ1716| allowed, in [0, 1] (0: only an exactly singular wrist fails).
    """
    q = _solve(params, as_poses(poses), _check_wrist_margin(wrist_margin))
    return make_continuous(np.stack([q[n] for n in JOINTS], axis=-1), reference)


def position_ik_masked(params, poses) -> tuple[np.ndarray, dict]:
    """Closed-form angles (N, 18) in :data:`JOINTS` order, as :func:`position_ik` but without
    raising: NaN where a chain has no solution, and {chain: (N,) mask of those samples}
    (a leg's mask includes the samples where chain 0 already failed). The angles are those of
    the closed form (not unwrapped along the samples); the wrist margin is not checked."""
    failures = {}
    with np.errstate(invalid="ignore"):
        q = _solve(params, as_poses(poses), 0.0, failures=failures)
    return np.stack([q[n] for n in JOINTS], axis=-1), failures


def inverse_kinematics(params, poses, d_poses, dd_poses, reference=None,
                       wrist_margin: float = 0.0):
    """(q, qd, qdd), each (N, 18): the closed forms and their exact time derivatives.

    Raises :class:`SingularPoseError` where a derivative is not finite (a pose exactly on a
    reach boundary or a wrist/joint singularity)."""
    x = [as_poses(a, pre) for a, pre in ((poses, ""), (d_poses, "d_"), (dd_poses, "dd_"))]
    if not x[0].shape == x[1].shape == x[2].shape:
        raise TaskInputError(f"poses, rates and accelerations differ in shape: "
                             f"{[a.shape for a in x]}")
    with np.errstate(divide="ignore", invalid="ignore"):  # checked just below
        sol = _solve(params, Jet(*x), _check_wrist_margin(wrist_margin))
        q = J.stack([sol[n] for n in JOINTS], axis=-1)
    _check_rates(q, JOINTS)
    return make_continuous(q.v, reference), q.d, q.dd


def direction_jet(poses) -> Jet:
    """First-order pose jet: value (N, 1, 6), derivatives (N, 6, 6) along the unit vectors e_j,
    so any quantity's ``.d[:, j]`` is its partial derivative ∂/∂q_j."""
    x = as_poses(poses)
    return Jet(x[:, None, :], np.broadcast_to(np.eye(6), (x.shape[0], 6, 6)), order=1)


def actuation_jacobian(params, poses, wrist_margin: float = 0.0) -> np.ndarray:
    """J_τ = ∂(actuator angles, :data:`ACTUATED` order)/∂(x, y, z, ψ, θ, φ), shape (N, 6, 6)."""
    with np.errstate(divide="ignore", invalid="ignore"):  # checked just below
        q = _solve(params, direction_jet(poses), _check_wrist_margin(wrist_margin),
                   spherical=False)
        Jt = J.stack([q[n] for n in ACTUATED], axis=-1)
    _check_rates(Jt, ACTUATED)
    return np.swapaxes(Jt.d, -1, -2)


# --- forward chain of docs/model.md §3 (numpy or jets)
# ---------------------------------------------

def _angles(q):
    """Accept a name→angle mapping or an (..., 18)/(..., 12) array in JOINTS order."""
    if isinstance(q, dict):
        return q
    q = np.asarray(q, dtype=float)
    return {n: q[..., k] for k, n in enumerate(JOINTS[: q.shape[-1]])}


def forward_frames(params, q) -> dict:
    """World (R, origin) of every frame of docs/model.md §3 from the 12 tree angles.

    Keys: arm0, cross0, platform, wrist1, wrist2, gun, tip, arm_i, cross_i, link_i (i = 1, 2),
    closure_link_i / closure_platform_i (origins only meaningful; R of the carrying body).
    """
    q = _angles(q)
    ex = np.array([1.0, 0.0, 0.0])
    f = {}
    f["arm0"] = (J.Ry(q["theta21"]), np.array([0.0, 0.0, params.z10]))
    R = J.rot(f["arm0"][0], 1, q["theta43"])
    f["cross0"] = (R, f["arm0"][1] + J.matvec(f["arm0"][0], params.x32 * ex))
    f["platform"] = (J.rot(R, 2, q["theta54"]), f["cross0"][1])
    Rp, op = f["platform"]
    o15 = op + J.matvec(Rp, (params.x65 + params.x1514) * ex)
    f["wrist1"] = (J.rot(Rp, 0, q["theta1615"]), o15)
    f["wrist2"] = (J.rot(f["wrist1"][0], 2, q["theta1716"]), o15)
    f["gun"] = (J.rot(f["wrist2"][0], 0, q["theta1817"]), o15)
    f["tip"] = (f["gun"][0], o15 + J.matvec(f["gun"][0], params.x1918 * ex))
    for i, leg in enumerate(params.legs):
        s = f"_{i + 1}"
        Ra = J.Rz(q["theta21" + s])
        oa = np.array([0.0, leg.side * leg.y10, 0.0])
        Rc = J.rot(Ra, 0, np.asarray(leg.beta54))
        oc = oa + J.matvec(Ra, np.array([leg.x43, 0.0, -leg.z32]))
        Rl = J.rot(J.rot(Rc, 1, q["theta65" + s]), 2, q["theta76" + s])
        f["arm" + s], f["cross" + s], f["link" + s] = (Ra, oa), (Rc, oc), (Rl, oc)
        f["closure_link" + s] = (Rl, oc + J.matvec(Rl, leg.x87 * ex))
        f["closure_platform" + s] = (Rp, op + J.matvec(Rp, params.attachment(i)))
    return f


def rotation_to_pose_angles(R):
    """(ψ, θ, φ) of R = Rx(θ)Ry(ψ)Rz(φ), ψ in [−π/2, π/2]."""
    psi = np.arctan2(R[..., 0, 2], np.hypot(R[..., 1, 2], R[..., 2, 2]))
    theta = np.arctan2(-R[..., 1, 2], R[..., 2, 2])
    phi = np.arctan2(-R[..., 0, 1], R[..., 0, 0])
    return psi, theta, phi


def forward_tool_pose(params, q) -> np.ndarray:
    """Tip pose (…, 6) = (x, y, z, ψ, θ, φ) from the chain-0 angles of q (numpy only)."""
    R, o = forward_frames(params, q)["tip"]
    o = np.broadcast_to(o, R.shape[:-1])
    return np.concatenate([o, np.stack(rotation_to_pose_angles(R), axis=-1)], axis=-1)


def closure_points(params, q) -> np.ndarray:
    """(…, 2, 2, 3): [leg, 0] = Tx(x87) on link_i, [leg, 1] = A_i on the platform (docs/model.md
    §4)."""
    f = forward_frames(params, q)
    return np.stack([np.stack([f[f"closure_link_{i}"][1], f[f"closure_platform_{i}"][1]], -2)
                     for i in (1, 2)], -3)


# --- body kinematics ----------------------------------------------------------------------


def body_states(params, pose_jet, wrist_margin: float = 0.0):
    """({name: (R jet, CoG position jet)} for the 9 moving bodies (world frame, docs/model.md §3,
    §5),
    {angle name: jet}) from the closed-form IK run on ``pose_jet``."""
    f = {}
    q = _solve(params, pose_jet, wrist_margin, spherical=False, frames=f)
    bodies = {}
    for name in BODIES:
        R, o = f[name]
        bodies[name] = (R, o + J.matvec(R, np.asarray(params.body(name).com)))
    return bodies, q


def vee_skew(W):
    """Axial vector of the skew part of W (..., 3, 3)."""
    return 0.5 * np.stack([W[..., 2, 1] - W[..., 1, 2], W[..., 0, 2] - W[..., 2, 0],
                           W[..., 1, 0] - W[..., 0, 1]], axis=-1)


def angular_rates(R: Jet):
    """World ω = vee(Ṙ Rᵀ) and α = vee(skew(R̈ Rᵀ)) (Ṙ Ṙᵀ is symmetric, so it drops out)."""
    Rt = np.swapaxes(R.v, -1, -2)
    return vee_skew(R.d @ Rt), vee_skew(R.dd @ Rt)


def body_kinematics(params, poses, d_poses, dd_poses, wrist_margin: float = 0.0) -> dict:
    """name → dict(R, r, v, a, omega, alpha): world rotation, CoG position, CoG velocity and
    acceleration, angular velocity and acceleration (world frame), each (N, ...)."""
    x = Jet(as_poses(poses), as_poses(d_poses, "d_"), as_poses(dd_poses, "dd_"))
    out = {}
    for name, (R, r) in body_states(params, x, wrist_margin)[0].items():
        w, al = angular_rates(R)
        out[name] = {"R": R.v, "r": r.v, "v": r.d, "a": r.dd, "omega": w, "alpha": al}
    return out
