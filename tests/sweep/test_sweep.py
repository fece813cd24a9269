"""Design sweeps (pollard_pin.sweep): grid files, per-variant rows equal to individual runs,
infeasible variants as rows, the local process pool and a Dask LocalCluster giving one table."""
import math
import pickle

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.model.names import ACTUATED
from pollard_pin.run import run_pipeline
from pollard_pin.sweep import (
    METRIC_COLUMNS,
    SweepError,
    evaluate_variant,
    load_grid,
    make_sweep,
    run_sweep,
    write_csv,
)

SAMPLES = 201  # the fewest the thesis curve needs without tripping the branch-jump check

GRID = f"""
trajectory = "thesis"
duration = 20.0
samples = {SAMPLES}
[grid]
"chain0.x32" = [0.32, 0.34]
bodies.gun.mass = [0.035, 0.05]    # unquoted dotted key: a nested TOML table, flattened
[[variant]]
name = "short leg 1"               # home reachable, painting curve not: infeasible mid-way
"leg1.x87" = 0.31
[[variant]]
name = "no home"                   # home pose unreachable: invalid parameter set
"leg1.x87" = 0.2
[[variant]]
name = "gun cog"
"bodies.gun.com[0]" = 0.045
"""


@pytest.fixture(scope="module")
def grid_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "grid.toml"
    path.write_text(GRID)
    return path


@pytest.fixture(scope="module")
def sweep(grid_file):
    return load_grid(grid_file)


@pytest.fixture(scope="module")
def pool_rows(sweep):
    return run_sweep(sweep, workers=2)  # the local process pool


def _single_run(overrides):
    """The variant run by hand: load_params(overrides) → load → thesis trajectory → pipeline."""
    params = pp.load_params(overrides=overrides)
    robot = pp.load(params)
    traj = pp.thesis_trajectory(duration=20.0, samples=SAMPLES, home_pose=params.home_pose)
    return robot, run_pipeline(robot, traj)


def test_grid_file_variants_and_columns(sweep):
    names = [n for n, _ in sweep.variants]
    assert names == ["x32=0.32 gun.mass=0.035", "x32=0.32 gun.mass=0.05",
                     "x32=0.34 gun.mass=0.035", "x32=0.34 gun.mass=0.05",
                     "short leg 1", "no home", "gun cog"]
    assert sweep.variants[1][1] == {"chain0.x32": 0.32, "bodies.gun.mass": 0.05}
    assert sweep.keys == ("chain0.x32", "bodies.gun.mass", "leg1.x87", "bodies.gun.com[0]")
    assert sweep.trajectory == {"kind": "thesis", "duration": 20.0, "samples": SAMPLES}
    assert sweep.columns[:5] == ["variant", *sweep.keys]
    assert sweep.columns[-len(METRIC_COLUMNS):] == list(METRIC_COLUMNS)


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
        except (pp.KinematicsError, pp.ParameterError) as exc:
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


def test_serial_equals_pool(sweep, pool_rows):
    assert run_sweep(sweep, workers=1) == pool_rows


def test_spawned_pool_equals_pool(sweep, pool_rows):
    # the start method used in a threaded parent: workers import everything afresh
    assert run_sweep(sweep, workers=2, mp_context="spawn") == pool_rows


def test_example_grid_file_is_valid():
    from pathlib import Path

    s = load_grid(Path(__file__).parents[2] / "examples" / "sweep.toml")
    assert len(s) == 16 and s.trajectory["samples"] == 401


def test_dask_local_cluster_gives_the_pool_table(sweep, pool_rows, tmp_path):
    from distributed import Client, LocalCluster

    # processes=True: real worker processes (spawned by dask's nannies), as on a cluster.
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        rows = run_sweep(sweep, dask=cluster.scheduler_address)  # by address, as the CLI does
        with Client(cluster) as client:
            rows_client = run_sweep(sweep, dask=client)
    assert rows == pool_rows
    assert rows_client == pool_rows
    write_csv(pool_rows, tmp_path / "pool.csv", sweep.columns)
    write_csv(rows, tmp_path / "dask.csv", sweep.columns)
    assert (tmp_path / "pool.csv").read_bytes() == (tmp_path / "dask.csv").read_bytes()


def test_evaluate_variant_is_pure_and_picklable(sweep):
    spec = sweep.specs()[0]
    assert pickle.loads(pickle.dumps(evaluate_variant)) is evaluate_variant
    again = pickle.loads(pickle.dumps(spec))
    assert evaluate_variant(again) == evaluate_variant(spec)
    assert spec == sweep.specs()[0]  # not mutated


def test_csv_trajectory_and_explicit_variants(tmp_path):
    traj = pp.thesis_trajectory(duration=20.0, samples=SAMPLES)
    from pollard_pin.io.trajectory import to_csv

    to_csv(traj, tmp_path / "traj.csv")
    (tmp_path / "g.toml").write_text(
        'trajectory = "traj.csv"\n[[variant]]\nname = "base"\n'
        '[[variant]]\nname = "heavy gun"\n"bodies.gun.mass" = 0.05\n')
    s = load_grid(tmp_path / "g.toml")
    assert s.trajectory["kind"] == "arrays" and s.keys == ("bodies.gun.mass",)
    rows = run_sweep(s, workers=1)
    robot = pp.load(pp.load_params(overrides={"bodies.gun.mass": 0.05}))
    result = run_pipeline(robot, pp.from_csv(tmp_path / "traj.csv"))
    assert rows[1]["peak_tau_theta21"] == np.abs(result.dynamics.tau[:, 0]).max()
    assert rows[0]["bodies.gun.mass"] == pp.load_params().body("gun").mass
    assert rows[1]["bodies.gun.mass"] == 0.05


