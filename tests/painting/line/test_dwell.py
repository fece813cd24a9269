"""A slow line's dwell (paint/line/dwell.py, docs/model.md §24.1), on a raster whose numbers
are known: the drift brought to 0, the turn's own track run at half pace about a wait at
rest, the pieces joined C², the gun shut while waiting. A slow line planned for real: in
test_panel.py and test_part.py."""
import numpy as np
import pytest

from pollard_pin.painting.line.dwell import (
    drift_along,
    dwell_time,
    dwelled,
    dwelling,
    slow,
    wait_per_turn,
    with_dwell,
)
from pollard_pin.painting.line.phases import LineProgram, Relative
from pollard_pin.painting.passes.raster import raster_segments

E = np.array([0.0, 1.0, 0.0])  # the travel: the passes step along −y, leading end first
OFFSETS = np.array([0.2, 0.15, 0.1, 0.05, 0.0])
SPEED = 0.3  # on the part [m/s]


def build(tau):
    """Passes along z (across the travel), 0.1 m long, stepping along −y."""
    seg = raster_segments(OFFSETS, 0.05, SPEED, tau[1:-1], (tau[0], tau[-1]))

    def motion(t):
        u, v, du, dv, ddu, ddv = seg.evaluate(np.atleast_1d(np.asarray(t, float)))
        z = np.zeros_like(u)
        pose = np.column_stack([z, v, u, z, z, z])
        return pose, np.column_stack([z, dv, du, z, z, z]), np.column_stack(
            [z, ddv, ddu, z, z, z])

    return Relative(motion, seg.start, seg.duration, seg.kind, program=seg)


TAU = np.full(len(OFFSETS) + 1, 0.12)


def test_the_drift_is_zero_at_the_wait():
    base = build(TAU)
    pace = 0.2 / base.total  # the stepped length over the program time: no drift
    assert abs(drift_along(base, pace, E)) < 1e-12
    s = 0.2 * pace
    assert slow(base, s, E) and not slow(base, 2 * pace, E)
    w = wait_per_turn(base, s, E)
    rel = dwelled(build, s, E)(TAU)
    turns = len(OFFSETS) - 1
    # each turn run at half pace (its τ again) plus the wait: s·T' = the stepped 0.2 m
    assert rel.total == pytest.approx(base.total + turns * (0.12 + w), rel=1e-12)
    assert rel.total == pytest.approx(0.2 / s, rel=1e-12)
    assert abs(drift_along(rel, s, E)) < 1e-12
    assert dwell_time(rel) == pytest.approx(turns * w, rel=1e-12)
    assert wait_per_turn(base, 2 * pace, E) == 0.0  # a fast line: no wait


def test_the_turn_keeps_its_track_and_stops_for_the_wait():
    base = build(TAU)
    rel = with_dwell(base, 0.5)
    k = rel.kind.index("turn")
    assert rel.kind[k:k + 3] == ("turn", "wait", "turn")
    tb = base.start[base.kind.index("turn")]
    x = np.linspace(0.0, 1.0, 11)
    # first half: σ = τ(x − x³ + x⁴/2), an independent statement of RAMP_OUT
    p, v, _ = rel.evaluate(rel.start[k] + 0.12 * x)
    q, _, _ = base.evaluate(tb + 0.12 * (x - x ** 3 + x ** 4 / 2))
    assert np.abs(p - q).max() < 1e-12
    p, v, a = rel.evaluate(rel.start[k + 1] + np.linspace(0, 0.5, 7))  # the wait: at rest
    mid, _, _ = base.evaluate(np.array([tb + 0.06]))
    assert np.abs(p - mid).max() < 1e-12 and np.abs(v).max() == 0 and np.abs(a).max() == 0
    # second half: σ = τ/2 + τ(x³ − x⁴/2)
    p, _, _ = rel.evaluate(rel.start[k + 2] + 0.12 * x)
    q, _, _ = base.evaluate(tb + 0.06 + 0.12 * (x ** 3 - x ** 4 / 2))
    assert np.abs(p - q).max() < 1e-12


