"""The world path of a line plan (paint/line/world.py, plan_world; docs/model.md §24): the
relative program searched, then sampled and checked on the line. Real plans: test_panel.py,
test_part.py, test_phases.py."""
from types import SimpleNamespace

import numpy as np
import pytest

from pollard_pin.painting.line.phases import Relative


def test_a_dwelling_program_out_of_reach_is_judged_per_turnaround(monkeypatch):
    """On a slow line a turnaround is two halves and a wait (dwell.py), three pieces sharing
    one τ: a try whose path leaves the reach is infinite once per τ, as a try in reach is
    (the search compares it with the guess, one entry per τ), and ends as a line speed
    refusal, not a shape error."""
    from pollard_pin.painting.errors import LineSpeedError
    from pollard_pin.painting.line import search, world
    from pollard_pin.painting.line.phases import LineProgram
    from pollard_pin.painting.policy import DEFAULT_POLICY

    kind = ("ramp", "pass", "turn", "wait", "turn", "pass", "ramp")
    start, dur = np.arange(7.0), np.ones(7)

    def motion(t):
        p = np.zeros((len(np.atleast_1d(t)), 6))
        return p, np.zeros_like(p), np.zeros_like(p)

    rel = Relative(motion, start, dur, kind, passes_only=True)
    tried = []

    def fastest(evaluate, guess, utilisation):
        got = evaluate(guess)
        tried.append((len(guess), got.shape))
        raise search.PlanError("no τ")

    def unreachable(*a, **k):
        raise search.ReachError("out of reach", 0)

    monkeypatch.setattr(search, "choose_shift", lambda *a, **k: 0.0)
    monkeypatch.setattr(search, "motion", unreachable)
    monkeypatch.setattr(search, "fastest", fastest)
    program = LineProgram(lambda tau: rel, np.ones(3), 0.01, "track", "2 passes", "job")
    with pytest.raises(LineSpeedError):
        world.plan_world(SimpleNamespace(params=None), None, program, 0.01,
                         np.array([0.0, 1.0, 0.0]), DEFAULT_POLICY)
    assert tried == [(3, (3,))]  # ramp, turn + wait + turn, ramp: 3 τ, not 5 pieces
