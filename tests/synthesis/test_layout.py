"""Where a design's robots stand (synthesis/layout.py; docs/model.md §31.3): the part moved by
a design's place, a job placed for n robots. The placed job against the full evaluation's
robots.toml: test_evaluation.py (its strip fixture)."""
import pytest

import pollard_pin as pp

# the strip of test_evaluation.py: a 0.30 × 0.10 m panel on a 0.03 m/s line
STRIP = {"panel": {"center": [0.70, -0.5, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.30,
                   "height": 0.10},
         "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
         "job": {"thickness": 25e-6}, "line": {"speed": 0.03, "direction": [0.0, 1.0, 0.0]}}


def test_moved_job_moves_the_part_only():
    from pollard_pin.synthesis.layout import moved_job

    panel = pp.job_from_dict(STRIP)
    m = moved_job(panel, [0.3, 0.0, 0.0])
    assert m.center == pytest.approx((1.0, -0.5, 0.16)) and m.normal == panel.normal
    part = pp.load_job("examples/line_part.toml")
    assert moved_job(part, [0.1, 0.0, 0.2]).position == pytest.approx((0.1, -0.75, 0.2))
