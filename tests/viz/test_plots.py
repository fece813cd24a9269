"""The figures (viz/plots.py): they carry the run's arrays. (The command:
tests/cli/test_plot.py; the report: tests/viz/test_report.py.)"""
import csv
from pathlib import Path

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.cli import main
from pollard_pin.run import run_pipeline
from pollard_pin.viz.plots import FIGURES, figures

SAMPLES = 401
ARGS = ["--samples", str(SAMPLES), "--quiet"]
ACTUATED = ("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716", "theta1817")


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=float)
    return {h: data[:, i] for i, h in enumerate(rows[0])}


@pytest.fixture(scope="module")
def robot():
    return pp.load()


@pytest.fixture(scope="module")
def result(robot):
    return run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES))


@pytest.fixture(scope="module")
def run_csv(tmp_path_factory):
    """The ``run`` command's CSV for the same trajectory."""
    path = tmp_path_factory.mktemp("run") / "run.csv"
    assert main(["run", *ARGS, "--out", str(path)]) == 0
    return read_csv(path)


# --- plots ---------------------------------------------------------------------------------
def test_a_failed_figure_leaves_the_existing_png(result, tmp_path, monkeypatch):
    # savefig wrote straight into the PNG: a failure half-way left a truncated figure
    import matplotlib.figure

    from pollard_pin.viz.plots import write_figures

    old = tmp_path / f"{FIGURES[0]}.png"
    old.write_bytes(b"precious")

    def broken_savefig(fig, target, **kw):  # to a path or into a file object
        with open(target, "wb") if isinstance(target, (str, Path)) else target as f:
            f.write(b"\x89PNG half")
        raise OSError("disk full")

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", broken_savefig)
    with pytest.raises(OSError, match="disk full"):
        write_figures(result, tmp_path, dpi=20)
    assert [p.name for p in tmp_path.iterdir()] == [old.name]
    assert old.read_bytes() == b"precious"


def _scale(ylabel):
    return np.degrees(1.0) if "[deg" in ylabel else 1.0


def test_figures_plot_the_run_arrays(result, run_csv):
    import matplotlib.pyplot as plt

    figs = figures(result)
    assert tuple(figs) == FIGURES
    seen = set()
    try:
        for name, fig in figs.items():
            assert fig._suptitle is not None or any(ax.get_title() for ax in fig.axes), name
            for ax in fig.axes:
                lines = [ln for ln in ax.get_lines() if ln.get_gid()]
                assert lines, f"{name}: an axes without data"
                assert ax.get_title(), f"{name}: untitled axes"
                assert "[" in ax.get_ylabel() or name == "tool_path", (name, ax.get_ylabel())
                assert ax.get_legend() is not None, f"{name}: no legend"
                if name != "tool_path":
                    assert ax.get_xlabel() in ("", "t [s]")
                for ln in lines:
                    gid = ln.get_gid()
                    if name == "tool_path":
                        x, y, z = ln.get_data_3d()
                        for arr, col in ((x, "x"), (y, "y"), (z, "z")):
                            np.testing.assert_allclose(arr, run_csv[col], rtol=0, atol=1e-15)
                        seen.add(gid)
                        continue
                    x, y = ln.get_data()
                    np.testing.assert_allclose(x, run_csv["t"], rtol=0, atol=1e-15)
                    if gid.startswith("|"):  # force magnitude
                        i = gid[2]
                        ref = np.sqrt(sum(run_csv[f"f{i}_{c}"] ** 2 for c in "xyz"))
                    else:
                        ref = run_csv[gid] * _scale(ax.get_ylabel())
                    np.testing.assert_allclose(y, ref, rtol=1e-12, atol=1e-12,
                                               err_msg=f"{name}: {gid}")
                    seen.add(gid)
            if name == "tool_path":
                assert fig.axes[0].get_zlabel() == "z [m]"
    finally:
        for fig in figs.values():
            plt.close(fig)
    # Everything asked of the plots is on some figure.
    tree = ["theta21", "theta43", "theta54", "theta1615", "theta1716", "theta1817"] + [
        f"{n}_{i}" for i in (1, 2) for n in ("theta21", "theta65", "theta76")]
    wanted = {p + j for j in tree for p in ("", "d_", "dd_")}
    wanted |= {f"{p}_{n}" for p in ("tau", "power", "work") for n in ACTUATED}
    wanted |= {f"f{i}_{c}" for i in (1, 2) for c in "xyz"} | {"|f1|", "|f2|"}
    wanted |= {"wrist_margin", "sigma_parallel", "sigma_serial", "tool_path"}
    assert wanted <= seen, sorted(wanted - seen)


def test_figures_need_dynamics(robot):
    res = run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES), dynamics=False)
    with pytest.raises(ValueError, match="dynamics"):
        figures(res)


def test_write_figures_refuses_before_making_the_folder(robot, tmp_path):
    """No dynamics, or no run's result at all: one InputError line and no folder made."""
    res = run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES), dynamics=False)
    for result, says in ((res, "plots need the dynamics"),
                         ("x", "^result = 'x': expected a RunResult")):
        with pytest.raises(pp.InputError, match=says):
            pp.write_figures(result, tmp_path / "plots")
        assert not (tmp_path / "plots").exists()
