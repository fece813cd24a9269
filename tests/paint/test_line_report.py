"""The film of a panel on the line, in the part's frame, and paint.json's line table
(docs/model.md §24)."""
import numpy as np
import pytest

from pollard_pin.analytic.taskspace import rotation
from pollard_pin.paint.deposition import film, gun_of
from pollard_pin.paint.line import relative_motion
from pollard_pin.paint.line_report import line_film, line_table


def test_film_in_the_parts_frame(line_plan):
    """Moving the part and the gun by the same motion gives the film of the relative motion
    over a still part (docs/model.md §24), to 1e-12."""
    p = line_plan
    U, V, pts, f = line_film(p, p.job.sigma)
    tr = p.trajectory
    on = p.spray > 0
    rel, _, _ = relative_motion(p.frame, p.job, p.segments, p.horizontal,
                                tr.t[on] - p.times.delay)
    still = film(gun_of(p.job), tr.t[on] - p.times.delay, rel[:, :3],
                 rotation(rel)[:, :, 0], pts.reshape(-1, 3), p.frame.n, origin=p.frame.c)
    assert np.abs(f.thickness - still.thickness).max() <= 1e-12 * p.job.thickness
    # and the film is the target's: ≥ 99 % within ±5 %, all within ±10 %
    dev = np.abs(f.thickness / p.job.thickness - 1)
    assert np.mean(dev <= 0.05) >= 0.99 and dev.max() <= 0.10


def test_line_table_numbers(line_plan):
    t = line_table(line_plan)
    assert t["cycle"] == pytest.approx(line_plan.trajectory.t[-1])
    assert t["min_pitch"] == pytest.approx(line_plan.speed * t["cycle"], rel=1e-15)
    assert t["parts_per_hour"] == pytest.approx(3600 / t["cycle"], rel=1e-15)
    j = line_plan.job
    assert t["upper_bound"] == pytest.approx((0.9 + t["window_length"]) / (
        0.9 * 0.1 * j.thickness / j.flow), rel=1e-12)
    # the window: the world interval the sprayed tips span along the line
    on = line_plan.spray > 0
    y = line_plan.trajectory.poses[on, 1]
    assert t["window"] == [y.min(), y.max()]
    assert line_plan.speed < t["upper_bound"]


