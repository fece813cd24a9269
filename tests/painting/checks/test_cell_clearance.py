"""The cell's clearance (docs/model.md §26.4): two guns facing each other at a gap known by
hand, refused just inside the clearance and passed just outside; the screened pair search
against every capsule pair; the bound between samples against a finer replay on other
robots' times; a rigid motion of everything changes nothing; the part against the gun's own
check (painting/checks/clearance.py)."""
import numpy as np
import pytest
import trimesh
from capsule_steps import steps
from scipy.spatial.transform import Rotation

from pollard_pin.errors import InputError
from pollard_pin.kinematics.capsules import capsule_layout, link_capsules, segment_distance
from pollard_pin.kinematics.ik import inverse_kinematics
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.checks.capsule_pairs import pair_distance
from pollard_pin.painting.checks.cell_clearance import MovingPart, cell_clearance
from pollard_pin.painting.checks.clearance import clearance_of
from pollard_pin.painting.errors import ClearanceError
from pollard_pin.painting.spray.gun_body import gun_body

NOZZLE = 0.004  # m: the nozzle capsule's radius, reaching this far ahead of the tip


@pytest.fixture(scope="module")
def sway(robot):
    """4 s of the home pose swaying ±0.1 m across and ±0.05 m up, 801 samples."""
    t = np.linspace(0.0, 4.0, 801)
    poses = np.tile(np.array(robot.params.home_pose, float), (len(t), 1))
    poses[:, 1] += 0.1 * np.sin(1.3 * t)
    poses[:, 2] += 0.05 * np.sin(0.7 * t)
    return t, poses


def facing(gap):
    """A robot at the origin and one turned about z to face it, their guns' tips (x = 0.55 m
    in each base frame at the home pose) ``gap`` apart, nozzle to nozzle less 2 × 4 mm."""
    return (CellRobot("low", (0.0, 0.0, 0.0)),
            CellRobot("high", (1.1 + 2 * NOZZLE + gap, 0.0, 0.0), (0.0, 0.0, 180.0)))


def test_facing_guns_at_a_gap_known_by_hand(robot, sway):
    t, poses = sway
    a, b = facing(0.005)
    c = cell_clearance(robot, [(a, t, poses), (b, t, poses)], required=0.004)
    # the tips meet where the sway crosses zero in both: at t = 0 (y = z = 0 for both)
    assert c.between_robots == pytest.approx(0.005, abs=1e-12)  # achieved 1e-16
    assert c.pair == ("low", "high") and c.pair_time == 0.0
    assert 0 < c.robots_between < 1e-3
    a, b = facing(0.003)
    with pytest.raises(ClearanceError) as err:
        cell_clearance(robot, [(a, t, poses), (b, t, poses)], required=0.004)
    assert str(err.value).startswith("robots 'low' and 'high' come within 3 mm at t = 0.00 s "
                                     "(clearance 4 mm")
    a, b = facing(-0.002)
    with pytest.raises(ClearanceError, match="cut 2 mm into each other"):
        cell_clearance(robot, [(a, t, poses), (b, t, poses)])


def test_the_screened_search_finds_every_pairs_least(robot, sway):
    """pair_distance screens capsule pairs by bounding spheres; every pair's exact distance
    (no screen) gives the same least and sample."""
    t, poses = sway
    q = inverse_kinematics(robot, poses, t=t).q
    a, b, r = link_capsules(robot, q)
    cuts = 0
    for base, rot in (((0.0, 0.75, 0.17), (0, 0, 0)), ((1.0, 0.3, 0.0), (0, 0, 180)),
                      ((0.2, 0.2, 0.9), (180, 0, 0)), ((0.0, 0.25, 0.0), (0, 0, 0)),
                      ((1.06, 0.05, 0.0), (0, 0, 180))):  # the last two cut into each other
        other = CellRobot("b", base, rot)
        a2, b2 = other.to_world(a), other.to_world(b)
        d, k = pair_distance(a, b, a2, b2, r, r)
        every = (segment_distance(a[:, :, None], b[:, :, None], a2[:, None], b2[:, None])
                 - r[:, None] - r[None, :]).min(axis=(1, 2))
        assert d == pytest.approx(every.min(), abs=1e-12) and k == int(np.argmin(every))
        # the samples the way travelled proves beyond the ceiling skipped: the same answer
        assert pair_distance(a, b, a2, b2, r, r, steps(a, b) + steps(a2, b2)) == (d, k)
        cuts += d < 0
    assert cuts == 2


