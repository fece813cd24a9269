"""``pollard-pin simulate`` (cli/simulate.py): bad inputs give one line, exit 2 and write
nothing; the table it writes; plot and report read it back."""
from pathlib import Path

import pytest
from cli_run import run_cli
from thesis_curves import thesis_head

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
MOTORS = EXAMPLES / "actuators.toml"
FIGURE8 = EXAMPLES / "figure8.csv"


@pytest.fixture(scope="module")
def short_csv(tmp_path_factory):
    from pollard_pin.io.trajectory import to_csv

    path = tmp_path_factory.mktemp("sim") / "head.csv"
    to_csv(thesis_head(0.5), path)
    return path


@pytest.mark.parametrize("argv, says", [
    (["--controller", "lqr"], "invalid choice: 'lqr'"),
    (["--wn", "-3"], "must be >= 0, got -3"),
    (["--dt", "0"], "must be > 0, got 0"),
    (["--dt", "100"], "--dt 100 s is longer than --control-period 0.001 s"),
    (["--control-period", "5e-7"], "1,000,000 RK4 steps (0.5 s, --control-period 5e-07 s, "
                                   "--dt 5e-07 s) would take about"),
    (["--dt", "1e-7"], "over the budget of 500,000 steps: give --force"),
    # steps past what a float counts: an OverflowError traceback
    (["--dt", "5e-324"], "inf RK4 steps (0.5 s, --control-period 0.001 s, --dt 4.94066e-324 s): "
                         "more than a simulation can hold (5e+07), even with --force"),
    (["--control-period", "5e-324"], "inf RK4 steps"),
    (["--mass-error", "-2"], "mass error must be a fraction > -1"),
    (["--torque-limit", "1", "2"], "--torque-limit takes 1 value"),
    (["--start", "home"], "trajectory starts off the path"),
    # figure8 starts at home's tool pose but moving: not "off the path"
    (["--start", "home", "--trajectory", str(FIGURE8)], "trajectory starts moving"),
    (["--actuators", str(MOTORS), "--armature", "1"], "do not combine"),
    (["--actuators", "missing.toml"], "does not exist"),
])
def test_cli_bad_inputs_one_line_exit_2_nothing_written(short_csv, tmp_path, capsys, argv,
                                                        says):
    out = tmp_path / "sim.csv"
    code, _, err = run_cli(["simulate", "--trajectory", short_csv, "--out", out, *argv], capsys)
    err = err.strip()
    assert code == 2 and says in err and len(err.splitlines()) == 1, err
    assert not out.exists() and not list(tmp_path.iterdir())


def test_cli_simulate_writes_the_columns(short_csv, tmp_path, capsys):
    from pollard_pin.cli import main
    from pollard_pin.io.table import read_result

    out = tmp_path / "sim.csv"
    assert main(["simulate", "--trajectory", str(short_csv), "--payload", "0.05",
                 "--mass-error", "0.1", "--out", str(out)]) == 0
    table = read_result(out)
    for name in ("t", "theta21", "d_theta43", "dd_theta76_2", "tau_theta1817",
                 "tip_position_error", "tip_orientation_error", "closure_residual"):
        assert name in table.columns
    assert table.units["tip_position_error"] == "m"
    assert len(table) == 51
    summary = table.metadata["summary"]
    assert summary["max_tip_position_error"] == pytest.approx(
        table["tip_position_error"].max(), rel=1e-12)
    assert "tool-tip position error" in capsys.readouterr().out


