"""Notes of a line plan's searches (paint/line/notes.py, docs/model.md §31.5): kept only within
plan_notes, by a fingerprint of what the search reads (not the checks' fidelity), a noted
refusal raised again in its words. That the plan made again from the notes is the plan from
scratch, to the bit: tests/synthesis/test_evaluation.py (a design's exact evaluation)."""
import json
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from pollard_pin.painting.errors import LineReachError, LineSpeedError
from pollard_pin.painting.line.notes import fingerprint, noted, plan_notes
from pollard_pin.painting.line.phases import LineProgram, Relative
from pollard_pin.painting.policy import PlannerPolicy


def _inputs(speed=0.012, shape=1.0, gravity=-9.81, peak=0.05):
    """(robot, act, program, rel, speed, e, policy, screen) stand-ins: a ramp, a pass and a
    ramp whose motion is ``shape``·t along x."""
    robot = SimpleNamespace(params=("arms", 0.33), model=SimpleNamespace(
        gravity=SimpleNamespace(linear=np.array([0.0, 0.0, gravity]))))
    act = SimpleNamespace(units=(("peak_torque", peak),))

    def motion(t):
        p = np.zeros((len(t), 6))
        p[:, 0] = shape * t
        return p, np.ones_like(p) * shape, np.zeros_like(p)

    rel = Relative(motion, np.array([0.0, 1.0, 3.0]), np.array([1.0, 2.0, 1.0]),
                   ("ramp", "pass", "ramp"))
    program = LineProgram(lambda tau: rel, np.array([0.5, 0.5]), 0.01, "here", "the passes",
                          "job.toml")
    return robot, act, program, rel, speed, np.array([0.0, 1.0, 0.0]), PlannerPolicy(), True


def test_only_within_plan_notes_a_search_is_kept_and_taken():
    calls = []

    def search():
        calls.append(1)
        return {"tau": [0.25, 0.5], "delay": 3.0, "back": 1.5}

    args = _inputs()
    assert noted(search, *args) == noted(search, *args) and len(calls) == 2  # none kept
    with plan_notes() as notes:
        first = noted(search, *args)
        assert noted(search, *args) == first and len(calls) == 3  # taken, not searched
    assert list(notes.values()) == [first]
    stored = json.loads(json.dumps(notes))  # plain data: as a study stores it
    with plan_notes(stored) as again:
        assert noted(search, *args) == first and len(calls) == 3 and again is stored


def test_the_fingerprint_is_what_the_search_reads_not_the_checks_fidelity():
    base = _inputs()
    key = fingerprint(*base)
    checks = replace(base[6], check_refine=1, clearance_stride=4, name_speeds=False)
    assert fingerprint(*base[:6], checks, base[7]) == key
    others = [_inputs(speed=0.013), _inputs(shape=1.0 + 1e-12), _inputs(gravity=-9.8),
              _inputs(peak=0.06)]
    utilisation = (*base[:6], replace(base[6], utilisation=0.9), base[7])
    keys = {fingerprint(*a) for a in [*others, utilisation, (*base[:7], False)]}
    assert key not in keys and len(keys) == 6


def test_a_noted_refusal_is_raised_again_in_its_words():
    args = _inputs()

    def refuse():
        raise LineSpeedError("at line speed 0.012 m/s the program drifts", False, "drifts",
                             0.0125)

    with plan_notes() as notes:
        with pytest.raises(LineSpeedError):
            noted(refuse, *args)
        with pytest.raises(LineSpeedError) as again:
            noted(lambda: pytest.fail("searched again"), *args)
    e = again.value
    assert (str(e), e.too_fast, e.why, e.hint) == ("at line speed 0.012 m/s the program "
                                                   "drifts", False, "drifts", 0.0125)
    # any other refusal is not noted: searched again, raising as it does
    with plan_notes() as notes:
        for _ in range(2):
            with pytest.raises(LineReachError):
                noted(lambda: (_ for _ in ()).throw(LineReachError("a pass out of reach")),
                      *args)
    assert notes == {}
