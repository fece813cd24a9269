"""The result of a closed-loop simulation (docs/model.md §18): :class:`TrackingResult`, the
``pollard-pin simulate`` table and its figures, and :func:`tracking_summary`, the time-weighted
RMS errors (docs/model.md §13) that the table and the file read back share."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .averages import time_rms
from .drives.flexible import flexible_columns, max_deflection


def tracking_summary(t, tip_position_error, tip_orientation_error, torques: dict,
                     max_closure_residual: float, saturation_time: float | None) -> dict:
    """Max and time-weighted RMS (√(∫e² dt / T), docs/model.md §13) tool errors, peak |τ| per
    actuator (``torques``: name → (N,)), saturation time and closure residual (JSON-ready)."""
    e, o = np.asarray(tip_position_error), np.asarray(tip_orientation_error)
    return {"max_tip_position_error": float(e.max()),
            "rms_tip_position_error": float(time_rms(t, e)),
            "max_tip_orientation_error": float(o.max()),
            "rms_tip_orientation_error": float(time_rms(t, o)),
            "peak_torque": {n: float(np.abs(x).max()) for n, x in torques.items()},
            "saturation_time": None if saturation_time is None else float(saturation_time),
            "max_closure_residual": float(max_closure_residual)}


@dataclass
class TrackingResult:
    """A closed-loop simulation (:func:`~pollard_pin.simulate_tracking`), one row per output
    sample (the input trajectory's times).

    Attributes
    ----------
    t : ndarray
        Times (N,) [s].
    q, v, a : ndarray
        The plant's joint positions [rad], velocities [rad/s] and accelerations [rad/s²]
        under the applied torque, each (N, 12).
    tau : ndarray
        (N, 6) the applied (held, saturated) actuator torques [N·m].
    tip, tip_desired : ndarray
        (N, 3) the actual and desired tool-tip positions [m].
    tip_position_error, tip_orientation_error : ndarray
        (N,) |p − p_d| [m] and |log(R R_dᵀ)| [rad].
    closure_residual : ndarray
        (N,) the largest component of ``p_A − p_B`` [m].
    joint_names, actuated : tuple of str
        The columns of ``q`` and of ``tau``.
    saturation_time : float
        Seconds during which at least one actuator was saturated.
    max_closure_residual : float
        The largest loop residual over every control tick [m].
    steps : int
        RK4 steps taken.
    wall : float
        Seconds spent integrating.
    settings : dict
        The run's settings (controller, gains, steps, errors), for the table's metadata.
    phi, d_phi : ndarray or None
        With flexible drives, the motor angles [rad] and rates [rad/s] (N, 6), joint side;
        None otherwise.

    :meth:`columns` is the ``pollard-pin simulate`` table, :meth:`summary` its figures.
    """

    t: np.ndarray
    q: np.ndarray  # (N, 12) plant joint positions [rad]
    v: np.ndarray  # (N, 12) [rad/s]
    a: np.ndarray  # (N, 12) plant accelerations under the applied torque [rad/s²]
    tau: np.ndarray  # (N, 6) applied (held, saturated) actuator torques [N·m]
    tip: np.ndarray  # (N, 3) tool-tip position [m]
    tip_desired: np.ndarray  # (N, 3) [m]
    tip_position_error: np.ndarray  # (N,) |p − p_d| [m]
    tip_orientation_error: np.ndarray  # (N,) |log(R R_dᵀ)| [rad]
    closure_residual: np.ndarray  # (N,) max |p_A − p_B| component [m]
    joint_names: tuple[str, ...]
    actuated: tuple[str, ...]
    saturation_time: float = 0.0  # s during which at least one actuator was saturated
    max_closure_residual: float = 0.0  # over every control tick [m]
    steps: int = 0  # RK4 steps
    wall: float = 0.0  # s spent integrating
    settings: dict = field(default_factory=dict)
    phi: np.ndarray | None = None  # (N, 6) flexible drives: motor angles, joint side [rad]
    d_phi: np.ndarray | None = None  # (N, 6) [rad/s]

    def __len__(self) -> int:
        return len(self.t)

    def columns(self) -> dict[str, np.ndarray]:
        cols = {"t": self.t}
        cols.update({n: self.q[:, i] for i, n in enumerate(self.joint_names)})
        cols.update({f"d_{n}": self.v[:, i] for i, n in enumerate(self.joint_names)})
        cols.update({f"dd_{n}": self.a[:, i] for i, n in enumerate(self.joint_names)})
        cols.update({f"tau_{n}": self.tau[:, i] for i, n in enumerate(self.actuated)})
        cols.update({c: self.tip[:, i] for i, c in enumerate("xyz")})
        cols.update({f"desired_{c}": self.tip_desired[:, i] for i, c in enumerate("xyz")})
        cols.update({"tip_position_error": self.tip_position_error,
                     "tip_orientation_error": self.tip_orientation_error,
                     "closure_residual": self.closure_residual})
        if self.phi is not None:
            cols.update(flexible_columns(self.actuated, self.joint_names, self.q, self.phi,
                                         self.d_phi))
        return cols

    def summary(self) -> dict:
        s = tracking_summary(self.t, self.tip_position_error, self.tip_orientation_error,
                             dict(zip(self.actuated, self.tau.T)),
                             self.max_closure_residual, self.saturation_time)
        if self.phi is not None:
            s["max_deflection"] = max_deflection(self.actuated, self.joint_names, self.q,
                                                 self.phi)
        return s

    def summary_lines(self) -> list[str]:
        s = self.summary()
        return [(f"tool-tip position error: max {s['max_tip_position_error']:.3g} m, "
                 f"RMS {s['rms_tip_position_error']:.3g} m"),
                (f"tool orientation error: max {s['max_tip_orientation_error']:.3g} rad, "
                 f"RMS {s['rms_tip_orientation_error']:.3g} rad"),
                "peak |τ| [N·m]: " + ", ".join(f"{n} {p:.4g}"
                                               for n, p in s["peak_torque"].items()),
                (f"saturated {s['saturation_time']:.4g} s; max closure residual "
                 f"{s['max_closure_residual']:.3g} m"),
                *(["max |φ − q| [rad]: " + ", ".join(
                    f"{n} {p:.3g}" for n, p in s["max_deflection"].items())]
                  if self.phi is not None else []),
                f"{self.steps} RK4 steps in {self.wall:.2f} s wall"]


__all__ = ["TrackingResult", "tracking_summary"]
