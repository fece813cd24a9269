"""What both inverse-kinematics solvers share (docs/model.md §7, §11): the result type, the
validation of task inputs and options, the closed-form start, ZYZ angles of the cut spherical
joints and the frame ids looked up once."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..analytic import closed_form
from ..analytic.taskspace import TaskInputError, check_task_array
from ..checks import float_array, real, shorten
from ..model.build import Robot
from .errors import (
    KinematicsError,
    KinematicsInputError,
    SingularityError,
    UnreachablePoseError,
)
from .margins import SERIAL_FLOOR, Margins, as_margins
from .singularity import floor_message

IK_TOL = 1e-12  # m / rad, closure residual and tool-pose error reached by Newton
BATCH_CHUNK = 4096  # samples per stacked block: bounds memory (≈ 10 kB per sample)
MAX_ITER = 30  # Newton iterations per sample (sample-by-sample solver)
METHODS = ("batch", "newton")


@dataclass(frozen=True)
class IkOptions:
    """How the constrained IK solves, checked once when made.

    Parameters
    ----------
    method : {"batch", "newton"} or None, optional
        "batch" (stacked over samples), "newton" (sample by sample) or None (newton with a
        ``q_start``, else batch).
    margins : Margins or None, optional
        How close to a singularity a sample may come (docs/model.md §12); None: the
        defaults.
    tol : float, optional
        Newton's tolerance [m or rad].
    max_iter : int, optional
        Newton's iterations per sample at most.
    chunk : int, optional
        Samples per stacked block (batch method).

    Raises
    ------
    pollard_pin.kinematics.errors.KinematicsInputError
        An unknown method, a tolerance that is not > 0, a count below 1.
    MarginError
        ``margins`` is not a :class:`~pollard_pin.Margins`.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> pp.IkOptions(method="newton", margins=pp.Margins(wrist=0.1)).margins.wrist
    0.1
    """

    method: str | None = None
    margins: Margins | None = None
    tol: float = IK_TOL
    max_iter: int = MAX_ITER
    chunk: int = BATCH_CHUNK

    def __post_init__(self):
        if self.method is not None and self.method not in METHODS:
            raise KinematicsInputError(f"method must be 'batch' or 'newton', got "
                                       f"{shorten(self.method)}")
        object.__setattr__(self, "margins", check_options(
            self.tol, self.margins, max_iter=self.max_iter, chunk=self.chunk))


def ik_options(options) -> IkOptions:
    """``options``, or the defaults for None; anything else is refused in one line."""
    if options is None:
        return IkOptions()
    if not isinstance(options, IkOptions):
        raise KinematicsInputError(f"options must be an IkOptions, got "
                                   f"{type(options).__name__}", chain="options")
    return options


def zyz(M: np.ndarray) -> np.ndarray:
    """ZYZ angles (..., 3) of M = Rz(a) Ry(b) Rz(c) (..., 3, 3), b in [0, π] (docs/model.md §4).
    b from atan2(sin b, cos b): accurate to round-off near 0 and π, where arccos is not."""
    b = np.arctan2(np.hypot(M[..., 0, 2], M[..., 1, 2]), M[..., 2, 2])
    return np.stack([np.arctan2(M[..., 1, 2], M[..., 0, 2]), b,
                     np.arctan2(M[..., 2, 1], -M[..., 2, 0])], axis=-1)


def zyz_rates(ang: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(ȧ, ḃ, ċ) from w, where Ṁ Mᵀ = ŵ and w = ȧ e_z + ḃ Rz(a) e_y + ċ Rz(a)Ry(b) e_z.

    Solved in closed form: Rz(−a) w = (ċ sin b, ḃ, ȧ + ċ cos b). At sin b = 0 (θ109 = 0 or π)
    the system is singular and the rates are not finite; :func:`check_margins` rejects such
    samples (|sin θ109| below SIGMA_FLOOR, docs/model.md §12)."""
    if ang.ndim == 1:  # one sample (per-sample Newton): scalar math
        a, b = float(ang[0]), float(ang[1])
        wx, wy, wz = w.tolist()
        ca, sa, sb = math.cos(a), math.sin(a), math.sin(b)
        cdot = (ca * wx + sa * wy) / sb if sb else math.copysign(math.inf, ca * wx + sa * wy)
        return np.array([wz - cdot * math.cos(b), ca * wy - sa * wx, cdot])
    a, b = ang[..., 0], ang[..., 1]
    ca, sa = np.cos(a), np.sin(a)
    wx = ca * w[..., 0] + sa * w[..., 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        cdot = wx / np.sin(b)
    return np.stack([w[..., 2] - cdot * np.cos(b), ca * w[..., 1] - sa * w[..., 0], cdot],
                    axis=-1)


@dataclass
class KinematicFrames:
    """Frame and joint ids used on the hot path, looked up once."""

    tip: int
    closure_a: tuple[int, ...]
    closure_b: tuple[int, ...]
    link_joints: tuple[int, ...]
    platform_joint: int
    spherical_offset: tuple[np.ndarray, ...]  # Rz(−β1413i)
    actuated_v: np.ndarray
    passive_v: np.ndarray
    wrist_q: int

    @classmethod
    def of(cls, robot: Robot) -> KinematicFrames:
        def rz(a):
            c, s = np.cos(a), np.sin(a)
            return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

        return cls(tip=robot.tip_frame,
                   closure_a=tuple(robot.frame_id(c.frame_a) for c in robot.closures),
                   closure_b=tuple(robot.frame_id(c.frame_b) for c in robot.closures),
                   link_joints=tuple(robot.joint_id(f"theta76_{i}") for i in (1, 2)),
                   platform_joint=robot.joint_id("theta54"),
                   spherical_offset=tuple(rz(-leg.beta1413) for leg in robot.params.legs),
                   actuated_v=robot.actuated_v, passive_v=robot.passive_v,
                   wrist_q=robot.idx_q("theta1716"))


@dataclass
class IKResult:
    """Joint motion along a trajectory, from :func:`~pollard_pin.inverse_kinematics`.

    Arrays have one row per sample; tree joints in :attr:`Robot.joint_names` order, the
    spherical joints' ZYZ angles leg 1 (θ98, θ109, θ1110) then leg 2.

    Attributes
    ----------
    t : ndarray
        Times (N,) [s].
    poses : ndarray
        Tool poses (N, 6): x, y, z [m], ψ, θ, φ [rad].
    q, v, a : ndarray
        Joint positions [rad], velocities [rad/s], accelerations [rad/s²], each (N, 12).
    spherical, d_spherical : ndarray
        The cut spherical joints' angles [rad] and rates [rad/s], each (N, 6).
    closure_residual : ndarray
        (N,) the largest component of ``p_A − p_B`` [m].
    tool_error : ndarray
        (N,) the largest tool pose error component [m or rad].
    wrist_margin : ndarray
        (N,) |sin θ1716|, the wrist's distance to its singularity.
    sigma_parallel, sigma_serial : ndarray
        (N,) the smallest singular values of the passive-joint constraint Jacobian and of
        the actuator-rate → tool-twist map (docs/model.md §12).
    joint_names : tuple of str
        The column names of ``q``, ``v`` and ``a``.
    constraint_jacobian : ndarray or None
        (N, 6, 12) at ``q``, reused by the dynamics.
    sigma_parallel_max, sigma_serial_max : ndarray or None
        The largest singular values of the same maps (the scale of the numerical floors).
    """

    t: np.ndarray
    poses: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    spherical: np.ndarray
    d_spherical: np.ndarray
    closure_residual: np.ndarray  # max |p_A − p_B| component [m]
    tool_error: np.ndarray  # max |pose error| component [m, rad]
    wrist_margin: np.ndarray  # |sin θ1716|
    sigma_parallel: np.ndarray  # σ_min of Jc over the passive joints
    sigma_serial: np.ndarray  # σ_min of the actuator-rate → tool-twist map
    joint_names: tuple[str, ...] = field(default=())
    constraint_jacobian: np.ndarray | None = None  # (N, 6, nv) at q, reused by dynamics
    sigma_parallel_max: np.ndarray | None = None  # σ_max of the same maps: the scale of the
    sigma_serial_max: np.ndarray | None = None  # numerical floors (docs/model.md §12)

    def __len__(self) -> int:
        return len(self.t)


MIN_TIME_STEP = 1e-9  # s: closer samples are duplicated or mis-scaled times (a 1 GHz rate)


def task_inputs(poses, d_poses, dd_poses, t):
    """Validated (N, 6) poses, rates, accelerations (zeros when None) and times (N,).

    Raises :class:`KinematicsInputError` naming the cause: an empty or mis-shaped array,
    times that are not finite or not increasing by at least MIN_TIME_STEP (sample k), or a
    non-finite or absurd entry (column x … phi, d_x … d_phi, dd_x … dd_phi; sample, value)."""
    poses = np.atleast_2d(float_array(poses, "poses", error=KinematicsInputError))
    n = len(poses)
    if poses.size == 0:
        raise KinematicsInputError(f"no samples: the pose array is empty (shape "
                                   f"{poses.shape}); give at least one pose (x, y, z, psi, "
                                   "theta, phi)")
    t = (np.arange(n, dtype=float) if t is None
         else float_array(t, "t", error=KinematicsInputError).reshape(-1))
    arrays = [poses]
    for label, arr in (("d_poses", d_poses), ("dd_poses", dd_poses)):
        arrays.append(np.zeros_like(poses) if arr is None else np.atleast_2d(
            float_array(arr, label, error=KinematicsInputError)))
    names = ("pose", "pose rate", "pose acceleration")
    for name, arr in zip(names, arrays):
        if arr.shape != (n, 6):
            raise KinematicsInputError(f"{name} array has shape {arr.shape}, expected ({n}, 6) "
                                       "(x, y, z, psi, theta, phi per sample)")
    if t.shape != (n,):
        raise KinematicsInputError(f"times have shape {t.shape}, expected ({n},)")
    bad = np.flatnonzero(~np.isfinite(t))
    if len(bad):
        k = int(bad[0])
        raise KinematicsInputError(f"time t = {t[k]} is not a finite number", sample=k,
                                   chain="t")
    if n > 1:
        dt = np.diff(t)
        bad = np.flatnonzero(~(dt >= MIN_TIME_STEP))
        if len(bad):
            k = int(bad[0]) + 1
            what = ("times are not increasing" if dt[k - 1] <= 0 else
                    f"time step too small (below {MIN_TIME_STEP:g} s)")
            raise KinematicsInputError(
                f"{what}: t = {t[k]:.17g} s follows t = {t[k - 1]:.17g} s at sample {k - 1} "
                f"(step {dt[k - 1]:.3g} s)", sample=k, time=float(t[k]), chain="t",
                amount=float(dt[k - 1]))
    try:
        for prefix, arr in zip(("", "d_", "dd_"), arrays):
            check_task_array(arr, prefix)
    except TaskInputError as exc:
        raise KinematicsInputError(exc.detail, sample=exc.sample, time=float(t[exc.sample]),
                                   chain=exc.column, amount=abs(exc.value)) from None
    return (*arrays, t)


def check_options(tol, margins, **counts) -> Margins:
    """The margins (a :class:`Margins`, validated when it was made; None: the defaults), after
    rejecting a tolerance that is not a positive number and counts below 1, before any work
    (:class:`KinematicsInputError`)."""
    real(tol, "tol", 0.0, above=True,
         error=lambda msg: KinematicsInputError(msg, chain="tol"))
    for name, value in counts.items():
        if not (isinstance(value, (int, np.integer)) and value >= 1):
            raise KinematicsInputError(f"{name} = {shorten(value)}: must be an integer >= 1",
                                       chain=name)
    return as_margins(margins)


def _wrist_error(k, tk, sin1716, margins: Margins) -> SingularityError:
    limit = float(margins.limits()["wrist"])
    return SingularityError(
        floor_message("wrist |sin θ1716| =", sin1716, margins.wrist, limit, SERIAL_FLOOR)
        + " (near the wrist singularity: spray axis parallel to the platform arm)",
        sample=k, time=tk, chain="wrist", sigma=sin1716, amount=limit - sin1716)


def closed_form_angles(robot: Robot, poses, t, margins: Margins | None) -> np.ndarray:
    """Closed-form tree angles (N, 12) on docs/model.md §9 branches, errors mapped to ours, in
    the closed form's order: chain 0 out of reach, then the wrist, judged by the margin rule
    (:meth:`Margins.violations`; not judged for None) on |sin θ1716| of these very angles as
    the workspace map judges it, then the legs; each at its first sample."""
    q18, failed = closed_form.position_ik_masked(robot.params, poses)
    if failed["chain 0"].any():
        raise _closed_form_error(robot, poses, t)
    if margins is not None:
        wrist = np.abs(np.sin(q18[:, closed_form.JOINTS.index("theta1716")]))
        bad = margins.violations(wrist=wrist)["wrist"]
        if bad.any():
            k = int(np.argmax(bad))
            raise _wrist_error(k, float(t[k]), float(wrist[k]), margins)
    if any(f.any() for f in failed.values()):
        raise _closed_form_error(robot, poses, t)
    return closed_form.make_continuous(q18[:, :12])


def _closed_form_error(robot: Robot, poses, t) -> KinematicsError:
    """The closed form's own error (it names the chain and the shortfall) as ours."""
    try:
        closed_form.position_ik(robot.params, poses)
    except closed_form.UnreachableError as exc:
        k, tk = exc.sample, float(t[exc.sample])
        if exc.kind == "singular" and exc.chain == "wrist":  # |sin θ1716| exactly 0
            return _wrist_error(k, tk, exc.ratio, Margins(0.0, 0.0))
        msg = str(exc).replace(f" at sample {exc.sample}", "")  # the prefix says where
        cls = SingularityError if exc.kind == "singular" else UnreachablePoseError
        return cls(msg, sample=k, time=tk, chain=exc.chain, amount=exc.shortfall)
    return UnreachablePoseError("the closed form has no solution")  # not reached: it raised