@pytest.mark.parametrize("text, message", [
    ('[grid]\n"chain0.x99" = [0.3]\n', "'chain0.x99'"),
    ('[grid]\n"chain9.x32" = [0.3]\n', "'chain9.x32'"),
    ('[[variant]]\nname = "a"\n"bodies.gun.masss" = 0.1\n', "'bodies.gun.masss'"),
    ('[grid]\n"chain0.x32" = [0.33, -0.3]\n', "'chain0.x32' = -0.3: must be > 0"),
    ('[grid]\n"bodies.gun.mass" = ["heavy"]\n', "'bodies.gun.mass' = 'heavy': must be a number"),
    ('[grid]\n"home.tip" = [0.55, 0.0, 0.16]\n', "'home.tip' = 0.55: must be a list of 3 numbers"),
    ('[grid]\n"home.tip[3]" = [0.1]\n', "index [3] is out of range"),
    ('[grid]\n"chain0.x32" = 0.33\n', "must be a list of values"),
    ('[grid]\n"chain0.x32" = []\n', "empty list"),
    ('samples = 101\n', "no variants"),
    ('[grid]\n', "no variants"),
    ('sample = 101\n[grid]\n"chain0.x32" = [0.3]\n', "unknown entry 'sample'"),
    ('samples = 1\n[grid]\n"chain0.x32" = [0.3]\n', "samples"),
    ('duration = -1.0\n[grid]\n"chain0.x32" = [0.3]\n', "duration"),
    ('trajectory = "missing.csv"\n[grid]\n"chain0.x32" = [0.3]\n', "missing.csv"),
    ('[[variant]]\nname = "a"\n[[variant]]\nname = "a"\n', "two variants are named 'a'"),
    ('[[variant]]\n"home.tip" = [0.55, 0, 0.16]\n"home.tip[0]" = 0.5\n', "same parameter"),
    ('[grid\n', "not valid TOML"),
])
def test_grid_validation_errors(tmp_path, text, message):
    (tmp_path / "g.toml").write_text(text)
    with pytest.raises(SweepError, match=None) as info:
        load_grid(tmp_path / "g.toml")
    assert message in str(info.value)
    assert str(tmp_path / "g.toml") in str(info.value)


def test_make_sweep_api():
    s = make_sweep(variants=[("base", {}), ("x32", {"chain0.x32": 0.34})], samples=SAMPLES)
    assert [n for n, _ in s.variants] == ["base", "x32"] and s.keys == ("chain0.x32",)
    with pytest.raises(SweepError, match="'duration' and 'samples' apply to the thesis"):
        make_sweep(variants=[("a", {})], trajectory=pp.thesis_trajectory(samples=11), samples=5)


def test_cli_sweep(grid_file, tmp_path, capsys):
    from pollard_pin.cli import main

    out = tmp_path / "sub" / "sweep.csv"
    assert main(["sweep", "--grid", str(grid_file), "--out", str(out), "--workers", "1",
                 "--quiet"]) == 0
    lines = out.read_text().splitlines()
    assert lines[0].startswith("variant,chain0.x32,bodies.gun.mass,leg1.x87,bodies.gun.com[0],"
                               "feasible,failure_kind,failure,")
    assert len(lines) == 8
    text = capsys.readouterr().out
    assert "7 variants: 5 feasible, 2 infeasible" in text
    assert "INFEASIBLE: UnreachablePoseError" in text

    bad = tmp_path / "bad.toml"
    bad.write_text('[grid]\n"chain0.nope" = [1.0]\n')
    assert main(["sweep", "--grid", str(bad), "--out", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err
    assert "'chain0.nope'" in err and "nothing written" in err
    assert not (tmp_path / "x.csv").exists()


def test_a_sweep_over_its_budget_is_refused_before_the_grid_is_built():
    # 10^6 variants: the product was built and the duplicate-name check was quadratic
    # (nothing in 120 s); now one line at once, before any variant exists
    from pollard_pin.sweep.grid import MAX_VARIANTS

    grid = {"chain0.x32": [0.30 + 1e-5 * i for i in range(1000)],
            "bodies.gun.mass": [0.04 + 1e-5 * i for i in range(1000)]}
    with pytest.raises(SweepError, match=r"1e\+06 variants \(1000 × 1000\), budget 1e\+04"):
        make_sweep(grid, samples=SAMPLES)
    many = [(f"v{i}", {}) for i in range(MAX_VARIANTS + 1)]
    with pytest.raises(SweepError, match="more than 1e\\+04 variants"):
        make_sweep(variants=many, samples=SAMPLES)
    with pytest.raises(SweepError, match="two variants are named 'v3'"):
        make_sweep(variants=[*many[:50], ("v3", {})], samples=SAMPLES)
