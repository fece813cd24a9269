"""What a design study writes (synthesis/result.py): the chosen design's files, read back through
the model's own loaders, the front and every evaluation with units, the plot; all or none."""
import json
import tomllib

import pytest
import synthesis_stub as stub
from synthesis_runs import run_stub, stub_result  # noqa: F401 — the shared study

from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.io.atomic import OutputError
from pollard_pin.model.params import load_params
from pollard_pin.synthesis.result import DESIGN_FILES
from pollard_pin.synthesis.table import read_rows


def test_the_chosen_design_reads_back_through_the_models_loaders(stub_result, tmp_path):  # noqa: F811
    folder = stub_result.write(tmp_path / "out")
    chosen = stub_result.design
    params = load_params(folder / "params.toml")
    assert params.x32 == pytest.approx(chosen["values"]["chain0.x32"])
    assert load_actuators(folder / "actuators.toml")  # the motors every command takes
    cell = (folder / "robots.toml").is_file()
    assert cell == (chosen["values"]["robots"] > 1)
    if cell:
        assert len(tomllib.loads((folder / "robots.toml").read_text())["robot"]) == \
            chosen["values"]["robots"]


def test_front_and_trials_tables_with_units(stub_result, tmp_path):  # noqa: F811
    folder = stub_result.write(tmp_path / "out")
    front, units = read_rows(folder / "front.csv")
    assert [r["design"] for r in front] == list(range(len(stub_result.front) + 1))
    assert front[0]["parts_per_hour"] == pytest.approx(
        stub_result.baseline["objectives"]["parts_per_hour"])  # row 0: the thesis robot
    for row, d in zip(front[1:], stub_result.front):
        assert row["kmin"] == pytest.approx(d["objectives"]["kmin"])
        assert row["motor"] == tuple(stub.MOTORS)[d["values"]["motor"]]  # the choice, shown
    assert units["kmin"] == "N/m" and units["parts_per_hour"] == "1/h"
    assert units["moving_mass"] == "kg" and units["chain0.x32"] == "m"
    assert units["robots"] == "1"  # the objective's, not the variable's
    trials, tunits = read_rows(folder / "trials.parquet")
    assert [r["trial"] for r in trials] == [r["trial"] for r in stub_result.trials]
    assert sum(r["feasible"] for r in trials) == stub_result.feasible
    assert tunits["c_reach"].startswith("1 (≤ 0")
    for r in trials:  # an infeasible design's missing figures are empty, not stand-ins
        if r["level"] == "full" and not r["feasible"]:
            assert r["kmin"] is None
    assert (folder / "front.png").read_bytes()[:4] == b"\x89PNG"
    meta = json.loads((folder / "front.units.json").read_text())["metadata"]
    assert meta["front_resolution"] == {  # the default FrontResolution, said with the front
        "parts_per_hour": {"relative": 0.01}, "robots": {"absolute": 0.0},
        "motor_use": {"absolute": 0.01}, "kmin": {"relative": 0.1},
        "moving_mass": {"relative": 0.02}}


def test_writing_is_all_or_nothing(stub_result, tmp_path):  # noqa: F811
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "front.png").mkdir()  # a folder where the plot goes: the writing fails
    with pytest.raises(OutputError):
        stub_result.write(folder)
    assert sorted(p.name for p in folder.iterdir()) == ["front.png"]
    assert set(DESIGN_FILES) >= set(stub_result.design["files"])


def test_a_one_robot_pick_writes_no_robots_file(tmp_path):
    result = run_stub(None, 30)
    ones = [d["design"] for d in result.front if d["values"]["robots"] == 1]
    assert ones
    picked = run_stub(None, 30, pick=ones[0])
    folder = picked.write(tmp_path / "one")
    assert not (folder / "robots.toml").exists()


def test_variable_units_by_kind_and_name():
    from pollard_pin.synthesis.result import variable_unit
    from pollard_pin.synthesis.space import Variable

    assert [variable_unit(v) for v in (
        Variable("scale.arms", 1.0, 1.8, "float"), Variable("place.back", 0.0, 0.4, "float"),
        Variable("robots", 1, 3, "int"), Variable("motor.base", 0, 4, "categorical", ("a",)),
        Variable("chain0.x32", 0.3, 0.5, "float"))] == [
        "1 (factor)", "m", "1", "choice", "as models/pollard.toml (m, deg)"]
    assert variable_unit(stub.Variable("y", 0, 1, "float", unit="rad")) == "rad"  # its own
