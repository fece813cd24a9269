"""The cell's split (paint/cell/split.py, docs/model.md §26.2): zones contiguous, each with
its run-outs inside its robot's band, the longest zone the shortest the bands allow
(against a brute-force search of the seams), one-line refusals."""
import math

import numpy as np
import pytest
from cell_split_jobs import check_zones, plate_part, tall_panel

from pollard_pin.painting.cell.bands import Band, Strokes, job_strokes, robot_band
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.cell.split import seam_runs, seams_between, split_cell
from pollard_pin.painting.errors import CellError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.policy import PlannerPolicy

LOW, HIGH = CellRobot("low"), CellRobot("high", (0.0, 0.75, 0.17))


def test_two_stacked_robots_split_the_part_in_halves(robot):
    job = tall_panel()
    split = split_cell(robot, job, [HIGH, LOW])
    assert split.axis == (0.0, 0.0, 1.0) and split.runout == pytest.approx(0.04, abs=1e-15)
    assert [z.robot for z in split.zones] == ["low", "high"]
    lengths = check_zones(robot, [LOW, HIGH], split, job_strokes(job))
    # the bands (-0.06…0.28, 0.11…0.45 m) allow seams 0.15…0.24 m: the middle, to bisection
    assert lengths == pytest.approx([0.17, 0.17], abs=1e-3)  # seen 2e-6


def test_the_seam_moves_to_where_both_run_outs_fit(robot):
    job = tall_panel()
    high = CellRobot("high", (0.0, 0.75, 0.21))  # band 0.15…0.49 m: seam ≥ 0.15 + R
    split = split_cell(robot, job, [LOW, high])
    check_zones(robot, [LOW, high], split, job_strokes(job))
    assert split.zones[0].hi == pytest.approx(0.19, abs=1e-3)  # seen 2.4e-6


def test_seams_given_cut_the_zones_there(robot):
    """Seams set by hand (PlannerPolicy.seams, docs/model.md §26.5) replace the bands'
    balanced ones, the robots kept in order; a count or a seam off the part is one line."""
    job = tall_panel()
    split = split_cell(robot, job, [HIGH, LOW], seams=(0.12,))
    assert [(z.robot, z.lo, z.hi) for z in split.zones] == [("low", -math.inf, 0.12),
                                                           ("high", 0.12, math.inf)]
    assert split.seams() == [0.12] and split.runout == pytest.approx(0.04, abs=1e-15)
    for seams, words in [((0.1, 0.2), "2 seam(s) given for 2 robots facing the painted faces: "
                          "expected 1"), ((0.5,), "the seam at 0.5 m lies off the part")]:
        with pytest.raises(CellError) as info:
            split_cell(robot, job, [HIGH, LOW], seams=seams)
        assert words in str(info.value) and "\n" not in str(info.value), str(info.value)


def test_three_robots_take_a_third_each(robot):
    job = tall_panel()
    robots = [LOW, HIGH, CellRobot("mid", (0.0, 1.5, 0.08))]
    split = split_cell(robot, job, robots)
    assert [z.robot for z in split.zones] == ["low", "mid", "high"]
    lengths = check_zones(robot, robots, split, job_strokes(job))
    assert lengths == pytest.approx([0.34 / 3] * 3, abs=1e-3)  # seen 3e-6


def test_moving_the_part_and_robots_together_moves_the_seams(robot):
    a = split_cell(robot, tall_panel(), [LOW, CellRobot("high", (0.0, 0.75, 0.21))])
    lift = 0.1
    b = split_cell(robot, tall_panel(lift=lift), [CellRobot("low", (0.0, 0.0, lift)),
                                                  CellRobot("high", (0.0, 0.75, 0.21 + lift))])
    # the same band grid, moved: equal to round-off and the bisection (1e-5 m)
    assert b.zones[0].hi - a.zones[0].hi == pytest.approx(lift, abs=1e-3)  # seen 1e-16


def test_turning_the_whole_cell_about_z_leaves_the_split(robot):
    """Panel, line and robots turned 90° about world z (x, y → −y, x): the same seams."""
    from cell_split_jobs import GUN

    from pollard_pin.painting.job import job_from_dict

    turned = job_from_dict({
        "panel": {"center": [0.75, 0.70, 0.17], "normal": [0.0, -1.0, 0.0], "width": 0.8,
                  "height": 0.34},
        "gun": dict(GUN), "job": {"thickness": 25e-6},
        "line": {"speed": 0.012, "direction": [-1.0, 0.0, 0.0]}})
    robots = [CellRobot("low", (0.0, 0.0, 0.0), (0.0, 0.0, 90.0)),
              CellRobot("high", (-0.75, 0.0, 0.21), (0.0, 0.0, 90.0))]
    a = split_cell(robot, tall_panel(), [LOW, CellRobot("high", (0.0, 0.75, 0.21))])
    b = split_cell(robot, turned, robots)
    assert b.axis == pytest.approx(a.axis, abs=1e-15)
    # the bands agree to round-off on the grid; the seam to the bisection (1e-5 m)
    assert b.zones[0].hi == pytest.approx(a.zones[0].hi, abs=1e-4)  # seen 0


