"""A cell's proposed layout (painting/layout/cell.py, docs/model.md §26.5): the fewest robots
whose bands hold equal zones, bases clear of each other along the line, every zone with its
run-outs in its robot's band; the search for the fewest that paint."""
import math
from dataclasses import replace

import numpy as np
import pytest
from cell_split_jobs import check_zones, door_part, tall_panel
from refusals import WRONG, refused

from pollard_pin.errors import InputError
from pollard_pin.painting.cell.bands import STEP, job_strokes, robot_band
from pollard_pin.painting.cell.robots import CellRobot, base_footprint
from pollard_pin.painting.cell.split import split_cell
from pollard_pin.painting.errors import CellError
from pollard_pin.painting.layout.cell import (
    LayoutOptions,
    cover_edge,
    propose_layout,
    reference_band,
    zone_needs,
)

BAND = 0.34  # m: one robot's band along z at the gun plane x = 0.55 (test_bands.py)


pytestmark = pytest.mark.usefixtures("bands_remembered")


def no_seating(monkeypatch):
    """No robot planned alone before a mocked paint_job (the seating: test_seat.py)."""
    from pollard_pin.painting.layout import seat

    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))


@pytest.mark.parametrize("height, fewest", [(0.24, 1), (0.34, 2), (0.6, 3), (1.0, 4)])
def test_the_fewest_robots_whose_bands_hold_the_zones(robot, height, fewest):
    job = tall_panel(height=height, z=height / 2)
    R = run_on = 0.04  # 4σ past a seam and past a panel's free edge
    # by hand: one zone needs height + 2 run-ons; n ≥ 2 equal zones, height/n + R + run-on
    # at the ends, height/n + 2R between
    need = [height + 2 * run_on] + [height / n + max(R + run_on, 2 * R) for n in range(2, 6)]
    assert fewest == 1 + next(i for i, x in enumerate(need) if x <= BAND + 1e-9)
    robots = propose_layout(robot, job, fewest)
    assert len(robots) == fewest
    if fewest > 1:
        with pytest.raises(CellError, match=f"at least {fewest} robots"):
            propose_layout(robot, job, fewest - 1)


def test_the_proposal_covers_the_part_with_clear_bases(robot):
    job = tall_panel(height=0.6, z=0.3)
    robots = propose_layout(robot, job, 3)
    strokes = job_strokes(job)
    split = split_cell(robot, replace(job, robots=robots), robots)
    lengths = check_zones(robot, robots, split, strokes)
    assert lengths == pytest.approx([0.2] * 3, abs=1e-3)  # seen 3e-6
    foot = base_footprint(robot.model)
    e = np.array(job.line.direction)
    along = [np.array(r.base) @ e for r in robots]
    # neighbours at least the tip's reach window along the line (0.60 m here) + 2 footprints
    assert np.diff(along) == pytest.approx(0.60 + 2 * foot, abs=2 * STEP)
    # each band is the reference band moved with its base (a flat panel: exact to the grid)
    ref = reference_band(robot, strokes)
    for r in robots:
        b = robot_band(robot, r, strokes, margin=1.0)
        assert b.lo == pytest.approx(ref.lo + r.base[2], abs=1.01 * STEP)
        assert b.hi == pytest.approx(ref.hi + r.base[2], abs=1.01 * STEP)


def test_options_and_bad_counts(robot):
    job = tall_panel()
    robots = propose_layout(robot, job, 2, LayoutOptions(spacing=1.2, prefix="paint"))
    assert [r.name for r in robots] == ["paint1", "paint2"]
    assert robots[1].base[1] - robots[0].base[1] == pytest.approx(1.2, abs=1e-12)
    for n in (0, 17, 10 ** 6, 2.0, True):
        with pytest.raises(CellError, match=r"expected 1\.\.16"):
            propose_layout(robot, job, n)
    with pytest.raises(CellError, match=r"^n = 1e\+400 \(a 401-digit integer\): expected"):
        propose_layout(robot, job, 10**400)  # shown short, not in 401 digits
    for bad in ({"spacing": 0.0}, {"spacing": math.nan}, {"prefix": "a b"},
                {"edge_room": -0.001}, {"edge_room": 0.6}, {"edge_room": "0.02"},
                {"end_pitch": 46.0}, {"end_pitch": math.inf}, {"end_pitch": None}):
        with pytest.raises(InputError):
            LayoutOptions(**bad)
    for bad in ({"spacing": 10**400}, {"prefix": 10**400}):  # not OverflowError, shown short
        with pytest.raises(InputError, match=r"= 1e\+400 \(a 401-digit integer\): expected"):
            LayoutOptions(**bad)
    placed = tall_panel(robots=[{"name": "a", "base": [0.0, 0.0, 0.0]}])
    with pytest.raises(CellError, match="already places its 1 robot"):
        propose_layout(robot, placed, 2)


