"""The deflection along a paint program (docs/model.md §27.7): the standoff error against
stiffness_at's deflection projected by hand, the recoil's bad values one line each."""
import math

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.analytic.taskspace import rotation
from pollard_pin.dynamics.drives.stiffness import StiffnessOptions, stiffness_at
from pollard_pin.errors import PollardError
from pollard_pin.painting.job import JobError, job_from_dict
from pollard_pin.painting.plan.compliance import program_deflection

SMALL = {"panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.06,
                   "height": 0.04},
         "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7, "recoil": 5.0},
         "job": {"thickness": 25e-6}}


def test_standoff_error_is_the_projected_deflection(robot, plan, act):
    """examples/paint.toml with a 3 N recoil: at a few samples (both sides of a CHUNK), the
    deflection of stiffness_at under the weight and the recoil's wrench −3 a, projected by
    hand on the spray axis and across it (achieved 7e-20 m on ~1e-4 m: round-off)."""
    k = act.stiffness()
    d = program_deflection(robot, plan.trajectory, k, plan.spray, recoil=3.0)
    idx = [0, 1234, 4095, 4096, len(plan.trajectory) - 1]
    q = pp.inverse_kinematics(robot, plan.trajectory.poses[idx]).q
    for j, i in enumerate(idx):
        a = rotation(plan.trajectory.poses[i])[:, 0]
        w = StiffnessOptions(wrench=(*(-3.0 * a), 0.0, 0.0, 0.0))
        ref = stiffness_at(robot, q[j:j + 1], k, w).deflection[0]
        along = ref[:3] @ a
        assert d.standoff[i] == pytest.approx(along, abs=1e-17)
        assert d.lateral[i] == pytest.approx(np.linalg.norm(ref[:3] - along * a), abs=1e-17)
        assert d.tilt[i] == pytest.approx(np.linalg.norm(ref[3:] - (ref[3:] @ a) * a),
                                          abs=1e-17)
    # the weight alone sags the tip by tens of µm, the recoil pushes it back along the axis
    weight = program_deflection(robot, plan.trajectory, k)
    assert 1e-6 < np.abs(weight.deflection[:, :3]).max() < 1e-3
    assert np.all(d.standoff < weight.standoff)


@pytest.mark.parametrize("value, rule", [
    (-0.5, ">= 0"), (math.nan, "finite"), (1e6, "at most 100 N"), ("0.5", "a number"),
    (True, "a number")])
def test_bad_recoil_is_one_line(value, rule):
    d = {**SMALL, "gun": {**SMALL["gun"], "recoil": value}}
    with pytest.raises(JobError) as exc:
        job_from_dict(d, "bad.toml")
    msg = str(exc.value)
    assert isinstance(exc.value, PollardError) and "\n" not in msg
    assert "bad.toml" in msg and "gun.recoil" in msg and rule in msg, msg


def test_recoil_round_trips():
    job = job_from_dict(SMALL, "small.toml")
    assert job.recoil == 5.0 and job.to_dict()["gun"]["recoil"] == 5.0
    assert job_from_dict({**SMALL, "gun": {"standoff": 0.15, "sigma": 0.01, "flow": 1e-7}}
                         ).recoil is None


@pytest.mark.parametrize("recoil", [-1.0, math.nan, 1e6, True])
def test_program_deflection_refuses_a_bad_recoil(robot, act, plan, recoil):
    with pytest.raises(PollardError, match="recoil") as exc:
        program_deflection(robot, plan.trajectory, act.stiffness(), recoil=recoil)
    assert "\n" not in str(exc.value)