def test_a_robot_on_the_far_side_paints_the_back_faces(robot, tmp_path):
    job = load_job(plate_part(tmp_path, height=0.25, z=0.125))
    back = CellRobot("back", (1.40, 0.3, 0.0), (0.0, 0.0, 180.0))  # gun along −x
    split = split_cell(robot, job, [back, LOW])
    assert [(z.robot, z.facing, z.lo, z.hi) for z in split.zones] == [
        ("low", None, -math.inf, math.inf), ("back", (1.0, 0.0, 0.0), -math.inf, math.inf)]


@pytest.mark.parametrize("robots, words", [
    ([LOW, CellRobot("high", (0.0, 0.75, 0.30))],
     "robots 'low' and 'high' overlap along z by 40 mm (0.240…0.280 m), less than the 80 mm"),
    ([LOW, CellRobot("high", (0.0, 0.75, 0.8))],
     "robot 'high' reaches z 0.740…1.080 m at the part's depth; the part spans z "
     "0.000…0.340 m"),
    ([LOW], "no robot reaches z 0.280…0.380 m (the part's edge 0.340 m"),
    ([CellRobot("high", (0.0, 0.75, 0.17))], "no robot reaches z -0.040…0.110 m"),
    ([LOW, CellRobot("high", (0.0, 0.75, 0.40))], "no robot reaches z 0.280…0.340 m between "
     "robots 'low'"),
    ([LOW, HIGH, CellRobot("back", (1.4, 0.0, 0.1), (0.0, 0.0, 180.0))],
     "robot 'back' faces the panel's back"),
    ([CellRobot("back", (1.4, 0.0, 0.1), (0.0, 0.0, 180.0))],
     "no robot faces the job's painted faces (facing (-1, 0, 0))"),
    ([CellRobot("far", (0.0, 0.0, 2.0))], "robot 'far' reaches z 1.940…2.100 m at the part's"),
    ([CellRobot("deep", (-1.5, 0.0, 0.0))], "robot 'deep' reaches no point at the part's depth"),
])
def test_refusals_say_where(robot, robots, words):
    with pytest.raises(CellError) as info:
        split_cell(robot, tall_panel(), robots)
    msg = str(info.value)
    assert words in msg and "\n" not in msg, msg


def test_no_robot_on_the_job_side_is_refused(robot, tmp_path):
    job = load_job(plate_part(tmp_path))
    with pytest.raises(CellError, match="no robot faces the job's painted faces"):
        split_cell(robot, job, [CellRobot("back", (1.40, 0.3, 0.08), (0.0, 0.0, 180.0))])


def test_a_seam_keeps_what_room_its_overlap_allows():
    """With a seam run set, a seam whose bands overlap by less than 2R keeps as much of R as
    the overlap allows (half of it each side: room for a ramp, §26.5), the others R, before
    the zones are balanced; a split that cannot falls back to the run at every seam. By hand:
    overlaps 100 and 45 mm (R = 40 mm, run 5 mm): runs 40 and 22.5 mm, the top seam at the
    overlap's middle 0.7225 m, the other as balanced as R lets it, at 0.36 m (zones 0.36,
    0.3625, 0.2775 m; at 0.34…0.36 m the middle zone is longer)."""
    fake = [Band("a", -0.05, 0.40, None), Band("b", 0.30, 0.745, None),
            Band("c", 0.70, 1.05, None)]
    strokes = fake_strokes(seam_run=0.005)
    assert seam_runs(fake, strokes) == pytest.approx([0.04, 0.0225], abs=1e-15)
    assert seam_runs(fake, strokes, room=False) == [0.005, 0.005]
    assert seam_runs(fake, fake_strokes()) == [0.04, 0.04]  # no run set: R, as before
    assert seams_between(fake, strokes, 0.01) == pytest.approx([0.36, 0.7225], abs=2e-5)
    assert seams_between(fake, fake_strokes(), 0.01) is None  # R does not fit 45 mm
    # a zone the held room leaves too short: the run at every seam (the old split)
    tight = [Band("a", -0.05, 0.40, None), Band("b", 0.36, 0.45, None),
             Band("c", 0.41, 1.05, None)]
    assert seams_between(tight, strokes, 0.06) is None  # 20 mm runs: b's zone 50 < 60 mm
    split = seams_between(tight, strokes, 0.06, room=False)
    assert split is not None and split[1] - split[0] >= 0.06 - 1e-9
    assert 0.365 - 1e-9 <= split[0] and split[1] <= 0.445 + 1e-9


def fake_strokes(lo=0.0, hi=1.0, runout=0.04, run_on=0.03, seam_run=None):
    return Strokes(np.array([0.0, 0.0, 1.0]), np.array([-1.0, 0.0, 0.0]),
                   np.array([0.0, 1.0, 0.0]), (), (lo, hi), run_on, runout, True,
                   seam_run=seam_run)