def test_plot_and_report_show_a_simulation(short_csv, tmp_path, capsys):
    from pollard_pin.cli import main

    sim = tmp_path / "sim.csv"
    assert main(["simulate", "--trajectory", str(short_csv), "--controller", "pd",
                 "--out", str(sim)]) == 0
    assert main(["plot", "--simulation", str(sim), "--out", str(tmp_path / "plots")]) == 0
    assert sorted(p.name for p in (tmp_path / "plots").iterdir()) == [
        "simulation_path.png", "simulation_torques.png", "simulation_tracking.png"]
    md = tmp_path / "report.md"
    assert main(["report", "--trajectory", str(short_csv), "--no-cross-check",
                 "--simulation", str(sim), "--out", str(md)]) == 0
    text = md.read_text()
    assert "## Closed-loop simulation" in text and "controller pd" in text
    capsys.readouterr()
    # Not a simulation table: one line, exit 2.
    assert main(["plot", "--simulation", str(short_csv), "--out", str(tmp_path / "p2")]) == 2
    err = capsys.readouterr().err.strip()
    assert "not a simulation table" in err and len(err.splitlines()) == 1


def _with_stiffness(path):
    """examples/actuators.toml with a 'stiffness' per drive (3e3 N·m/rad base, 1e2 wrist)."""
    lines, table = [], ""
    for line in MOTORS.read_text().splitlines():
        table = line if line.startswith("[") else table
        if not line.startswith("stiffness"):
            lines.append(line)
        if line.startswith("max_speed"):  # the last key of each table
            lines.append(f"stiffness = {3e3 if table.startswith('[theta21') else 1e2}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_cli_flexible_refusals(short_csv, tmp_path, capsys):
    out = tmp_path / "sim.csv"
    bare = tmp_path / "bare.toml"
    bare.write_text("".join(line for line in MOTORS.read_text().splitlines(True)
                            if not line.startswith("stiffness")))
    for argv, says in ((["--flexible"], "--flexible needs --actuators FILE.toml with a "
                                        "'stiffness'"),
                       (["--flexible", "--actuators", bare], "'theta21.stiffness' is missing"),
                       (["--flexible", "--actuators", _with_stiffness(tmp_path / "k.toml"),
                         "--dt", "1e-3"], "too long for the drives' fastest mode")):
        code, _, err = run_cli(["simulate", "--trajectory", short_csv, "--out", out, *argv],
                               capsys)
        err = err.strip()
        assert code == 2 and says in err and len(err.splitlines()) == 1, err
        assert not out.exists()


def test_cli_flexible_writes_the_motors(tmp_path, capsys):
    """The table's motor columns are the API's simulation, same bits; the deflection is the
    motor angle less the joint's."""
    import numpy as np

    import pollard_pin
    from pollard_pin.dynamics.drives.flexible import FlexibleDrives
    from pollard_pin.dynamics.motors import load_actuators
    from pollard_pin.dynamics.tracking import TrackingOptions, simulate_tracking
    from pollard_pin.io.table import read_result
    from pollard_pin.io.trajectory import to_csv

    head = thesis_head(0.05)
    to_csv(head, tmp_path / "head.csv")
    motors = _with_stiffness(tmp_path / "k.toml")
    out = tmp_path / "sim.csv"
    code, stdout, err = run_cli(["simulate", "--trajectory", tmp_path / "head.csv",
                                 "--actuators", motors, "--flexible", "--out", out], capsys)
    assert code == 0, err
    assert "max |φ − q| [rad]" in stdout
    table = read_result(out)
    robot = pollard_pin.load()
    act = load_actuators(motors)
    losses = act.joint_losses(robot.joint_names)
    limit = act.column("gear_ratio") * act.column("peak_torque")
    api = simulate_tracking(robot, head, TrackingOptions(
        known_losses=losses, torque_limit=limit, drives=FlexibleDrives.from_actuators(act)))
    for i, name in enumerate(robot.actuated):
        assert np.array_equal(table[f"phi_{name}"], api.phi[:, i])
        assert np.array_equal(table[f"deflection_{name}"], table[f"phi_{name}"] - table[name])
        assert table.units[f"d_phi_{name}"] == "rad/s"
    assert table.metadata["drives"]["stiffness"] == [3e3] * 3 + [1e2] * 3
