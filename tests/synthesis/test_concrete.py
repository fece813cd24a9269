"""One design made concrete (synthesis/concrete.py): the mass model's bodies, the chosen motors, and
files every command reads back."""
import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.synthesis import baseline_values, build, load_space
from pollard_pin.synthesis.concrete import actuators_toml, params_toml


@pytest.fixture(scope="module")
def space():
    return load_space("examples/design/space.toml")


def test_baseline_is_the_thesis_robot_with_its_motors(space):
    d = build(baseline_values(space), space)
    shipped = pp.load_params()
    assert (d.params.x32, d.params.x65, d.params.legs[0].x87) == (0.33, 0.37, 0.325)
    assert d.actuators.units == load_actuators().units
    # the links are today's; the platform carries the three wrist motors (W5, 0.04 kg each)
    assert d.params.body("arm0") == shipped.body("arm0")
    assert d.params.body("platform").mass == pytest.approx(0.188 + 3 * 0.04)
    assert d.moving_mass == pytest.approx(shipped.total_mass + 0.12)
    assert d.robots == 1 and d.price == 3 * 250 + 3 * 150
    assert d.motors["theta21"] == ("S20", 100.0)


def test_a_scaled_design(space):
    v = {**baseline_values(space), "scale.arms": 1.5, "scale.links": 1.4, "motor.base": 2,
         "ratio.base": 2}
    d = build(v, space)
    assert d.params.x32 == pytest.approx(0.495) and d.params.x65 == pytest.approx(0.518)
    assert d.params.body("arm0").mass == pytest.approx(0.166 * 1.5)
    assert d.params.body("link_1").mass == pytest.approx(0.062 * 1.4)
    assert d.actuators["theta21"].gear_ratio == 160.0
    assert d.params.joint_limits("theta21").effort == pytest.approx(0.32 * 160)


def test_files_read_back(space, tmp_path):
    v = {**baseline_values(space), "scale.arms": 1.3, "motor.wrist": 5}
    d = build(v, space)
    (tmp_path / "p.toml").write_text(params_toml(d, "header"), encoding="utf-8")
    (tmp_path / "a.toml").write_text(actuators_toml(d), encoding="utf-8")
    p = pp.load_params(tmp_path / "p.toml")
    assert p.x32 == d.params.x32 and p.legs == d.params.legs
    for (n1, b1), (n2, b2) in zip(p.bodies, d.params.bodies):
        assert n1 == n2 and b1.mass == b2.mass
        np.testing.assert_allclose(b1.inertia, b2.inertia, rtol=1e-12)
    assert p.limits == d.params.limits
    assert load_actuators(tmp_path / "a.toml").units == d.actuators.units
