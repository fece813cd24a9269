"""Passes out of reach on the line (paint/line/reach.py, docs/model.md §24): a part taller
than the reach is refused in one line naming the passes and the excess in mm, before any
line speed is searched; the excess checked against the planner's own reach check."""
import numpy as np
import pytest
from line_parts import LINE_PART_TOML

from pollard_pin.painting.checks.motion import reach
from pollard_pin.painting.errors import PlanError, ReachError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.line import phases, search, speeds
from pollard_pin.painting.line.panel import plan_line_job
from pollard_pin.painting.line.reach import PASS_SAMPLES, numbers, unreachable_passes
from pollard_pin.painting.line.shifts import SHIFT_RANGE
from pollard_pin.painting.workpiece import shapes


def tall_job(folder, height: float):
    """A 0.30 m wide strip (radius 3 m) ``height`` tall on the test line (0.03 m/s along
    +y, tests/line_parts.py)."""
    shapes.curved_panel(radius=3.0, width=0.30, height=height, step=0.01).export(
        folder / "strip.stl")
    (folder / "job.toml").write_text(LINE_PART_TOML)
    return load_job(folder / "job.toml")


@pytest.fixture
def no_search(monkeypatch):
    """Any speed search fails the test: the refusal must come from the first plan."""
    def search(*args, **kwargs):
        raise AssertionError("a line speed was searched")

    monkeypatch.setattr(speeds, "fastest_line_speed", search)
    monkeypatch.setattr(speeds, "line_speed_interval", search)


@pytest.mark.parametrize("height, words", [(0.5, "mm too tall for the reach"),
                                           (0.3, "its top ")])
def test_too_tall_is_refused_before_any_search(robot, act, tmp_path, no_search, height,
                                               words):
    job = tall_job(tmp_path, height)
    with pytest.raises(PlanError) as info:
        plan_line_job(robot, job, act)
    msg = str(info.value)
    assert len(msg) <= 250 and "\n" not in msg, msg
    assert msg.startswith("all 19 passes out of reach at any place on the line: pass "), msg
    assert words in msg
    # the pass: the strip's height and the run-on, as planned
    length = float(msg.split(" is ")[1].split(" m ")[0])
    assert height < length < height + 0.1
    covered = float(msg.split("at most ")[1].split(" m ")[0])
    excess_mm = float(msg.split(" mm")[0].split()[-1])
    assert excess_mm == pytest.approx(1000 * (length - covered), abs=1.0)  # printed to mm


def relative_program(robot, job, act):
    """The relative program the line planner builds for ``job`` (its first ``build``)."""
    seen = {}
    real = search.choose_shift

    def spy(robot_, rel, *args):
        seen.setdefault("rel", rel)
        return real(robot_, rel, *args)

    search.choose_shift = spy
    try:
        with pytest.raises(PlanError):
            plan_line_job(robot, job, act)
    finally:
        search.choose_shift = real
    return seen["rel"]


def test_excess_against_the_planners_reach(robot, act, tmp_path):
    """The stretch reported in reach fits at some shift by the planner's IK check, and two
    samples more never does (shifts at 5 mm over the planner's 2 m of travel)."""
    job = tall_job(tmp_path, 0.3)
    rel = relative_program(robot, job, act)
    e = np.asarray(job.line.direction)
    lo = job.line.speed * phases.CATCH
    bad, n = unreachable_passes(robot, rel, e, lo, lo + SHIFT_RANGE)
    assert n == 19 and len(bad) == 19
    worst = max(bad, key=lambda b: b.excess)
    assert worst.side() == "top" and worst.ends[0] == 0.0
    k = [i for i, kind in enumerate(rel.kind) if kind == "pass"][worst.number - 1]
    u = np.linspace(0.0, 1.0, PASS_SAMPLES)
    poses = rel.evaluate(rel.start[k] + rel.duration[k] * u)[0]
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(poses[:, :3], axis=0),
                                                          axis=1))])
    assert arc[-1] == pytest.approx(worst.length, rel=1e-12)
    m = int(np.argmin(np.abs(arc - worst.covered)))  # the last sample in reach
    assert poses[m, 2] < poses[-1, 2]  # from the bottom up

    def fits_somewhere(p):
        for x in np.arange(lo, lo + SHIFT_RANGE, 0.005):
            q = p.copy()
            q[:, :3] += x * e
            try:
                reach(robot, q)
            except ReachError:
                continue
            return True
        return False

    assert fits_somewhere(poses[:m + 1])
    assert not fits_somewhere(poses[:m + 3])