def test_the_pieces_join_c2():
    rel = with_dwell(build(TAU), 0.5)
    eps = 1e-7
    inner = rel.start[1:]
    before = rel.evaluate(inner - eps)
    after = rel.evaluate(inner + eps)
    peak = [np.abs(x).max() for x in rel.evaluate(np.linspace(0, rel.total, 4001))]
    for b, a, top in zip(before, after, peak):
        assert np.abs(b - a).max() < 1e-4 * top  # jerk·2ε ≈ 1e-6 of it


def test_the_gun_is_shut_while_waiting():
    rel = with_dwell(build(TAU), 0.5)  # a panel's relative: the gun open throughout
    mid = rel.start + rel.duration / 2
    on = rel.trigger(mid)
    assert list(on) == [0.0 if k == "wait" else 1.0 for k in rel.kind]
    b = build(TAU)
    parts = with_dwell(Relative(b.motion, b.start, b.duration, b.kind, passes_only=True), 0.5)
    assert list(parts.trigger(parts.start + parts.duration / 2)) == [
        1.0 if k == "pass" else 0.0 for k in parts.kind]


def test_a_zones_windows_follow_the_turns():
    """A cell robot's relative (docs/model.md §26.3): each turn half keeps its turn's
    window, the wait is shut, the seams (switches inside a pass) stay where they were."""
    from pollard_pin.painting.cell.zones import CLOSED, OPEN, ZoneRelative

    b = build(TAU)
    wins = tuple((0.05, 0.2) if k == "pass" else (OPEN if i == 2 else CLOSED)
                 for i, k in enumerate(b.kind))
    z = ZoneRelative(b.motion, b.start, b.duration, b.kind, program=b.program, windows=wins)
    d = with_dwell(z, 0.5)
    assert isinstance(d, ZoneRelative)
    assert all(w == CLOSED for k, w in zip(d.kind, d.windows) if k == "wait")
    halves = [w for k, w in zip(d.kind, d.windows) if k == "turn"]
    turns = [w for k, w in zip(b.kind, wins) if k == "turn"]
    assert halves == [w for w in turns for _ in (0, 1)]
    # the seams: the same local times in the same passes
    pb = [s for s, k in zip(b.start, b.kind) if k == "pass"]
    pd = [s for s, k in zip(d.start, d.kind) if k == "pass"]
    assert np.allclose(d.seam_times() - np.repeat(pd, 2), z.seam_times() - np.repeat(pb, 2))
    mid = d.start + d.duration / 2
    assert list(d.trigger(mid)) == [0.0 if k == "wait" else float(
        w[0] <= dd / 2 <= w[1]) for k, w, dd in zip(d.kind, d.windows, d.duration)]


def test_only_a_slow_line_dwells(monkeypatch):
    """At or above the strokes' pace the program is planned as it is; below it, as it is
    unless that fails as too slow, then with the waits (what planned before the waits plans
    as it did, docs/model.md §24.1).
    Every turnaround durations the motors' search tries get their own wait."""
    from pollard_pin.painting.errors import LineSpeedError
    from pollard_pin.painting.line import dwell

    program = LineProgram(build, TAU, 0.002, "track", "passes", "<test>")
    pace = 0.2 / build(TAU).total
    tried = []

    def plan_world(robot, act, prog, speed, e, policy, screen=False):
        waits = prog.build(prog.guess).kind.count("wait")
        # only the first try of a slow line, whose failure says no more than its side, is
        # screened (plan_world's motors at the path's own samples first)
        assert screen == (waits == 0 and speed < pace)
        tried.append(waits)
        if waits == 0 and fail:
            raise LineSpeedError("drifts back", False, "", 0.5)
        return waits

    monkeypatch.setattr(dwell, "plan_world", plan_world)
    fail = True
    with pytest.raises(LineSpeedError):  # not slow: as it is, its failure its own
        dwell.plan_dwelling(None, None, program, 1.01 * pace, E)
    assert tried == [0]
    tried.clear()
    assert wait_per_turn(build(TAU), 0.5 * pace, E) > 0
    assert dwell.plan_dwelling(None, None, program, 0.5 * pace, E) == 4 and tried == [0, 4]
    tried.clear()
    s = 0.99 * pace  # slow, but the half-paced turns absorb it: no wait of its own
    assert wait_per_turn(build(TAU), s, E) == 0
    assert dwell.plan_dwelling(None, None, program, s, E) == 4 and tried == [0, 4]
    tried.clear()
    fail = False
    assert dwell.plan_dwelling(None, None, program, s, E) == 0 and tried == [0]
    tried.clear()
    assert dwell.plan_dwelling(None, None, program, 0.5 * pace, E) == 0 and tried == [0]
    slow_one = dwelling(program, 0.5 * pace, E)
    for tau in (TAU, 0.5 * TAU, 2 * TAU):
        rel = slow_one.build(tau)
        assert rel.kind.count("wait") == len(OFFSETS) - 1
        assert abs(drift_along(rel, 0.5 * pace, E)) < 1e-12