def test_the_skip_answers_as_every_sample_measured(robot, sway, monkeypatch):
    """Two swaying robots and a moving plate (and a block under a leg): the cell's clearance
    skipping the samples the way travelled proves beyond the ceilings is, to the bit, the
    one of every sample measured (robot pairs, the gun's spheres, the other links')."""
    from pollard_pin.painting.checks import capsule_pairs as cc
    from pollard_pin.painting.checks import clearance

    t, poses = sway
    plate = trimesh.creation.box((0.01, 0.5, 0.3))
    plate.apply_translation((0.55 + 0.15 + 0.005, -0.2, 0.16))
    block = trimesh.creation.box((0.1, 0.1, 0.1))  # under leg 1's elbow
    block.apply_translation((0.3, -0.25, -0.12))
    cell = [CellRobot("low"), CellRobot("high", (0.1, 0.75, 0.17))]
    members = [(c, t, poses) for c in cell]
    cases = [(members, MovingPart(plate, (0.0, 0.05, 0.0))),
             (members[:1], MovingPart(block, (0.0, 0.01, 0.0)))]
    real, kept = cc.may_come_within, []

    def counted(*args):
        keep = real(*args)
        kept.append(keep.mean())
        return keep

    monkeypatch.setattr(cc, "may_come_within", counted)
    monkeypatch.setattr(clearance, "may_come_within", counted)
    skipped = [cell_clearance(robot, m, part) for m, part in cases]
    # the pair (6 levels; the first, 13 samples, keeps 9), guns, links: skipped
    assert len(kept) == 11 and max(kept[1:]) < 0.5

    def everywhere(known, at, way, limit, rows=None):
        return np.ones((len(way) if rows is None else len(rows),) + np.broadcast_shapes(
            np.shape(known)[1:], np.shape(limit)), bool)

    monkeypatch.setattr(cc, "may_come_within", everywhere)
    monkeypatch.setattr(clearance, "may_come_within", everywhere)
    assert [cell_clearance(robot, m, part) for m, part in cases] == skipped


def test_the_bound_between_samples_holds(robot, sway):
    """Each robot sampled every 16th sample of its own, the second offset by 8 samples: the
    least on the union of their times, less the bound between samples, is at most the least
    over all 801 samples (and within 20 mm of it)."""
    t, poses = sway
    a, b = facing(0.02)
    b = CellRobot("high", b.base, (0.0, 0.0, 170.0))
    fine = cell_clearance(robot, [(a, t, poses), (b, t, poses)])
    coarse = cell_clearance(robot, [(a, t[::16], poses[::16]), (b, t[8::16], poses[8::16])])
    assert coarse.between_robots - coarse.robots_between <= fine.between_robots + 1e-12
    assert coarse.between_robots >= fine.between_robots - 1e-3  # interpolated, not exact
    assert coarse.robots_between < 0.02


def _turned(robot_, R, p):
    """A CellRobot moved by the rigid motion x → R·x + p."""
    M = R @ robot_.R
    return CellRobot(robot_.name, tuple(R @ robot_.origin + p),
                     tuple(Rotation.from_matrix(M).as_euler("XYZ", degrees=True)))


def test_a_rigid_motion_of_everything_changes_nothing(robot, sway):
    t, poses = sway
    plate = trimesh.creation.box((0.01, 0.5, 0.3))
    plate.apply_translation((0.55 + 0.15 + 0.005, -0.2, 0.16))
    v = np.array([0.0, 0.05, 0.0])
    cell = [CellRobot("low"), CellRobot("high", (0.1, 0.75, 0.17))]
    before = cell_clearance(robot, [(c, t, poses) for c in cell], MovingPart(plate, tuple(v)))
    R = Rotation.from_euler("xyz", [30, -50, 110], degrees=True).as_matrix()
    p = np.array([0.4, -1.2, 0.7])
    moved = plate.copy()
    moved.apply_transform(np.block([[R, p[:, None]], [np.zeros((1, 3)), np.ones((1, 1))]]))
    after = cell_clearance(robot, [(_turned(c, R, p), t, poses) for c in cell],
                           MovingPart(moved, tuple(R @ v)))
    # achieved 3e-15 m (pair) and 2e-13 m (part)
    assert after.between_robots == pytest.approx(before.between_robots, abs=1e-11)
    assert after.to_part == pytest.approx(before.to_part, abs=1e-9)
    assert (after.pair, after.pair_time, after.robot, after.part_time) == (
        before.pair, before.pair_time, before.robot, before.part_time)


