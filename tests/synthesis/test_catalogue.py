"""The motor catalogue (synthesis/catalogue.py, docs/model.md §31.2)."""
import pytest

from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.synthesis.catalogue import CatalogueError, catalogue_from_dict, load_catalogue

MOTOR = {"rated_torque": 0.02, "peak_torque": 0.05, "speed": 500.0, "rotor_inertia": 5e-6,
         "mass": 0.25, "ratios": [100, 50]}


def test_example_catalogue():
    cat = load_catalogue("examples/design/motors.toml")
    assert cat.names[:2] == ("S20", "S40") and cat.priced
    assert cat.ratios == (50.0, 100.0, 160.0)
    # S20 behind 100:1 and W5 behind 50:1 are the shipped actuators
    shipped = load_actuators()
    assert cat["S20"].actuator(100) == shipped["theta21"]
    assert cat["W5"].actuator(50) == shipped["theta1615"]


def test_ratio_near_is_nearest_in_log():
    m = catalogue_from_dict({"motors": {"a": MOTOR}}).motors[0]
    assert m.ratios == (50.0, 100.0)
    assert m.ratio_near(80) == 100.0 and m.ratio_near(60) == 50.0 and m.ratio_near(160) == 100
    assert m.price is None and m.stiffness is None and m.viscous == 0.0


@pytest.mark.parametrize("change, match", [
    ({"ratios": [50, 0]}, "gear ratio must be > 0"),
    ({"ratios": []}, "list of gear ratios"),
    ({"mass": -1.0}, "mass"),
    ({"rated_torque": 1.0}, "exceeds"),
    ({"speeed": 1.0}, "unknown column.*speed"),
    # 5 kg·m² behind 0.05 N·m: 5·500/0.05 = 5e4 s to spin the rotor up, 5e3 × the 10 s bound
    ({"rotor_inertia": 5}, r"'motors.a.rotor_inertia' = 5: the motor would take 5e\+04 s .* "
                           r"5e\+03 times the 10 s"),
    ({"rotor_inertia": 1.01e-3}, "would take 10.1 s"),  # just over: 1.01e-3·500/0.05
])
def test_bad_motor_is_one_line(change, match):
    with pytest.raises(CatalogueError, match=match) as e:
        catalogue_from_dict({"motors": {"a": {**MOTOR, **change}}}, "m.toml")
    assert "\n" not in str(e.value) and len(str(e.value)) <= 250


def test_missing_column_and_bad_layout():
    bad = dict(MOTOR)
    del bad["rotor_inertia"]
    with pytest.raises(CatalogueError, match="'motors.a.rotor_inertia' is missing"):
        catalogue_from_dict({"motors": {"a": bad}})
    with pytest.raises(CatalogueError, match=r"\[motors.NAME\]"):
        catalogue_from_dict({"a": MOTOR})
    with pytest.raises(CatalogueError, match="motor name"):
        catalogue_from_dict({"motors": {"a b\n": MOTOR}})
    with pytest.raises(CatalogueError, match="motor catalogue"):
        load_catalogue("no/such/file.toml")
