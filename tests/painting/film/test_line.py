"""The film of a panel on the line, in the part's frame (docs/model.md §24)."""
import numpy as np

from pollard_pin.analytic.taskspace import rotation
from pollard_pin.painting.film.line import line_film
from pollard_pin.painting.line.panel import relative_motion
from pollard_pin.painting.spray.deposition import film, gun_of


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
