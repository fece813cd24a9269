"""Stiffness and vibration with compliant drives and rigid links (docs/model.md §27).

Each actuated joint's drive is a torsional spring kᵢ [N·m/rad] (joint side) between the motor,
held by its position loop, and the joint. At closed-loop configurations q (N, 12), stacked over
samples with no Python loop over them:

* J (6 × 6) = ∂(tip velocity, gun angular velocity; world axes)/∂(actuated angles), both loops
  closed, from the batched IK's [Jc; J_tool] (J⁻¹ is a block of its inverse);
* the compliance C = J K⁻¹ Jᵀ, the softest tip stiffness under a pure force
  kmin = 1/λmax(C[:3, :3]);
* the deflection d = J K⁻¹ (Jᵀ W − τ_g) under a wrench W (force at the tip, moment about the
  tip, world axes) plus the weight, τ_g the actuator torques that hold the robot still;
* the natural frequencies from K u = ω² Mₐ u, Mₐ = Sᵀ M S the links' mass matrix reduced to the
  actuated angles (S = ∂q/∂θ on the loops). The rotors sit on the motor side of the springs
  and do not count.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from ...checks import float_array, shorten
from ...errors import InputError
from ...kinematics.errors import SingularityError
from ...kinematics.ik_batch import kinematic_inverse, layout, point_rows
from ...kinematics.singularity import inverse_stack
from ..motors import MIN_STIFFNESS

DEFLECTION = ("dx", "dy", "dz", "rx", "ry", "rz")
FREQUENCIES = tuple(f"f{i}" for i in range(1, 7))
COLUMNS = ("t", *DEFLECTION, *FREQUENCIES, "kmin")
UNITS = {"t": "s", **dict.fromkeys(DEFLECTION[:3], "m"), **dict.fromkeys(DEFLECTION[3:], "rad"),
         **dict.fromkeys(FREQUENCIES, "Hz"), "kmin": "N/m"}
WRENCH = ("FX", "FY", "FZ", "MX", "MY", "MZ")
MAX_WRENCH = 1e6  # N, N·m: beyond it a unit slip (the linear model is long gone anyway)
# The largest drive turn |Δθᵢ| [rad] the linear model is used for: its relative error was
# measured at ≤ 3.2 × max |Δθᵢ| against the nonlinear equilibrium, so ≈ 1 % here (§27.2).
MAX_TURN = 3e-3
# k [N·m/rad] outside it is a unit slip (the weight alone would turn a drive by ~10² rad, or
# 1/k's squares leave float range); the low end is the actuator file's (dynamics.motors)
STIFFNESS_RANGE = (MIN_STIFFNESS, 1e12)


class StiffnessError(InputError):
    """A stiffness option or input the model cannot use (one line)."""


@dataclass(frozen=True)
class StiffnessOptions:
    """What :func:`stiffness_at` applies, checked once.

    Attributes
    ----------
    wrench : tuple of float
        FX, FY, FZ [N] and MX, MY, MZ [N·m] on the tool: the force at the tip and the moment
        about the tip, world axes (default none: the weight alone).

    Raises
    ------
    StiffnessError
        A wrench that is not six finite numbers.
    """

    wrench: tuple = field(default=(0.0,) * 6)

    def __post_init__(self):
        w = self.wrench
        try:
            values = tuple(float(x) for x in w)
        except (TypeError, ValueError, OverflowError):  # OverflowError: 10**400
            raise StiffnessError(f"wrench must be six numbers {', '.join(WRENCH)}, got "
                                 f"{shorten(w)}") from None
        if len(values) != 6:
            raise StiffnessError(f"wrench must be six numbers {', '.join(WRENCH)}, got "
                                 f"{len(values)}")
        for name, v in zip(WRENCH, values):
            if not (math.isfinite(v) and abs(v) <= MAX_WRENCH):
                raise StiffnessError(f"wrench {name} = {v!r}: must be a finite number of at "
                                     f"most {MAX_WRENCH:g} in magnitude (N, N·m)")
        object.__setattr__(self, "wrench", values)


def check_stiffness(k) -> np.ndarray:
    """The six drive stiffnesses [N·m/rad] as an array, each finite, > 0 and within
    :data:`STIFFNESS_RANGE` (:class:`StiffnessError` naming the first that is not)."""
    k = float_array(k, "stiffness", error=StiffnessError).reshape(-1)
    if k.shape != (6,):
        raise StiffnessError(f"stiffness must be six numbers (one per actuator), got {k.size}")
    bad = np.flatnonzero(~(np.isfinite(k) & (k > 0)))
    if len(bad):
        i = int(bad[0])
        raise StiffnessError(f"stiffness of actuator {i + 1} = {k[i]!r}: must be a finite "
                             "number > 0 N·m/rad")
    lo, hi = STIFFNESS_RANGE
    bad = np.flatnonzero((k < lo) | (k > hi))
    if len(bad):
        i = int(bad[0])
        raise StiffnessError(f"stiffness of actuator {i + 1} = {float(k[i]):g}: must be {lo:g} to "
                             f"{hi:g} N·m/rad")
    return k


@dataclass
class StiffnessResult:
    """Stiffness and vibration per sample (the table's writer:
    :class:`pollard_pin.run.stiffness.StiffnessRun`).

    Attributes
    ----------
    t : numpy.ndarray
        (N,) the samples' times [s].
    deflection : numpy.ndarray
        (N, 6) dx, dy, dz [m] and rx, ry, rz [rad] (rotation vector), world axes.
    frequencies : numpy.ndarray
        (N, 6) the natural frequencies [Hz], ascending.
    kmin : numpy.ndarray
        (N,) the tip's stiffness in its softest direction, 1 / λmax(C[:3, :3]) [N/m].
    turn : numpy.ndarray or None
        (N,) the largest drive turn max |Δθᵢ| [rad] under the load (the linear model holds
        up to :data:`MAX_TURN`; :func:`check_linear`).
    """

    t: np.ndarray
    deflection: np.ndarray
    frequencies: np.ndarray
    kmin: np.ndarray
    turn: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.t)

    def columns(self) -> dict[str, np.ndarray]:
        """The ``stiffness`` table's columns (:data:`COLUMNS`), SI units (:data:`UNITS`)."""
        cols = {"t": self.t}
        cols.update({n: self.deflection[:, i] for i, n in enumerate(DEFLECTION)})
        cols.update({n: self.frequencies[:, i] for i, n in enumerate(FREQUENCIES)})
        cols["kmin"] = self.kmin
        return cols


