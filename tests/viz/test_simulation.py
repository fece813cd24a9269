"""A simulation's figures and report section (viz/simulation.py) from a table made here: the
summary's numbers against the table's, each line the column it names, and a table that is not
a simulation's refused in one line."""
import numpy as np
import pytest

from pollard_pin.dynamics.control import ControlError
from pollard_pin.viz.simulation import (
    FLEXIBLE_FIGURES,
    SIMULATION_FIGURES,
    check_simulation_columns,
    simulation_figures,
    simulation_markdown,
    simulation_summary,
)


def _table(n=201):
    t = np.linspace(0.0, 2.0, n)
    cols = {"t": t, "x": 0.5 + 0.01 * t, "y": 0 * t, "z": 0.2 + 0 * t,
            "desired_x": 0.5 + 0.01 * t, "desired_y": 0 * t, "desired_z": 0.2 + 0 * t,
            "tip_position_error": 1e-4 * np.sin(np.pi * t) ** 2,  # RMS over 2 s: √(3/8)·1e-4
            "tip_orientation_error": 2e-3 * t, "closure_residual": 1e-12 + 0 * t}
    for k, name in enumerate(("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716",
                              "theta1817")):
        cols[f"tau_{name}"] = (k + 1) * 0.1 * np.cos(t)
    return cols


def test_summary_is_the_tables():
    cols = _table()
    s = simulation_summary(cols, {"controller": "pd", "summary": {}})
    assert s["samples"] == 201 and s["duration"] == 2.0
    assert s["settings"] == {"controller": "pd"}
    assert s["max_tip_position_error"] == pytest.approx(1e-4, rel=1e-12)
    # sin⁴ over whole periods: the trapezoid rule is exact to round-off (achieved 1e-16)
    assert s["rms_tip_position_error"] == pytest.approx(1e-4 * np.sqrt(3 / 8), rel=1e-12)
    assert s["max_tip_orientation_error"] == pytest.approx(4e-3, rel=1e-12)
    # ∫₀² (2e-3 t)² dt / 2 = 4e-6·4/3; the trapezoid rule adds h²/12·f'' (achieved 6.3e-6)
    assert s["rms_tip_orientation_error"] == pytest.approx(2e-3 * np.sqrt(4 / 3), rel=1e-3)
    assert s["peak_torque"] == pytest.approx({"theta21": 0.1, "theta21_1": 0.2,
                                              "theta21_2": 0.3, "theta1615": 0.4,
                                              "theta1716": 0.5, "theta1817": 0.6}, rel=1e-12)
    assert s["max_closure_residual"] == 1e-12
    text = "\n".join(simulation_markdown(s))
    assert "Closed-loop simulation" in text and "controller pd" in text


def test_lines_are_the_columns():
    cols = _table()
    figs = simulation_figures(cols)
    assert tuple(figs) == SIMULATION_FIGURES
    seen = {}
    for fig in figs.values():
        for ax in fig.axes:
            for ln in ax.get_lines():
                if ln.get_gid() in cols:
                    seen[ln.get_gid()] = ln
    assert {"tip_position_error", "tau_theta21", "tau_theta1817"} <= set(seen)
    for name, ln in seen.items():
        y = np.asarray(ln.get_ydata(), dtype=float)
        scale = y.max() / cols[name].max() if cols[name].max() else 1.0  # a unit per axis
        assert np.allclose(y, cols[name] * scale, rtol=1e-12, atol=0), name


def test_flexible_drives_add_their_deflections():
    """A table with the motors' columns (docs/model.md §28) adds one figure, whose lines are
    the deflection columns (in mrad)."""
    cols = _table()
    for k, name in enumerate(("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716",
                              "theta1817")):
        cols[f"deflection_{name}"] = (k + 1) * 1e-4 * np.sin(cols["t"])
    figs = simulation_figures(cols)
    assert tuple(figs) == SIMULATION_FIGURES + FLEXIBLE_FIGURES
    lines = {ln.get_gid(): ln for ax in figs["simulation_deflection"].axes
             for ln in ax.get_lines()}
    assert len(lines) == 6
    for name, ln in lines.items():
        assert np.allclose(ln.get_ydata(), 1e3 * cols[name], rtol=1e-15, atol=0), name


@pytest.mark.parametrize("edit, says", [
    (lambda c: c.pop("tip_position_error"), "missing column(s) tip_position_error"),
    (lambda c: [c.pop(k) for k in list(c) if k.startswith("tau_")], "missing column(s) tau_*"),
    (lambda c: c["z"].__setitem__(7, np.nan), "sample 7, column 'z': nan is not finite"),
    (lambda c: c["t"].__setitem__(5, c["t"][4]), "sample 5: time"),
])
def test_not_a_simulation_table(edit, says):
    cols = _table()
    edit(cols)
    with pytest.raises(ControlError) as info:
        check_simulation_columns(cols, "sim.csv")
    assert str(info.value).startswith("sim.csv: ") and says in str(info.value)
    assert "\n" not in str(info.value)
