"""What both IK solvers share (kinematics/ik_common.py): ZYZ angles and rates against
rotations written out (tests/rotations.py) and finite differences, and the input and option
checks."""
import math

import numpy as np
import pytest
from rotations import Ry, Rz

from pollard_pin.kinematics.errors import KinematicsInputError
from pollard_pin.kinematics.ik_common import check_options, task_inputs, zyz, zyz_rates


def zyz_matrix(a, b, c):
    return Rz(a) @ Ry(b) @ Rz(c)


def test_zyz_round_trip():
    rng = np.random.default_rng(1)
    ang = np.column_stack([rng.uniform(-np.pi, np.pi, 100), rng.uniform(1e-3, np.pi - 1e-3, 100),
                           rng.uniform(-np.pi, np.pi, 100)])
    M = np.array([zyz_matrix(*x) for x in ang])
    assert np.abs(zyz(M) - ang).max() < 1e-12  # achieved 2e-15
    # b near 0 is accurate (atan2, not arccos): b = 1e-9 comes back to round-off
    assert zyz(zyz_matrix(0.3, 1e-9, -0.2)[None])[0, 1] == pytest.approx(1e-9, rel=1e-6)


def test_zyz_rates_from_finite_differences():
    """(ȧ, ḃ, ċ) from w with Ṁ Mᵀ = ŵ, M(t) by central differences (h = 1e-6; achieved
    4e-10), one sample (scalar path) and batched."""
    def ang(t):
        return np.array([0.4 + 0.7 * t, 1.1 - 0.3 * t**2, -0.5 + 0.9 * np.sin(t)])

    def rates(t):
        return np.array([0.7, -0.6 * t, 0.9 * np.cos(t)])

    h, ts = 1e-6, np.linspace(0.0, 1.5, 7)
    ws = []
    for t in ts:
        W = (zyz_matrix(*ang(t + h)) - zyz_matrix(*ang(t - h))) / (2 * h) \
            @ zyz_matrix(*ang(t)).T
        ws.append([W[2, 1], W[0, 2], W[1, 0]])
        assert np.abs(zyz_rates(ang(t), np.array(ws[-1])) - rates(t)).max() < 5e-8
    batched = zyz_rates(np.array([ang(t) for t in ts]), np.array(ws))
    assert np.abs(batched - np.array([rates(t) for t in ts])).max() < 5e-8


def test_task_inputs_fill_zeros_and_default_times():
    p, d, dd, t = task_inputs(np.ones((3, 6)), None, None, None)
    assert not d.any() and not dd.any() and np.array_equal(t, [0.0, 1.0, 2.0])


@pytest.mark.parametrize("args, says", [
    ((np.ones((0, 6)), None, None, None), "no samples"),
    ((np.ones((3, 5)), None, None, None), "expected (3, 6)"),
    ((np.ones((3, 6)), np.ones((2, 6)), None, None), "pose rate array has shape (2, 6)"),
    ((np.ones((3, 6)), None, None, [0.0, 1.0, 1.0]), "times are not increasing"),
    ((np.ones((3, 6)), None, None, [0.0, 1.0, 1.0 + 1e-12]), "time step too small"),
    ((np.ones((3, 6)), None, None, [0.0, np.nan, 2.0]), "is not a finite number"),
])
def test_task_inputs_reject(args, says):
    with pytest.raises(KinematicsInputError) as info:
        task_inputs(*args)
    assert says in str(info.value)


@pytest.mark.parametrize("kw, name", [
    ({"tol": 0.0}, "tol"), ({"tol": "x"}, "tol"), ({"tol": math.nan}, "tol"),
    ({"max_iter": 0}, "max_iter"), ({"max_iter": 2.0}, "max_iter"),
])
def test_check_options_names_the_option(kw, name):
    opts = {"tol": 1e-12, "margins": None}
    counts = {"max_iter": kw.pop("max_iter")} if "max_iter" in kw else {}
    with pytest.raises(KinematicsInputError) as info:
        check_options(**{**opts, **kw}, **counts)
    assert info.value.chain.startswith(name)