def test_the_part_against_the_guns_own_check(robot, sway):
    """One robot before a moving plate: its nearest capsules are the gun's, so the least
    distance to the part is the gun body's (painting/checks/clearance.py, on the poses in the
    part's frame): same spheres, same figure (achieved 0); 145.6 mm at the 150 mm standoff
    (the nozzle's front sphere reaches 4.386 mm ahead of the tip)."""
    t, poses = sway
    plate = trimesh.creation.box((0.01, 0.8, 0.4))
    plate.apply_translation((0.55 + 0.15 + 0.005, 0.1, 0.16))
    v = np.array([0.0, 0.05, 0.0])
    base = CellRobot("only", (0.0, 0.0, 0.0))
    c = cell_clearance(robot, [(base, t, poses)], MovingPart(plate, tuple(v)), required=0.01)
    rel = poses.copy()
    rel[:, :3] -= t[:, None] * v
    own = clearance_of(plate, rel, t, gun_body(robot.params))
    assert c.to_part == pytest.approx(own.distance, abs=1e-12)
    assert c.to_part == pytest.approx(0.15 - np.hypot(0.004, 0.0018), abs=1e-9)
    assert c.robot == "only" and c.part_between >= own.between - 1e-12  # every link: more
    assert c.between_robots == np.inf and c.pair is None
    with pytest.raises(ClearanceError, match=r"^robot 'only' comes within 146 mm of the part"):
        cell_clearance(robot, [(base, t, poses)], MovingPart(plate, tuple(v)), required=0.2)
    assert c.to_dict()["between_robots_m"] is None
    plate.apply_translation((-0.148, 0.0, 0.0))  # its face 2 mm ahead of the tip: 2.4 mm in
    with pytest.raises(ClearanceError, match=r"^robot 'only' cuts 2 mm into the part at t = "):
        cell_clearance(robot, [(base, t, poses)], MovingPart(plate, tuple(v)))


def test_capsule_count(robot):
    assert len(capsule_layout(robot)) == 25


@pytest.mark.parametrize("member, match", [
    ((CellRobot("a"), [0.0, 1.0], np.zeros((3, 6))), "expected"),
    ((CellRobot("a"), [0.0, 0.0], np.zeros((2, 6))), r"t\[1\] = 0 s does not follow"),
    ((CellRobot("a"), [0.0, np.nan], np.zeros((2, 6))), "not finite"),
    (("a", [0.0], np.zeros((1, 6))), "not a CellRobot"),
    ((CellRobot("a"), [0.0]), "expected"),
])
def test_bad_members(robot, member, match):
    with pytest.raises(InputError, match=match):
        cell_clearance(robot, [member])


def test_bad_required(robot, sway):
    t, poses = sway
    with pytest.raises(InputError, match="required"):
        cell_clearance(robot, [(CellRobot("a"), t, poses)], required=-0.1)


def test_a_pose_out_of_reach_names_its_robot(robot, sway):
    from pollard_pin.painting.errors import ReachError

    t, poses = sway
    far = poses.copy()
    far[400, 0] = 2.0  # 2 m ahead of the base: out of reach
    with pytest.raises(ReachError, match=r"^robot 'high': ") as err:
        cell_clearance(robot, [(CellRobot("low"), t, poses),
                               (CellRobot("high", (0.0, 0.75, 0.17)), t, far)])
    assert err.value.sample == 400


def test_the_parts_screen_keeps_the_nearest_link(robot, sway):
    """A block under a leg's elbow, nearer to it than to the gun: the screened search
    equals every capsule's spheres measured against it (§25's least_distance, no screen)."""
    from pollard_pin.kinematics.capsules import axis_spheres
    from pollard_pin.painting.checks.clearance import least_distance
    from pollard_pin.painting.spray.gun_body import AXIS_STEP

    t, poses = sway
    block = trimesh.creation.box((0.1, 0.1, 0.1))  # under leg 1's elbow (0.30, -0.23, -0.03)
    block.apply_translation((0.3, -0.25, -0.12))
    v = np.array([0.0, 0.01, 0.0])
    c = cell_clearance(robot, [(CellRobot("only"), t, poses)], MovingPart(block, tuple(v)))
    lay = capsule_layout(robot)
    a, b, _ = link_capsules(robot, inverse_kinematics(robot, poses, t=t).q, lay)
    a, b = a - (t[:, None] * v)[:, None], b - (t[:, None] * v)[:, None]
    owner, frac, radii = axis_spheres(lay.a, lay.b, lay.r, AXIS_STEP)
    centres = a[:, owner] + frac[None, :, None] * (b[:, owner] - a[:, owner])
    every, (n, s), _, _ = least_distance(block, centres, radii)
    assert not lay.gun[owner[s]]  # a leg, not the gun, is nearest
    assert c.to_part == pytest.approx(every, abs=1e-12) and c.part_time == t[n]
    # the spheres made capsule by capsule (not gathered sphere by sphere): the same bits
    assert c.to_part == every


def test_blocks_of_the_union_change_nothing(robot, sway, monkeypatch):
    """The union of times taken 37 at a time (blocks overlapping by one step) gives the same
    least, time and bound between samples as one block."""
    import pollard_pin.painting.checks.cell_clearance as clearance

    t, poses = sway
    a, b = facing(0.02)
    members = [(a, t[::3], poses[::3]), (CellRobot("high", b.base, (0.0, 0.0, 175.0)),
                                         t[1::4], poses[1::4])]
    whole = cell_clearance(robot, members)
    monkeypatch.setattr(clearance, "CHUNK", 37)
    parts = cell_clearance(robot, members)
    assert (parts.between_robots, parts.pair_time) == (whole.between_robots, whole.pair_time)
    assert parts.robots_between == whole.robots_between


