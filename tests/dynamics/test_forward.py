"""forward_dynamics, replay_open_loop and the plant leave the caller's model alone
(docs/model.md §14): rotor inertia and Baumgarte gains go on their own copies, never on the
shared model, not even for the duration of a call."""
import numpy as np
import pytest

from pollard_pin.dynamics.forward import forward_dynamics, replay_open_loop
from pollard_pin.dynamics.inverse import JointLosses, inverse_dynamics_sample
from pollard_pin.dynamics.plant import ModelMismatch, Plant
from pollard_pin.errors import InputError


def _fields(robot) -> dict:
    model = robot.model
    return {"armature": np.array(model.armature),
            "inertias": [(Y.mass, np.array(Y.lever), np.array(Y.inertia))
                         for Y in model.inertias],
            "gravity": np.array(model.gravity.linear),
            "baumgarte": [(cm.m_baumgarte_parameters.Kp, cm.m_baumgarte_parameters.Kd)
                          for cm in robot.constraint_models]}


def _same(a: dict, b: dict) -> bool:
    return (np.array_equal(a["armature"], b["armature"])
            and np.array_equal(a["gravity"], b["gravity"])
            and a["baumgarte"] == b["baumgarte"]
            and all(m1 == m2 and np.array_equal(c1, c2) and np.array_equal(i1, i2)
                    for (m1, c1, i1), (m2, c2, i2) in zip(a["inertias"], b["inertias"])))


def test_shared_model_is_never_changed(robot):
    before = _fields(robot)
    q, v = robot.home(), np.zeros(robot.model.nv)
    losses = JointLosses(viscous=0.01, armature=np.linspace(1e-4, 1e-3, 12))
    a = forward_dynamics(robot, q, v, np.full(6, 0.1), losses=losses)
    # the rotor inertia acted (on a copy): ID with the same losses returns the torque
    assert np.abs(inverse_dynamics_sample(robot, q, v, a, losses)[0] - 0.1).max() < 1e-13  # 3.8e-16
    assert _same(before, _fields(robot))

    during = []

    def torques(t, q_, v_):  # looks at the shared model while replay_open_loop runs
        during.append(_same(before, _fields(robot)))
        return np.zeros(6)

    sim = replay_open_loop(robot, torques, q, v, duration=0.01, dt=5e-3, baumgarte=(900.0, 60.0))
    assert len(during) == 8 and all(during)
    assert np.all(np.isfinite(sim.q))
    Plant(robot, ModelMismatch(payload=0.05, mass_error=0.2,
                               losses=JointLosses(armature=1e-3)), baumgarte=(100.0, 20.0))
    assert _same(before, _fields(robot))


def test_api_names_say_what_they_do():
    """The open-loop replay is not called ``simulate`` (the closed-loop command's name), and the
    plant's model mismatch is not one letter away from its error class."""
    import pollard_pin as pp
    from pollard_pin.dynamics import plant

    assert replay_open_loop is replay_open_loop
    assert "simulate" not in pp.__all__ and not hasattr(plant, "PlantErrors")
    assert ModelMismatch is ModelMismatch


@pytest.mark.parametrize("which, value, says", [
    ("q", np.zeros(5), r"^q has shape \(5,\), expected \(12,\)$"),
    ("v", np.zeros((1, 12)), r"^v has shape \(1, 12\), expected \(12,\)$"),
    ("tau_act", np.zeros(5), r"^tau_act has shape \(5,\), expected \(6,\)$"),
    ("tau_act", [0.0, np.nan, 0, 0, 0, 0], r"^tau_act\[1\] = nan: must be a finite number$"),
    ("q", "a", "^q = 'a': expected an array of real numbers"),
    ("tau_act", [10**400] * 6, "^tau_act = .*expected an array of real numbers"),
    ("settings", {}, "^settings = {}: expected pinocchio.ProximalSettings, got dict$"),
    ("losses", "x", "^losses = 'x': expected a JointLosses, got str$"),
])
def test_forward_dynamics_refuses_bad_arguments(robot, which, value, says):
    """A wrong size, a non-number or a NaN: one InputError line before Pinocchio is given
    the vector (its C++ check raises a multi-line ValueError or aborts)."""
    args = {"q": robot.home(), "v": np.zeros(12), "tau_act": np.zeros(6), which: value}
    with pytest.raises(InputError, match=says):
        forward_dynamics(robot, **args)
    with pytest.raises(InputError, match="^robot = None: expected a Robot"):
        forward_dynamics(None, robot.home(), np.zeros(12), np.zeros(6))