def test_every_proposal_reads_back_or_is_refused_in_one_line(robot, tmp_path):
    # robots.toml → load_job: what the project proposes, its job reader accepts (14 robots
    # for the example cell once put one at y = 10.01 m, beyond the reader's ±10 m)
    from pathlib import Path

    from pollard_pin.outputs.robots_toml import robots_toml
    from pollard_pin.painting.cell.robots import MAX_DISTANCE, MAX_ROBOTS
    from pollard_pin.painting.job import load_job

    text = (Path(__file__).resolve().parents[3] / "examples" / "cell.toml").read_text()
    text = text[:text.index("[[robot]]")]
    bare = tmp_path / "bare.toml"
    bare.write_text(text)
    job = load_job(bare)
    read, refused = [], []
    for n in range(1, MAX_ROBOTS + 1):
        try:
            robots = propose_layout(robot, job, n)
        except CellError as exc:
            msg = str(exc)
            assert "\n" not in msg and len(msg) <= 250, msg
            refused.append(n)
            if n > 13:
                assert f"±{MAX_DISTANCE:g} m" in msg
            continue
        placed = tmp_path / f"cell{n}.toml"
        placed.write_text(text + robots_toml(robots))
        assert load_job(placed).robots == robots
        read.append(n)
    # one robot's band is short of the panel; 14 robots 0.77 m apart pass y = 10 m
    assert read == list(range(2, 14)) and refused == [1, *range(14, MAX_ROBOTS + 1)]


def test_a_cell_of_one_robot_is_proposed_where_it_reaches(robot):
    job = tall_panel(height=0.2, z=0.5)  # above the origin robot's band
    (r,) = propose_layout(robot, job, 1)
    assert r.base[0] == 0.0 and r.base[1] == 0.0
    band = robot_band(robot, r, job_strokes(job))
    # the band's middle on the zone's (run-ons included): 0.5 m, to the grid
    assert (band.lo + band.hi) / 2 == pytest.approx(0.5, abs=1.01 * STEP)
    assert CellRobot("x").is_origin


def test_a_part_gets_the_layout_of_its_panel(robot, tmp_path):
    from cell_split_jobs import plate_part

    from pollard_pin.painting.job import load_job

    part = propose_layout(robot, load_job(plate_part(tmp_path, x=0.69 + 0.01)), 2)
    panel = propose_layout(robot, tall_panel(x=0.69), 2)
    # the plate's front face is the panel; only the free edges' run-on differs (3σ, 4σ), so
    # each zone's need, and with it each base, moves by half the difference or less
    for a, b in zip(part, panel):
        assert np.allclose(a.base, b.base, atol=0.005 + 1e-9), (a, b)


@pytest.mark.parametrize("arg, wrong", [
    *((arg, w) for arg in ("robot", "job", "options") for w in WRONG
      if not (arg == "options" and w is None)),
    *(("n", w) for w in WRONG + [0, 17, 2.5, True, float("inf")] if w != 3)], ids=repr)
def test_propose_layout_refuses_a_wrong_argument(robot, arg, wrong):
    """propose_layout's robot, job, n and options: None (where it is not the default), the
    wrong types, NaN and an n out of 1..16 are one line naming the argument, nothing solved."""
    args = {"robot": robot, "job": tall_panel(), "n": 2, "options": None, arg: wrong}
    refused(lambda: propose_layout(args["robot"], args["job"], args["n"], args["options"]),
            arg)


@pytest.mark.parametrize("height, n", [(0.33, 4), (0.47, 5)])
def test_the_proposal_covers_bevelled_edges(robot, tmp_path, height, n):
    # the bands lag their bases over a bevelled edge, so robots centred by the reference
    # band left the run-on past an edge unreached for any count (before: "no robot reaches
    # z 0.320…0.375 m")
    from pollard_pin.painting.job import load_job
    from pollard_pin.painting.spray.occlusion import load_painted_part

    job = load_job(door_part(tmp_path, height=height))
    part = load_painted_part(job)
    robots = propose_layout(robot, job, n, part=part)
    strokes = job_strokes(job, part)
    split = split_cell(robot, replace(job, robots=robots), robots, part)
    check_zones(robot, robots, split, strokes)  # every need held, the edges' run-ons too
    lo, hi = strokes.needed(-math.inf, math.inf)
    first, last = (robot_band(robot, r, strokes) for r in (robots[0], robots[-1]))
    assert first.holding(lo=lo).lo <= lo and last.holding(hi=hi).hi >= hi


