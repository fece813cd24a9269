"""The motor model written out from its formula (docs/model.md §19), for the tests of the
sizing: the shipped actuator file read directly (not through the loader), τm and ωm from run
columns."""
import math
import tomllib
from pathlib import Path

import numpy as np
from cli_run import run_cli as cli  # noqa: F401  (the sizing tests' CLI runner)

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "actuators.toml"
RATINGS = tomllib.loads(EXAMPLE.read_text())
NAMES = ("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716", "theta1817")


def motor(cols, name, ratings=None):
    """τm, ωm of one actuator from run-CSV columns; at rest (q̇ = 0) the breakaway friction
    ±c adds to the magnitude of the rest."""
    r = (ratings or RATINGS)[name]
    n, qd, qdd = r["gear_ratio"], cols[f"d_{name}"], cols[f"dd_{name}"]
    rest = cols[f"tau_{name}"] / n + r["rotor_inertia"] * n * qdd + r["viscous"] * n * qd
    friction = r["coulomb"] * np.where((qd > 0) | ((qd == 0) & (rest >= 0)), 1.0, -1.0)
    return rest + friction, n * qd


def run_columns(robot, traj) -> dict:
    """``pollard_pin.run_pipeline(robot, traj).columns()`` less the energies: the same IK,
    joint limits and torques (inverse_dynamics' energies are K and U, which no replay reads:
    a third of a long replay's time)."""
    import pollard_pin as pp
    from pollard_pin.dynamics.inverse import inverse_dynamics

    run = pp.run_pipeline(robot, traj, dynamics=False)
    return {**run.columns(), **inverse_dynamics(robot, run.ik, energies=False).columns()}


def rms(t, y):
    return math.sqrt(np.trapezoid(y * y, t) / (t[-1] - t[0]))
