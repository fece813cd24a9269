"""The planners' policy (paint/policy.py): the duration search's first turnaround reverses a
pass at a deceleration set by FIRST_DECELERATION whatever the pass speed, measured on the
panel's raster by finite differences of its along-pass rate."""
import numpy as np
import pytest

from pollard_pin.painting.passes.raster import raster_segments
from pollard_pin.painting.policy import FIRST_DECELERATION, first_guess


@pytest.mark.parametrize("speed", [0.05, 0.33, 1.5])
def test_first_turnaround_reverses_at_the_set_deceleration(speed):
    """The raster's turnaround shape peaks at 3·(2v)/(2τ) = 0.75 × FIRST_DECELERATION at
    τ = first_guess(v), for any v (central differences on 4001 samples: achieved 3e-7
    relative; asserted 1e-4), and reverses the pass rate from +v to −v."""
    tau = first_guess(speed)
    seg = raster_segments([0.0, 0.02], 0.1, speed, tau, (tau, tau))
    k = list(seg.kind).index("turn")
    assert seg.duration[k] == tau
    t = np.linspace(seg.start[k], seg.start[k] + tau, 4001)
    _, _, du, _, _, _ = seg.evaluate(t)
    assert du[0] == pytest.approx(speed, rel=1e-12)
    assert du[-1] == pytest.approx(-speed, rel=1e-12)
    peak = np.abs(np.gradient(du, t)).max()
    assert peak == pytest.approx(0.75 * FIRST_DECELERATION, rel=1e-4)