def test_cover_edge_moves_a_robot_by_its_shortfall_on_a_flat_part(robot, tmp_path):
    from cell_split_jobs import plate_part

    from pollard_pin.painting.job import load_job

    strokes = job_strokes(load_job(plate_part(tmp_path, z=0.10)))  # z −0.07 … 0.27 m
    lo, _ = strokes.needed(-math.inf, math.inf)
    need = (lo, lo + 0.2)
    at = robot_band(robot, CellRobot("a"), strokes)
    assert at.lo > lo + 0.03  # the origin robot misses the edge's run-on by some 5 cm
    moved = cover_edge(robot, CellRobot("a"), strokes, need)
    band = robot_band(robot, moved, strokes)
    assert band.holding(*need).holds(*need)
    # on a flat part the band moves with the base: one move of the shortfall below the
    # lowest point the robot reaches (it holds a short stretch from there), to the grid
    assert moved.base[2] == pytest.approx(lo - at.reached[0], abs=STEP + 1e-9)
    assert band.reached[0] == pytest.approx(at.reached[0] + moved.base[2], abs=STEP + 1e-9)
    assert moved.base[:2] == (0.0, 0.0)
    assert cover_edge(robot, CellRobot("a"), strokes, (lo, lo + 0.5)) is None  # too long


def test_room_at_the_free_edges_moves_the_end_robots_out(robot):
    """LayoutOptions.edge_room (docs/model.md §26.5): each end zone needs the room more past
    its free edge, so on a flat panel (its band moving with its base, to the grid) the
    bottom robot moves down and the top one up by half the room, their bands holding it."""
    job = tall_panel(height=0.34, z=0.17)
    strokes = job_strokes(job)
    room = 0.02
    wide = replace(strokes, room=room)
    lo, hi = strokes.needed(-math.inf, math.inf)
    assert wide.needed(-math.inf, math.inf) == pytest.approx((lo - room, hi + room), abs=1e-15)
    assert wide.needed(0.1, 0.2) == strokes.needed(0.1, 0.2)  # a seam's R alone
    plain = propose_layout(robot, job, 2)
    roomy = propose_layout(robot, job, 2, LayoutOptions(edge_room=room))
    moved = [b.base[2] - a.base[2] for a, b in zip(plain, roomy)]
    assert moved == pytest.approx([-room / 2, room / 2], abs=1e-6)
    first, last = (robot_band(robot, r, strokes) for r in (roomy[0], roomy[-1]))
    assert first.lo <= lo - room + STEP and last.hi >= hi + room - STEP


def test_a_pitched_top_robot_is_moved_onto_the_top_edge(robot):
    """LayoutOptions.end_pitch (docs/model.md §26.5): the top robot turned about the line
    (along y: rotation (0, pitch, 0)), as far down as its band still holds the top edge's
    run-on (to the grid), the robot below unmoved."""
    job = tall_panel(height=0.34, z=0.17)
    strokes = job_strokes(job)
    hi = strokes.needed(-math.inf, math.inf)[1]
    plain = propose_layout(robot, job, 2)
    turned = propose_layout(robot, job, 2, LayoutOptions(end_pitch=-5.0))
    assert turned[0] == plain[0] and turned[1].rotation == (0.0, -5.0, 0.0)
    band = robot_band(robot, turned[1], strokes)
    assert band.holding(hi=hi).hi >= hi - 1e-9
    lower = replace(turned[1], base=tuple(np.add(turned[1].base, (0.0, 0.0, -2 * STEP))))
    assert robot_band(robot, lower, strokes).holding(hi=hi).hi < hi  # no lower holds it


def test_zone_needs_with_end_zones(robot):
    strokes = job_strokes(tall_panel(height=0.34, z=0.17))  # extent 0 … 0.34 m
    e0, e1 = strokes.extent
    R, ro = strokes.runout, strokes.run_on
    needs = zone_needs(strokes, 4, (0.05, 0.07))
    cuts = [e0 + 0.05, e0 + 0.05 + (e1 - e0 - 0.12) / 2, e1 - 0.07]
    assert needs[0] == pytest.approx((e0 - ro, cuts[0] + R), abs=1e-12)
    assert needs[1] == pytest.approx((cuts[0] - R, cuts[1] + R), abs=1e-12)
    assert needs[3] == pytest.approx((cuts[2] - R, e1 + ro), abs=1e-12)
    two = zone_needs(strokes, 2, (0.1, 0.3))  # shared 1 : 3
    assert two[0][1] == pytest.approx(e0 + (e1 - e0) / 4 + R, abs=1e-12)
    assert zone_needs(strokes, 3) == zone_needs(strokes, 3, None)