def test_check_options_passes_the_margins_whole():
    """None gives the defaults; a Margins comes back as it is; anything else is refused (the
    margin values themselves are checked once, when the Margins is made)."""
    from pollard_pin.kinematics.margins import MarginError, Margins

    assert check_options(1e-12, None) == Margins()
    m = Margins(wrist=0.2, singularity=0.0)
    assert check_options(1e-12, m) is m
    with pytest.raises(MarginError):
        check_options(1e-12, {"wrist": 0.2})
    with pytest.raises(MarginError):
        Margins(wrist=1.5)


# --- IkOptions: checked once, passed whole ------------------------------------------------------
@pytest.mark.parametrize("kw, says", [
    ({"method": "lm"}, "method must be 'batch' or 'newton', got 'lm'"),
    ({"tol": 0.0}, "tol = 0.0: "),
    ({"max_iter": 0}, "max_iter = 0: must be an integer >= 1"),
    ({"chunk": 2.5}, "chunk = 2.5: must be an integer >= 1"),
])
def test_ik_options_refuse_bad_values_at_construction(kw, says):
    from pollard_pin.kinematics.ik_common import IkOptions

    with pytest.raises(KinematicsInputError) as ei:
        IkOptions(**kw)
    assert says in str(ei.value) and "\n" not in str(ei.value)


def test_ik_options_normalise_the_margins_and_the_solver_refuses_other_types(robot):
    from pollard_pin.kinematics.ik import inverse_kinematics
    from pollard_pin.kinematics.ik_common import IkOptions
    from pollard_pin.kinematics.margins import Margins

    assert IkOptions().margins == Margins()  # None: the defaults, made once
    pose = np.asarray(robot.params.home_pose, dtype=float)[None, :]
    with pytest.raises(KinematicsInputError, match="options must be an IkOptions, got dict"):
        inverse_kinematics(robot, pose, options={"method": "newton"})
    with pytest.raises(TypeError):  # the margins go in the options, the one way in
        inverse_kinematics(robot, pose, margins=Margins())
    # the options' margins reach the check: too strict a wrist margin refuses the home pose
    home_wrist = abs(np.sin(inverse_kinematics(robot, pose).q[0, 4]))
    from pollard_pin.kinematics.errors import SingularityError

    with pytest.raises(SingularityError, match=f"{home_wrist:.4f} is below the margin"):
        inverse_kinematics(robot, pose, options=IkOptions(margins=Margins(home_wrist + 0.1)))


@pytest.mark.parametrize("field, value", [
    ("poses", [["0.5", "0", "0.16", "0", "0", "0"]]),
    ("poses", [[10**400, 0, 0.16, 0, 0, 0]]),
    ("poses", np.full((1, 6), 0.5 + 1j)),
    ("d_poses", np.ones((1, 6), dtype=bool)),
    ("t", ["zero"]),
])
def test_task_inputs_refuse_what_is_not_real_numbers(field, value):
    """Strings, integers beyond a float, complex or bool values: one KinematicsInputError line
    naming the argument, not numpy's ValueError or OverflowError (complex was cast silently)."""
    args = {"poses": [[0.5, 0.0, 0.16, 0.0, 0.0, 0.0]], "d_poses": None, "dd_poses": None,
            "t": None, field: value}
    with pytest.raises(KinematicsInputError, match=f"^{field} = .*expected an array of real"):
        task_inputs(**args)


@pytest.mark.parametrize("field", ["method", "max_iter", "chunk", "margins"])
def test_ik_options_show_a_huge_value_short(field):
    """An integer beyond a float is one short line, not its 401 digits echoed."""
    from pollard_pin.errors import InputError
    from pollard_pin.kinematics.ik_common import IkOptions

    with pytest.raises(InputError, match=r"1e\+400 \(a 401-digit integer\)") as got:
        IkOptions(**{field: -10**400 if field != "method" else 10**400})
    assert len(str(got.value)) < 200