def test_just_below_the_pace_the_turns_add_only_what_the_line_needs():
    """At 0.99 of the pace the line needs less than the half-paced turns' own τ each: the
    turns wait 0 and their rate dips only to c = (τ − x)/(τ + x) (docs/model.md §24.1), so
    the drift is 0, not the half-paced turns' surplus (before: +n·τ·s − |drift|)."""
    from pollard_pin.painting.line.dwell import turn_timing

    base = build(TAU)
    pace = 0.2 / base.total
    s = 0.99 * pace
    x = -drift_along(base, s, E) / s / (len(OFFSETS) - 1)  # each turn's share, by hand
    assert 0 < x < 0.12
    waits, dips = turn_timing(base, s, E)
    assert np.all(waits == 0.0)
    assert dips == pytest.approx(np.full(len(OFFSETS) - 1, (0.12 - x) / (0.12 + x)),
                                 rel=1e-12)
    rel = dwelled(build, s, E)(TAU)
    assert abs(drift_along(rel, s, E)) < 1e-12
    assert rel.total == pytest.approx(0.2 / s, rel=1e-12)
    assert dwell_time(rel) == 0.0
    half = with_dwell(base, 0.0)  # half-paced with no wait: the surplus the dip avoids
    assert drift_along(half, s, E) > 0.1 * s * 0.12
    # far below the pace the turns stop and wait, as before
    w, d = turn_timing(base, 0.5 * pace, E)
    assert np.all(d == 0) and np.all(w == wait_per_turn(base, 0.5 * pace, E)) and w[0] > 0


def test_a_dipped_turn_keeps_its_track_and_joins_c2():
    base = build(TAU)
    c = 0.4
    rel = with_dwell(base, 0.0, c)
    k = rel.kind.index("turn")
    h = 0.12 / (1 + c)
    assert rel.duration[k] == pytest.approx(h) and rel.duration[k + 1] == 0.0
    tb = base.start[base.kind.index("turn")]
    x = np.linspace(0.0, 1.0, 11)
    S = x ** 3 - x ** 4 / 2  # ∫ smoothstep, independently
    p, _, _ = rel.evaluate(rel.start[k] + h * x)
    q, _, _ = base.evaluate(tb + h * (x - (1 - c) * S))
    assert np.abs(p - q).max() < 1e-12
    p, _, _ = rel.evaluate(rel.start[k + 2] + h * x)
    q, _, _ = base.evaluate(tb + 0.06 + h * (c * x + (1 - c) * S))
    assert np.abs(p - q).max() < 1e-12
    # the halves meet the turn's middle at rate c relative to the part, and join C²
    _, vb, _ = base.evaluate(np.array([tb + 0.06]))
    _, v, _ = rel.evaluate(np.array([rel.start[k + 2]]))
    assert np.abs(v - c * vb).max() < 1e-12
    eps = 1e-7
    before, after = rel.evaluate(rel.start[1:] - eps), rel.evaluate(rel.start[1:] + eps)
    peak = [np.abs(y).max() for y in rel.evaluate(np.linspace(0, rel.total, 4001))]
    for b, a, top in zip(before, after, peak):
        assert np.abs(b - a).max() < 1e-4 * top
