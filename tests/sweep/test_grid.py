"""Sweep grids (sweep/grid.py): grid files and the sweep API that makes them. (Rows:
tests/sweep/test_evaluate.py; where they run: test_backends.py; the table: test_table.py.)"""
import numpy as np
import pytest
from sweep_grid import SAMPLES

import pollard_pin as pp
from pollard_pin.run import run_pipeline
from pollard_pin.sweep import (
    METRIC_COLUMNS,
    SweepError,
    load_grid,
    make_sweep,
    run_sweep,
)


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


def test_example_grid_file_is_valid():
    from pathlib import Path

    s = load_grid(Path(__file__).parents[2] / "examples" / "sweep.toml")
    assert len(s) == 16 and s.trajectory["samples"] == 401


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


def test_load_grid_refuses_what_names_no_file():
    with pytest.raises(pp.InputError, match=r"^path = 3: expected a file path \(str or "):
        pp.load_grid(3)


@pytest.mark.parametrize("grid", ["abc", [("x32", [0.3])]])
def test_make_sweep_refuses_a_grid_that_is_no_mapping(grid):
    with pytest.raises(pp.InputError, match="^grid = .*: expected a mapping of parameter keys"):
        pp.make_sweep(grid)
