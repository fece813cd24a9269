"""What paint writes for a panel (outputs/paint_files.py): the table's part columns against an
independent integral."""
import numpy as np

from pollard_pin.outputs.paint_files import panel_table


def test_panel_table_areas_weight_the_film_as_the_trapezoid_rule():
    """Uneven grid steps: the area shares sum to the rectangle (round-off; asserted 1e-12)
    and the area-weighted film is np.trapezoid's double integral (1e-12)."""
    U = np.array([-0.1, -0.07, 0.0, 0.02, 0.1])
    V = np.array([-0.05, 0.0, 0.01, 0.05])
    UU, VV = np.meshgrid(U, V)
    pts = np.stack([np.full_like(UU, 0.7), UU, VV], axis=-1)
    th = (25e-6 * (1 + 0.1 * np.sin(20 * UU) * np.cos(30 * VV))).ravel()
    t = panel_table(U, V, pts, th, np.array([-1.0, 0.0, 0.0]))
    assert list(t) == ["x", "y", "z", "nx", "ny", "nz", "area", "u", "v", "thickness"]
    assert abs(t["area"].sum() / (0.2 * 0.1) - 1) < 1e-12
    brute = np.trapezoid(np.trapezoid(th.reshape(len(V), len(U)), U, axis=1), V)
    assert abs(t["area"] @ th / brute - 1) < 1e-12
    assert (t["nx"] == -1.0).all() and not t["ny"].any() and not t["nz"].any()
    np.testing.assert_array_equal(t["y"], UU.ravel())
