"""The line planner's pre-check search (paint/line/search.py; docs/model.md §24): where the
part can be on the line at all (choose_shift), the searched turnarounds, delay and return. Its
scan of shifts: test_shifts.py; the plans it serves: test_phases.py, test_panel.py."""
from types import SimpleNamespace

import numpy as np
import pytest

from pollard_pin.painting.line.phases import Relative


def test_turnarounds_never_in_reach_are_no_line_speed(monkeypatch):
    """A program whose passes are in reach but some of whose turnarounds (or ramps) are at no
    place on the line (a cell robot's turns past its seam, examples/cell_curved.toml) is
    refused as a plan naming them, not as a line speed (no drift would help): a reach that
    ends at z = −0.04 m, passes down to −0.03 m, the turn after the first pass and the
    first ramp dipping to −0.05 m."""
    from pollard_pin.painting.errors import LineSpeedError, PlanError
    from pollard_pin.painting.line import search

    start, dur = np.arange(7.0), np.ones(7)
    kind = ("ramp", "pass", "turn", "pass", "turn", "pass", "ramp")
    low = {0: -0.05, 2: -0.05, 4: 0.2, 6: 0.2}  # each piece's z off the passes

    def motion(t):
        k = np.clip(np.floor(np.asarray(t, float)).astype(int), 0, 6)
        p = np.zeros((len(k), 6))
        p[:, 1] = -0.02 * k  # stepping against the travel
        p[:, 2] = [low.get(int(j), -0.03) for j in k]
        return p, np.zeros_like(p), np.zeros_like(p)

    rel = Relative(motion, start, dur, kind, passes_only=True)
    ROBOT = SimpleNamespace(params=None)  # noqa: N806 (the reach is the fake's below)
    judged = []

    def reachable(robot, poses):
        judged.append(poses.shape)
        return (np.asarray(poses)[..., 2] > -0.04).all(axis=-1)

    monkeypatch.setattr(search, "feasible_shifts", lambda *a, **k: None)
    monkeypatch.setattr(search, "unreachable_passes", lambda robot, rel, e, lo, hi: ([], 3))
    monkeypatch.setattr(search, "reachable_sequences", reachable)
    monkeypatch.setattr(search, "ball_shift_range", lambda params, points, e: (-0.1, 0.1))
    e = np.array([0.0, 1.0, 0.0])
    with pytest.raises(PlanError) as err:
        search.choose_shift(ROBOT, rel, 0.01, e, "track")
    assert not isinstance(err.value, LineSpeedError)
    assert "keeps 1 of its 2 turnarounds and its first ramp in reach" in str(err.value)
    assert judged and all(s[1:] == (1, 6) for s in judged)  # each sample judged alone
    low[0] = low[2] = 0.2  # all in reach: the drift's failure, as before
    with pytest.raises(LineSpeedError):
        search.choose_shift(ROBOT, rel, 0.01, e, "track")
