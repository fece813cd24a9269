"""The independent replay of a retimed file (``size --retime``), for the tests of io/retime.py
and dynamics/passes.py: the motion between its rows rebuilt by the definition its metadata
states (constant s̈ along the source path's arc length) with only numpy, the exact source path
and the pipeline's inverse dynamics (not toppra, not the solver's code, not its arc-length
path), at THETA of every interval; the worst motor use per point."""
import csv
import json

import numpy as np
import pytest
from motor_model import NAMES, RATINGS, run_columns
from motor_model import motor as _motor

import pollard_pin as pp

THETA = (np.arange(12) + 0.5) / 12  # 12 points per interval, none a row


def read_retimed(path):
    """The columns and the metadata of a retimed file."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    cols = dict(zip(rows[0], np.array(rows[1:], dtype=float).T))
    meta = json.loads(path.with_name(path.stem + ".units.json").read_text())["metadata"]
    return cols, meta


class ArcLength:
    """s(u) of the source path by the trapezoid rule on a fine grid of its time u, the
    metadata's scale; inverted by Newton steps."""

    def __init__(self, curve, u0, u1, scale, n=1_000_001):
        self.curve, self.scale = curve, np.asarray(scale)
        self.u = np.linspace(u0, u1, n)
        g = self.speed(self.u)[0]
        self.sigma = np.concatenate([[0.0], np.cumsum((g[1:] + g[:-1]) / 2 * np.diff(self.u))])
        self.length = self.sigma[-1]

    def speed(self, u):
        p, pu, puu = self.curve(u)
        w, ww = pu / self.scale, puu / self.scale
        g = np.sqrt((w * w).sum(1))
        g1 = np.divide((w * ww).sum(1), g, out=np.zeros_like(g), where=g > 0)
        return g, g1, p, pu, puu

    def at(self, s):
        """Poses, dp/du, d²p/du², ds/du, d²s/du² at the points s ∈ [0, 1]."""
        target = s * self.length
        u = np.interp(target, self.sigma, self.u)
        for _ in range(2):
            g = self.speed(u)[0]
            step = np.interp(u, self.u, self.sigma) - target
            u = u - np.divide(step, g, out=np.zeros_like(g), where=g > 0)
        g, g1, p, pu, puu = self.speed(u)
        return p, pu, puu, g / self.length, g1 / self.length


def replay(robot, cols, meta, curve, n=1_000_001):
    """Worst motor use, per definition, at THETA of every interval between the rows."""
    assert meta["path_parameter"] == "arc_length", meta
    names = ("x", "y", "z", "psi", "theta", "phi")
    t = cols["t"]
    rate = np.column_stack([cols["d_" + n] for n in names])
    arc = ArcLength(curve, meta["source_start"], meta["source_end"], meta["arc_length_scale"],
                    n)
    # the stated length is the path's (seen 5e-14; 6e-12 with rest ends, this trapezoid's)
    assert arc.length == pytest.approx(meta["length"], rel=1e-9)
    sd = np.sqrt(((rate / meta["arc_length_scale"]) ** 2).sum(1)) / meta["length"]
    s = np.concatenate([[0.0], np.cumsum((sd[1:] + sd[:-1]) / 2 * np.diff(t))])
    assert s[-1] == pytest.approx(1.0, abs=1e-9)  # seen 8e-12
    poses = np.column_stack([cols[n] for n in names])
    assert np.abs(arc.at(s)[0] - poses).max() < 5e-8  # the rows lie on the path: seen 4e-10
    ds, k = np.diff(s), len(THETA)
    acc = (sd[1:] ** 2 - sd[:-1] ** 2) / (2 * ds)
    S = (s[:-1, None] + THETA * ds[:, None]).ravel()
    A, s0, sd0 = (np.repeat(x, k) for x in (acc, s[:-1], sd[:-1]))
    SD = np.sqrt(np.maximum(sd0**2 + 2 * A * (S - s0), 0.0))
    T = np.repeat(t[:-1], k) + 2 * (S - s0) / (SD + sd0)
    p, pu, puu, s_u, s_uu = arc.at(S)
    ud = SD / s_u
    udd = (A - s_uu * ud**2) / s_u
    traj = pp.Trajectory(T, p, pu * ud[:, None], puu * (ud**2)[:, None] + pu * udd[:, None])
    run = run_columns(robot, traj)
    use = []
    for name in NAMES:
        tau_m, w_m = _motor(run, name)
        use += [np.abs(tau_m) / RATINGS[name]["peak_torque"],
                np.abs(w_m) / RATINGS[name]["max_speed"]]
    return np.max(use, axis=0)
