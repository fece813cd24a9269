"""Free-body joint loads (crosscheck/newton_euler.py), numpy only, against Newton's law for the
whole robot: the three base joints carry Σ m (a_G − g), the closure forces being internal, with
the CoG accelerations from finite differences of the CoG positions. (Against Pinocchio's loads
and MuJoCo's: tests/dynamics/test_loads.py.)"""

import numpy as np
from bare_modules import run_bare
from thesis_curves import T_PROBE, sinusoid_trajectory

from pollard_pin.analytic.closed_form import body_kinematics
from pollard_pin.crosscheck.newton_euler import joint_loads, static_loads
from pollard_pin.model.params import load_params
from pollard_pin.names import BODIES

G = np.array([0.0, 0.0, -9.81])
BASE = ("theta21", "theta21_1", "theta21_2")


def test_base_carries_the_rate_of_momentum():
    """Σ base forces = Σ_k m_k (a_Gk − g), a_G by central differences (h = 1e-4: achieved
    1.9e-8 N, mostly the round-off ε·r/h²; asserted 2e-6 N)."""
    p = load_params()
    _, x, xd, xdd = sinusoid_trajectory(p, t=T_PROBE[:4])
    loads = joint_loads(p, x, xd, xdd)
    base = [loads["joints"].index(j) for j in BASE]
    h = 1e-4
    cog = [{b: k["r"] for b, k in body_kinematics(p, *sinusoid_trajectory(
        p, t=T_PROBE[:4] + s)[1:]).items()} for s in (-h, 0.0, h)]
    want = sum(p.body(b).mass * ((cog[2][b] - 2 * cog[1][b] + cog[0][b]) / h**2 - G)
               for b in BODIES)
    got = loads["force"][:, base].sum(1)
    assert np.abs(want - sum(p.body(b).mass * -G for b in BODIES)).max() > 1e-2  # it moves
    assert np.abs(got - want).max() < 2e-6


def test_at_rest_the_base_carries_the_weight_and_static_is_rest():
    p = load_params()
    pose = np.array([p.home_pose])
    st = static_loads(p, pose)
    z = np.zeros((1, 6))
    moving = joint_loads(p, pose, z, z)
    assert all(np.array_equal(st[k], moving[k]) for k in ("force", "moment", "closure_forces"))
    base = [st["joints"].index(j) for j in BASE]
    weight = -9.81 * sum(p.body(b).mass for b in BODIES)
    assert abs(weight) > 9  # 0.92 kg
    assert np.abs(st["force"][0, base].sum(0) - [0.0, 0.0, -weight]).max() < 1e-13


def test_numpy_only():
    """With Pinocchio hidden and the package ``__init__`` files bypassed, the recursion loads
    (its own imports never reach Pinocchio)."""
    r = run_bare("import pollard_pin.crosscheck.newton_euler\n"
                 "assert not [m for m in sys.modules if m.startswith('pinocchio.')]\n")
    assert r.returncode == 0, r.stderr