@dataclass(frozen=True)
class ClosedLoop:
    """The closed-loop maps at a stack of configurations: ``J`` (N, 6, 6) actuated rates →
    tool twist (tip velocity, angular velocity; world axes) and ``S`` (N, 12, 6) actuated rates
    → tree rates (v = S θ̇)."""

    J: np.ndarray
    S: np.ndarray


def closed_loop_maps(robot, q) -> ClosedLoop:
    """J and S at closed configurations q (N, 12) (docs/model.md §27.1): with
    Kq = [Jc; J_tool] (12 × 12), Kq v = [0; twist] on the loops, so θ̇ = Kq⁻¹[act, 6:] twist:
    J⁻¹ is that block, and S = Kq⁻¹[:, 6:] J. NaN where Kq or J⁻¹ is singular."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    lay = layout(robot)
    R, o = lay.tree.placements(q)
    Kq, _ = point_rows(lay, R, o, robot.model.nv)
    Kinv = kinematic_inverse(Kq, lay)
    tool = Kinv[:, :, 6:]
    J = inverse_stack(tool[:, robot.actuated_v, :])
    return ClosedLoop(J=J, S=tool @ J)


def reduced_mass_and_gravity(robot, q, S) -> tuple[np.ndarray, np.ndarray]:
    """(Mₐ (N, 6, 6), τ_g (N, 6)) at closed configurations q (N, 12) with S = ∂q/∂θ
    (docs/model.md §27.3): Mₐ = Sᵀ M S with M Pinocchio's joint-space mass matrix of the links
    (CRBA; the model's armature, rotors, taken out), and τ_g = Sᵀ g(q), the open tree's
    gravity torques projected on the loops: the closed-loop inverse dynamics of §13 at zero
    velocity and acceleration (Jc S = 0 drops the closure forces)."""
    model, data = robot.model, robot.data
    n, nv = len(q), model.nv
    M, tree = np.empty((n, nv, nv)), np.empty((n, nv, 1))
    for i in range(n):  # ≈ 3 µs a sample: cheaper than any stacked numpy form here
        M[i] = pin.crba(model, data, q[i])
        tree[i, :, 0] = pin.computeGeneralizedGravity(model, data, q[i])
    M = np.triu(M) + np.swapaxes(np.triu(M, 1), 1, 2)  # crba fills the upper triangle
    arm = np.asarray(model.armature, dtype=float)
    if arm.any():
        M -= np.diag(arm)
    St = np.swapaxes(S, 1, 2)
    return St @ M @ S, (St @ tree)[..., 0]


def holding_torques(robot, q, S) -> np.ndarray:
    """τ_g (N, 6) = Sᵀ g(q): the actuator torques that hold the robot still at closed
    configurations q (the gravity half of :func:`reduced_mass_and_gravity`)."""
    model, data = robot.model, robot.data
    tree = np.empty((len(q), model.nv, 1))
    for i in range(len(q)):
        tree[i, :, 0] = pin.computeGeneralizedGravity(model, data, q[i])
    return (np.swapaxes(S, 1, 2) @ tree)[..., 0]


def deflection_at(robot, q, k, wrench=None, t=None) -> np.ndarray:
    """The deflection d = J K⁻¹ (Jᵀ W − τ_g) under the weight and a wrench, without the
    modes: one gravity pass per sample (docs/model.md §27.2).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    q : numpy.ndarray
        Configurations (N, 12) or (12,), loops closed.
    k : ArrayLike
        The six drives' stiffnesses [N·m/rad].
    wrench : ArrayLike or None, optional
        None (the weight alone), six numbers for every sample, or (N, 6) one per sample:
        FX, FY, FZ [N] at the tip, MX, MY, MZ [N·m] about it, world axes (e.g. a spray's
        recoil along each sample's gun axis).
    t : ArrayLike or None, optional
        The samples' times [s], for the error messages (default their indices).

    Returns
    -------
    numpy.ndarray
        (N, 6): dx, dy, dz [m] and rx, ry, rz [rad], world axes.

    Raises
    ------
    StiffnessError
        ``k`` or the wrench not finite, or of the wrong shape; a drive turned beyond
        :data:`MAX_TURN` (:func:`check_linear`), naming the sample.
    SingularityError
        A singular configuration, naming its sample.
    """
    d, turn = loaded_deflection(robot, q, k, wrench, t)
    check_linear(turn, t)
    return d


def loaded_deflection(robot, q, k, wrench=None, t=None) -> tuple[np.ndarray, np.ndarray]:
    """(:func:`deflection_at`'s deflection (N, 6), the largest drive turn max |Δθᵢ| (N,)
    [rad]), unchecked against :data:`MAX_TURN`: for a caller that flags the samples beyond
    it rather than refusing (docs/model.md §27.2).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    q : numpy.ndarray
        Configurations (N, 12) or (12,), loops closed.
    k : ArrayLike
        The six drives' stiffnesses [N·m/rad].
    wrench : ArrayLike or None, optional
        None, six numbers, or (N, 6) one per sample, as for :func:`deflection_at`.
    t : ArrayLike or None, optional
        The samples' times [s], for the error messages (default their indices).

    Returns
    -------
    tuple of numpy.ndarray
        The deflection (N, 6) [m, rad] and the largest drive turn (N,) [rad].
    """
    k = check_stiffness(k)
    q, t = _configurations(robot, q, t)
    W = np.zeros(6) if wrench is None else np.asarray(wrench, dtype=float)
    if W.shape not in ((6,), (len(q), 6)) or not np.isfinite(W).all():
        raise StiffnessError(f"wrench must be six finite numbers or ({len(q)}, 6) of them, got "
                             f"shape {W.shape}" + ("" if np.isfinite(W).all() else
                                                   " with non-finite entries"))
    loop = _regular_maps(robot, q, t)
    return _deflection(loop.J, k, W, holding_torques(robot, q, loop.S))


def check_linear(turn, t=None, first: int = 0) -> None:
    """Refuse (:class:`StiffnessError`, one line naming the first sample) a drive turn beyond
    :data:`MAX_TURN`, where the linear model's error exceeds ≈ 1 % (docs/model.md §27.2).

    Parameters
    ----------
    turn : ArrayLike
        (N,) the largest drive turn per sample [rad] (non-finite counts as beyond).
    t : ArrayLike or None, optional
        The samples' times [s] (default their indices).
    first : int, optional
        The first sample's number in the message (a window's start).
    """
    turn = np.asarray(turn, dtype=float).reshape(-1)
    bad = np.flatnonzero(~(turn <= MAX_TURN))
    if len(bad):
        i = int(bad[0])
        when = "" if t is None else f" (t = {float(np.asarray(t).reshape(-1)[i]):.6g} s)"
        raise StiffnessError(f"sample {first + i}{when}: a drive turns by {turn[i]:.3g} rad, "
                             f"beyond the linear model's {MAX_TURN:g} rad (docs/model.md §27.2)")


def _deflection(J, k, W, tau_g):
    # the springs' turn under the joint-space load, mapped to the tool (§27.2)
    load = (np.swapaxes(J, 1, 2) @ np.broadcast_to(W, (len(J), 6))[..., None])[..., 0] - tau_g
    with np.errstate(over="ignore", invalid="ignore"):  # a huge turn: refused by its caller
        dtheta = load / k
        turn = np.abs(dtheta).max(axis=1)
        return (J @ dtheta[..., None])[..., 0], np.where(np.isfinite(turn), turn, np.inf)


def _configurations(robot, q, t):
    q = np.atleast_2d(np.asarray(q, dtype=float))
    n = len(q)
    if q.shape != (n, robot.model.nq) or not np.isfinite(q).all():
        raise StiffnessError(f"configurations must be finite, shape (N, {robot.model.nq}), got "
                             f"shape {q.shape}")
    return q, np.arange(n, dtype=float) if t is None else np.asarray(t, dtype=float)


def _regular_maps(robot, q, t) -> ClosedLoop:
    """:func:`closed_loop_maps`, or a SingularityError naming the first sample where they are
    not finite."""
    loop = closed_loop_maps(robot, q)
    bad = ~np.isfinite(loop.S).all(axis=(1, 2))
    if bad.any():
        i = int(np.argmax(bad))
        raise SingularityError("the closed-loop Jacobian J (actuated rates → tool twist) is "
                               "not finite: a parallel or serial singularity (docs/model.md "
                               "§12, §27.1)", chain="stiffness", sample=i, time=float(t[i]))
    return loop


def stiffness_at(robot, q, k, options: StiffnessOptions | None = None, t=None
                 ) -> StiffnessResult:
    """Deflection, natural frequencies and kmin at closed configurations (docs/model.md §27).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    q : numpy.ndarray
        Configurations (N, 12) or (12,), loops closed (an IK's ``q``).
    k : ArrayLike
        The six drives' stiffnesses [N·m/rad], docs/model.md §6 order.
    options : StiffnessOptions or None, optional
        The wrench on the tool (default none: the weight alone).
    t : ArrayLike or None, optional
        The samples' times [s] (default their indices).

    Returns
    -------
    StiffnessResult
        Per sample the deflection [m, rad], the six frequencies [Hz], kmin [N/m] and the
        largest drive turn [rad] (not refused here: :func:`check_linear`).

    Raises
    ------
    StiffnessError
        ``k`` not six finite positive numbers, or ``options`` not a StiffnessOptions.
    SingularityError
        The closed-loop maps not finite at a configuration (a singular Jc_p or J), naming
        its sample.
    """
    options = StiffnessOptions() if options is None else options
    if not isinstance(options, StiffnessOptions):
        raise StiffnessError(f"options must be a StiffnessOptions, got {type(options).__name__}")
    k = check_stiffness(k)
    q, t = _configurations(robot, q, t)
    loop = _regular_maps(robot, q, t)
    J = loop.J
    Ma, tau_g = reduced_mass_and_gravity(robot, q, loop.S)
    defl, turn = _deflection(J, k, np.asarray(options.wrench), tau_g)
    C = (J[:, :3, :] / k) @ np.swapaxes(J[:, :3, :], 1, 2)  # the force block of J K⁻¹ Jᵀ
    kmin = 1.0 / np.linalg.eigvalsh(C)[:, -1]
    # K u = ω² Mₐ u ⇔ (D Mₐ D) y = ω⁻² y with D = K^-½, u = D y: symmetric, batched (§27.3)
    s = 1.0 / np.sqrt(k)
    mu = np.linalg.eigvalsh(s[:, None] * Ma * s[None, :])[:, ::-1]
    freq = 1.0 / (2.0 * np.pi * np.sqrt(mu))
    return StiffnessResult(t=t, deflection=defl, frequencies=freq, kmin=kmin, turn=turn)