def test_numbers_are_ranges():
    from pollard_pin.painting.line.reach import PassReach

    def passes(*nums):
        return [PassReach(k, 1.0, 0.5, (0.5, 0.0), 1.0, (0.0, 0.0, 0.0)) for k in nums]

    assert numbers(passes(3, 4, 5, 9, 11, 12)) == "3–5, 9, 11–12"
    assert numbers(passes(1, 3, 5, 7, 9)) == "1, 3, 5, 7, …"


def test_many_passes_keep_to_the_pose_budget(robot, monkeypatch):
    """1000 vertical passes 1 mm apart: the shift grid coarsens so that at most MAX_POSES
    poses are tried, and each pass is still judged (here: all in reach somewhere)."""
    from pollard_pin.painting.line import reach as reach_mod
    from pollard_pin.painting.line.phases import Relative

    n = 1000
    kind = ("ramp",) + ("pass", "turn") * (n - 1) + ("pass", "ramp")
    start = np.arange(len(kind), dtype=float)
    home = np.asarray(robot.params.home_pose, float)

    def motion(t):
        i = np.clip(np.ceil(t) - 1, 0, None)  # piece i holds t ∈ (i, i + 1]
        p = np.tile(home, (len(t), 1))
        p[:, 1] += -0.001 * (i // 2)  # levels along −y, the line along +y
        p[:, 2] += 0.02 * (t - i) - 0.01  # a 20 mm vertical pass
        return p, np.zeros_like(p), np.zeros_like(p)

    rel = Relative(motion, start, np.ones(len(kind)), kind)
    tried = []
    real = reach_mod.evaluate
    monkeypatch.setattr(reach_mod, "evaluate",
                        lambda r, poses: tried.append(len(poses)) or real(r, poses))
    bad, total = unreachable_passes(robot, rel, np.array([0.0, 1.0, 0.0]), 0.0, 2.0)
    assert total == n and sum(tried) <= reach_mod.MAX_POSES
    assert bad == []  # each 20 mm pass round home fits at some shift


def test_out_of_reach_says_why():
    from pollard_pin.painting.line.reach import PassReach, out_of_reach

    mid = (0.7, -0.9, 0.16)
    top = PassReach(1, 0.36, 0.29, (0.0, 0.07), 0.36, mid)  # rising: its end is the top
    both = PassReach(2, 0.50, 0.30, (0.10, 0.10), -0.50, mid)
    never = PassReach(3, 0.20, 0.0, (0.20, 0.20), 0.20, mid)
    one = PassReach(4, 0.20, 0.0, (0.05, 0.15), 0.20, mid)  # one sample in reach
    head = " out of reach at any place on the line: "
    assert out_of_reach([top], 9) == ("pass 1 of 9" + head + "pass 1 is 0.360 m (run-on "
                                      "included), at most 0.290 m of it in reach, its top 70 "
                                      "mm out")
    assert out_of_reach([top, both], 2).startswith("all 2 passes" + head + "pass 2 is 0.500")
    assert out_of_reach([top, both], 2).endswith("200 mm too tall for the reach")
    assert out_of_reach([top, never, one], 5) == (
        "passes 1, 3–4 of 5" + head + "no part of pass 3 (0.200 m, its middle at (0.700, "
        "-0.900, 0.160) m at t = 0) is ever in reach")
    assert not one.nowhere and one.side() == "both ends"


@pytest.mark.parametrize("coarsest", [1, 2, 16])
def test_coarse_to_fine_tries_every_index_once(coarsest):
    """The scans' rounds (unreachable_passes, the turnarounds’ reach in search.py): every
    index of 0..n−1 exactly once, every ``coarsest``-th in the first round, each round's
    indices the middles of the gaps the rounds before left."""
    from pollard_pin.painting.line.reach import coarse_to_fine

    for n in list(range(0, 40)) + [401, 1000]:
        rounds = coarse_to_fine(n, coarsest)
        flat = np.concatenate(rounds) if rounds else np.empty(0, int)
        assert sorted(flat.tolist()) == list(range(n))  # each once
        assert all(len(r) for r in rounds)
        if n:
            assert rounds[0].tolist() == list(range(0, n, coarsest))
        seen = set()
        for r in rounds:  # each index halfway between two of the rounds before (or the end)
            step = min((b - a for a, b in zip(sorted(seen), sorted(seen)[1:])), default=None)
            if seen and step is not None:
                assert all((i - step // 2) in seen for i in r.tolist())
            seen |= set(r.tolist())
