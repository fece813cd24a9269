"""The mass model of a design (model/masses.py, docs/model.md §29.1): today's bodies at today's
lengths, a stretched link against a uniform rod's closed form, motors by the parallel-axis
theorem."""
import numpy as np
import pytest

from pollard_pin.model.masses import (
    LINK_LENGTHS,
    design_bodies,
    link_sections,
    sphere_inertia,
    stretched,
    with_points,
)
from pollard_pin.model.overrides import ParameterError, apply_overrides
from pollard_pin.model.params import params_from_dict, read_params_dict


@pytest.fixture(scope="module")
def ref():
    return read_params_dict()


def test_todays_lengths_give_todays_bodies(ref):
    out = design_bodies(ref, ref)
    for name, b in ref["bodies"].items():
        assert out[name]["mass"] == pytest.approx(b["mass"], rel=1e-12)
        np.testing.assert_allclose(out[name]["com"], b["com"], atol=1e-12)
        np.testing.assert_allclose(out[name]["inertia"], b["inertia"], rtol=1e-9, atol=1e-9)


def test_a_stretched_uniform_rod_is_the_longer_rod():
    # a thin uniform rod, 1 kg, 1 m, radius 1 cm: I = m r²/2 about its axis, m L²/12 + m r²/4
    # across; twice as long with the same section: 2 kg, I across = 2·(4/12 + r²/4)
    r2 = 1e-4
    rod = np.diag([r2 / 2, 1 / 12 + r2 / 4, 1 / 12 + r2 / 4])
    m, c, inertia = stretched(1.0, [0.5, 0.0, 0.0], rod, 2.0)
    assert m == 2.0
    np.testing.assert_allclose(c, [1.0, 0.0, 0.0])
    np.testing.assert_allclose(np.diag(inertia), [2 * r2 / 2, 2 * (4 / 12 + r2 / 4),
                                                  2 * (4 / 12 + r2 / 4)], rtol=1e-12)
    with pytest.raises(ParameterError):
        stretched(1.0, [0, 0, 0], rod, 0.0)


def test_scaling_lengths_scales_mass_and_inertia_by_the_law(ref):
    s = 1.5
    keys = {k for keys in LINK_LENGTHS.values() for k in keys}
    d = apply_overrides(ref, {k: ref[k.split(".")[0]][k.split(".")[1]] * s for k in keys})
    out = design_bodies(ref, d)
    for name in LINK_LENGTHS:
        b = ref["bodies"][name]
        assert out[name]["mass"] == pytest.approx(s * b["mass"], rel=1e-12)
        assert out[name]["com"][0] == pytest.approx(s * b["com"][0], rel=1e-12)
        # a diagonal body's inertia: Ixx = Py + Pz grows as s, Iyy, Izz nearly as s³
        I0, I1 = np.array(b["inertia"]), np.array(out[name]["inertia"])
        P0 = np.trace(I0) / 2 - np.diag(I0)  # (Px, Py, Pz) = the diagonal of P
        assert I1[0, 0] == pytest.approx(s * I0[0, 0], rel=1e-9)
        assert I1[1, 1] == pytest.approx(s**3 * P0[0] + s * P0[2], rel=1e-9)
    for name in ("wrist1", "wrist2", "gun"):
        assert out[name]["mass"] == ref["bodies"][name]["mass"]
    params_from_dict({**d, "bodies": out})  # physical: the parameter checks pass


def test_wrist_motors_ride_on_the_platform(ref):
    out = design_bodies(ref, ref, {"theta1615": 0.1, "theta1716": 0.1, "theta1817": 0.1,
                                   "theta21": 5.0})  # a base motor does not move
    b = ref["bodies"]["platform"]
    assert out["platform"]["mass"] == pytest.approx(b["mass"] + 0.3)
    x65 = ref["chain0"]["x65"]
    com = (b["mass"] * b["com"][0] + 0.3 * x65) / (b["mass"] + 0.3)
    assert out["platform"]["com"][0] == pytest.approx(com, rel=1e-12)
    assert out["arm0"]["mass"] == ref["bodies"]["arm0"]["mass"]
    with pytest.raises(ParameterError, match="not an actuator"):
        design_bodies(ref, ref, {"theta43": 1.0})


def test_parallel_axis_and_sphere():
    m, c, inertia = with_points(1.0, [0, 0, 0], np.zeros((3, 3)), [(1.0, [2.0, 0, 0], 0.0)])
    assert m == 2.0
    np.testing.assert_allclose(c, [1.0, 0, 0])
    np.testing.assert_allclose(inertia, np.diag([0.0, 2.0, 2.0]))  # two 1 kg points ±1 m
    # a 1 kg sphere of 5000 kg/m³: r = (3/(4π·5000))^(1/3) = 0.03628 m, I = 0.4 r²
    assert sphere_inertia(1.0) == pytest.approx(0.4 * 0.036278**2, rel=1e-4)


def test_link_sections_are_aluminium_tubes(ref):
    s = link_sections(ref)
    assert s["arm0"] == pytest.approx(0.166 / 0.33 / 2700 * 1e6, rel=1e-12)  # 186 mm²
    assert 50 < min(s.values()) and max(s.values()) < 250