def brute_longest(bands, strokes, least, step=0.0025):
    """The shortest longest zone over every grid choice of seams (None: no choice fits)."""
    e0, e1 = strokes.extent
    R, grid = strokes.runout, np.arange(e0, e1 + step / 2, step)
    if bands[0].lo > e0 - strokes.run_on or bands[-1].hi < e1 + strokes.run_on:
        return None
    seams = np.stack(np.meshgrid(*[grid] * (len(bands) - 1), indexing="ij"), -1)
    seams = seams.reshape(-1, len(bands) - 1)
    w = np.column_stack([np.full(len(seams), e0), seams, np.full(len(seams), e1)])
    zones = np.diff(w, axis=1)
    ok = (zones >= least).all(axis=1)
    for i in range(len(bands) - 1):
        ok &= (bands[i + 1].lo + R <= seams[:, i]) & (seams[:, i] <= bands[i].hi - R)
    return float(zones[ok].max(axis=1).min()) if ok.any() else None


@pytest.mark.parametrize("seed", range(40))
def test_the_seams_shorten_the_longest_zone_as_brute_force_does(seed):
    rng = np.random.default_rng(seed)
    n = 2 + seed % 2
    s = fake_strokes()
    starts = np.sort(rng.uniform(-0.1, 0.8, n))
    starts[0] = -0.05
    bands = [Band(f"r{i}", float(a), float(a + rng.uniform(0.1, 0.9)), None)
             for i, a in enumerate(starts)]
    bands[-1] = Band(bands[-1].robot, bands[-1].lo, 1.05, None)
    if seed % 5 == 4:  # a middle band inside its neighbour's: the upper bounds not in order
        bands[0] = Band("r0", -0.05, 0.9, None)
    seams = seams_between(bands, s, 0.01)
    brute = brute_longest(bands, s, 0.01)
    if brute is None:
        # the brute force's 2.5 mm grid may miss a window narrower than it
        assert seams is None or min(b.hi - a.lo for a, b in zip(bands, bands[1:])) < 0.09
        return
    assert seams is not None
    w = [0.0, *seams, 1.0]
    for i, x in enumerate(seams):  # each seam's run-outs in both bands
        assert bands[i + 1].lo + s.runout - 1e-12 <= x <= bands[i].hi - s.runout + 1e-12
    assert all(b - a >= 0.01 - 1e-12 for a, b in zip(w, w[1:]))
    longest = max(b - a for a, b in zip(w, w[1:]))
    # the brute force on a 2.5 mm grid is at most a grid step worse; bisection to 1e-5
    assert brute - 0.0025 - 1e-9 <= longest <= brute + 1e-4, (longest, brute)


def test_a_seam_run_lets_bands_overlap_twice_it(robot):
    """With the strokes running ``seam_run`` past a seam (PlannerPolicy.seam_run, §26.5) the
    split holds that run in both bands where R does not fit: bands 50 mm over each other are
    refused at R = 40 mm and split at 20 mm, the seam in both robots' bands (computed here)
    with 20 mm past it, the free edges' needs as before."""
    job = tall_panel()
    high = CellRobot("high", (0.0, 0.75, 0.29))
    strokes = job_strokes(job)
    low_band, high_band = (robot_band(robot, r, strokes) for r in (LOW, high))
    overlap = low_band.hi - high_band.lo
    assert 0.04 < overlap < 0.08, overlap  # between 2·seam_run and 2R
    with pytest.raises(CellError, match=r"less than the 80 mm a seam's run-outs need \(R = "):
        split_cell(robot, job, [LOW, high])
    split = split_cell(robot, job, [LOW, high], policy=PlannerPolicy(seam_run=0.02))
    assert split.runout == pytest.approx(0.04, abs=1e-15)  # the film's seam window: R
    (seam,) = split.seams()
    lo, hi = strokes.needed(-math.inf, math.inf)  # the free edges' (no seam in them)
    assert low_band.holding(lo, seam + 0.02).holds(lo, seam + 0.02)
    assert high_band.holding(seam - 0.02, hi).holds(seam - 0.02, hi)
    # where R fits the split keeps it (room for the ramps): the seams as without a seam run
    assert split_cell(robot, job, [LOW, HIGH], policy=PlannerPolicy(seam_run=0.02)
                      ).seams() == split_cell(robot, job, [LOW, HIGH]).seams()
    # and the pure split: the same bands' numbers, a seam run of 20 mm or R
    fake = [Band("a", -0.05, 0.55, None), Band("b", 0.49, 1.05, None)]
    assert seams_between(fake, fake_strokes(), 0.01) is None
    (s,) = seams_between(fake, fake_strokes(seam_run=0.02), 0.01)
    assert 0.49 + 0.02 - 1e-9 <= s <= 0.55 - 0.02 + 1e-9
