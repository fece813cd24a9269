"""One sweep variant through the pipeline (sweep/evaluate.py): each row equals the variant run
by hand, infeasible variants are rows that say why, and the function is pure and picklable."""
import math
import pickle

import numpy as np
import pytest
from sweep_grid import SAMPLES

import pollard_pin as pp
from pollard_pin.kinematics import KinematicsError
from pollard_pin.model import ParameterError
from pollard_pin.names import ACTUATED
from pollard_pin.run import run_pipeline
from pollard_pin.sweep import METRIC_COLUMNS, evaluate_variant


def _single_run(overrides):
    """The variant run by hand: load_params(overrides) → load → thesis trajectory → pipeline."""
    params = pp.load_params(overrides=overrides)
    robot = pp.load(params)
    traj = pp.thesis_trajectory(duration=20.0, samples=SAMPLES, home_pose=params.home_pose)
    return robot, run_pipeline(robot, traj)


def test_actuator_names_are_the_robot_s(robot):
    assert ACTUATED == tuple(robot.actuated)


def test_sweep_rows_equal_individual_runs(sweep, pool_rows):
    assert [r["variant"] for r in pool_rows] == [n for n, _ in sweep.variants]  # input order
    checked_feasible = checked_infeasible = 0
    for (name, overrides), row in zip(sweep.variants, pool_rows):
        # every parameter column holds the value the variant used (base value if not swept)
        base = pp.load_params(check_home=False)
        assert row["leg1.x87"] == overrides.get("leg1.x87", base.legs[0].x87)
        assert row["chain0.x32"] == overrides.get("chain0.x32", base.x32)
        if name == "gun cog":
            overrides = {"bodies.gun.com": [0.045, 0.0, 0.0]}  # the component key, by hand
        try:
            robot, result = _single_run(overrides)
        except (KinematicsError, ParameterError) as exc:
            assert row["feasible"] is False
            assert row["failure_kind"] == type(exc).__name__
            assert row["failure"] == str(exc)
            assert row["failure_sample"] == getattr(exc, "sample", None)
            assert row["failure_time"] == getattr(exc, "time", None)
            assert row["failure_chain"] == getattr(exc, "chain", None)
            assert all(row[c] is None for c in METRIC_COLUMNS)
            checked_infeasible += 1
            continue
        assert row["feasible"] is True and row["failure"] is None
        dyn, ik = result.dynamics, result.ik
        for i, a in enumerate(robot.actuated):
            tau = dyn.tau[:, i]
            assert row[f"peak_tau_{a}"] == np.abs(tau).max()
            assert row[f"peak_power_{a}"] == np.abs(dyn.power[:, i]).max()
            trapezoid = getattr(np, "trapezoid", None) or np.trapz  # numpy < 2: trapz
            rms = math.sqrt(trapezoid(tau**2, ik.t) / (ik.t[-1] - ik.t[0]))
            assert row[f"rms_tau_{a}"] == pytest.approx(rms, rel=2e-14)  # achieves 1.7e-16
            assert 0.0 < row[f"rms_tau_{a}"] <= row[f"peak_tau_{a}"] or row[f"peak_tau_{a}"] == 0
        f = np.linalg.norm(dyn.closure_forces, axis=2).max(0)
        assert (row["peak_force_leg1"], row["peak_force_leg2"]) == (f[0], f[1])
        assert row["min_wrist_margin"] == ik.wrist_margin.min()
        checked_feasible += 1
    assert checked_feasible >= 4 and checked_infeasible >= 2


def test_infeasible_variants_are_rows_not_crashes(pool_rows):
    rows = {r["variant"]: r for r in pool_rows}
    short = rows["short leg 1"]
    assert short["feasible"] is False and short["failure_kind"] == "UnreachablePoseError"
    assert 0 < short["failure_sample"] < SAMPLES and short["failure_chain"] == "leg 1"
    assert short["failure_time"] == pytest.approx(short["failure_sample"] * 20.0 / (SAMPLES - 1),
                                                  rel=1e-14)  # achieves 0

    home = rows["no home"]
    assert home["feasible"] is False and home["failure_kind"] == "ParameterError"
    assert "home pose" in home["failure"] and home["failure_sample"] is None
    assert sum(r["feasible"] for r in pool_rows) >= 4


def test_evaluate_variant_is_pure_and_picklable(sweep):
    spec = sweep.specs()[0]
    assert pickle.loads(pickle.dumps(evaluate_variant)) is evaluate_variant
    again = pickle.loads(pickle.dumps(spec))
    assert evaluate_variant(again) == evaluate_variant(spec)
    assert spec == sweep.specs()[0]  # not mutated
