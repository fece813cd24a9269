"""The run's statistics: :class:`RunStats` accumulated window by window, the summary text,
and the run's duty figures (peaks, time-weighted RMS, energy) from its columns."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..dynamics.averages import time_mean, time_rms
from ..kinematics.ik import IKResult
from .pipeline import RunResult

_PEAK = ("tau_", "power_")


@dataclass
class RunStats:
    """What the summary needs, accumulated window by window (nothing per sample is kept)."""

    name: str
    derivatives: str
    samples: int = 0
    t_first: float = math.nan
    t_last: float = math.nan
    closure_residual: float = 0.0
    tool_error: float = 0.0
    wrist: tuple[float, float] = (math.inf, -math.inf)
    sigma_parallel: float = math.inf
    sigma_serial: float = math.inf
    actuated: tuple[str, ...] = ()
    peak: dict = field(default_factory=dict)  # column → max |value|
    work: dict = field(default_factory=dict)  # work column → last value
    closure_force: list = field(default_factory=lambda: [0.0, 0.0])
    joint_load: dict = field(default_factory=dict)  # joint → [peak |F| N, peak |M| N·m]

    def add(self, ik: IKResult, cols: dict) -> None:
        n = len(cols["t"])
        if not n:
            return
        skip = len(ik) - n  # the overlap sample of a window is counted once
        if not self.samples:
            self.t_first = float(cols["t"][0])
        self.samples += n
        self.t_last = float(cols["t"][-1])
        self.closure_residual = max(self.closure_residual, float(cols["closure_residual"].max()))
        self.tool_error = max(self.tool_error, float(ik.tool_error[skip:].max()))
        w = cols["wrist_margin"]
        self.wrist = (min(self.wrist[0], float(w.min())), max(self.wrist[1], float(w.max())))
        self.sigma_parallel = min(self.sigma_parallel, float(cols["sigma_parallel"].min()))
        self.sigma_serial = min(self.sigma_serial, float(cols["sigma_serial"].min()))
        for name, col in cols.items():
            if name.startswith(_PEAK):
                self.peak[name] = max(self.peak.get(name, 0.0), float(np.abs(col).max()))
            elif name.startswith("work_"):
                self.work[name] = float(col[-1])
        for i in range(2):
            if f"f{i + 1}_x" in cols:
                self.closure_force[i] = max(self.closure_force[i], _peak_norm(cols, f"f{i + 1}"))
        for name in cols:  # run --loads: F_<joint>_x … M_<joint>_z (docs/model.md §17)
            if name.startswith("F_") and name.endswith("_x"):
                joint = name[2:-2]
                peak = self.joint_load.setdefault(joint, [0.0, 0.0])
                for i, kind in enumerate("FM"):
                    peak[i] = max(peak[i], _peak_norm(cols, f"{kind}_{joint}"))
        if not self.actuated:
            self.actuated = tuple(c[4:] for c in cols if c.startswith("tau_"))

    def lines(self) -> list[str]:
        wmin, wmax = self.wrist
        lines = [
            f"trajectory {self.name}: {self.samples} samples over "
            f"{self.t_last - self.t_first:.4g} s (derivatives: {self.derivatives})",
            f"max closure residual {self.closure_residual:.3g} m, "
            f"max tool-pose error {self.tool_error:.3g}",
            f"wrist margin |sin θ1716| in [{wmin:.4f}, {wmax:.4f}] "
            f"(θ1716 in [{math.degrees(math.asin(wmin)):.2f}°, "
            f"{math.degrees(math.asin(wmax)):.2f}°])",
            f"worst conditioning: σ_min parallel {self.sigma_parallel:.4g}, "
            f"serial {self.sigma_serial:.4g}",
        ]
        if self.actuated:
            lines.append("actuator        peak |τ| [N·m]   peak |power| [W]   net work [J]")
            for n in self.actuated:
                lines.append(f"  {n:12s} {self.peak[f'tau_{n}']:14.5g} "
                             f"{self.peak[f'power_{n}']:18.5g} {self.work[f'work_{n}']:14.5g}")
            f = self.closure_force
            lines.append(f"peak closure force: leg 1 {f[0]:.4g} N, leg 2 {f[1]:.4g} N")
        if self.joint_load:
            lines.append("joint          peak |force| [N]  peak |moment| [N·m]  (pollard-pin "
                         "report: axial/radial/bending)")
            for joint, (fmax, mmax) in self.joint_load.items():
                lines.append(f"  {joint:12s} {fmax:16.5g} {mmax:20.5g}")
        return lines


def _peak_norm(cols: dict, stem: str) -> float:
    """Largest magnitude of the vector columns ``<stem>_x``, ``_y``, ``_z``."""
    return float(np.sqrt(sum(cols[f"{stem}_{c}"] ** 2 for c in "xyz")).max())


def summary(result: RunResult | RunStats) -> str:
    """The run's summary text."""
    if isinstance(result, RunResult):
        stats = RunStats(result.trajectory.name, result.trajectory.derivatives)
        stats.add(result.ik, result.columns())
    else:
        stats = result
    return "\n".join(stats.lines())


def duty_figures(columns: dict, actuated) -> dict:
    """The duty of each actuator (peak and time-weighted RMS torque, peak speed and power,
    energy, net work) and of each spherical joint (peak and RMS force) from run columns
    (:meth:`RunResult.columns` or a ``run`` CSV read back): the ``report``'s sizing table."""
    t = np.asarray(columns["t"], dtype=float)
    acts = {}
    for n in actuated:
        tau, qd = np.asarray(columns[f"tau_{n}"]), np.asarray(columns[f"d_{n}"])
        p = np.asarray(columns[f"power_{n}"])
        acts[n] = {
            "peak_torque": float(np.max(np.abs(tau))),
            "rms_torque": float(time_rms(t, tau)),
            "peak_speed": float(np.max(np.abs(qd))),
            "peak_power": float(np.max(np.abs(p))),
            "energy": float((t[-1] - t[0]) * time_mean(t, np.abs(p))),
            "net_work": float(np.asarray(columns[f"work_{n}"])[-1]),
        }
    joints = {}
    for i in (1, 2):  # the two spherical joints (closures), docs/model.md §8
        f = np.sqrt(sum(np.square(np.asarray(columns[f"f{i}_{c}"])) for c in "xyz"))
        k = int(np.argmax(f))
        joints[f"spherical_{i}"] = {"peak_force": float(f[k]), "peak_time": float(t[k]),
                                    "rms_force": float(time_rms(t, f))}
    return {"actuators": acts, "spherical_joints": joints}
