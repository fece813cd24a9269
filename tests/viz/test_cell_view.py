"""The cell's MeshCat scene (viz/cell_view.py): each robot under its base, its program on the
cell's one clock; the gun's tip in the world replayed from the page's transforms equals the
robot's base applied to its own tool pose (docs/model.md §26)."""
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pollard_pin.kinematics.ik import inverse_kinematics
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.viz import meshcat_page, viewer
from pollard_pin.viz.cell_view import CellMember, cell_html, cell_key_samples


class _Ik:
    def __init__(self, t, q, poses):
        self.t, self.q, self.poses = t, q, poses


def _sway(robot, t0, duration, n):
    t = t0 + np.linspace(0.0, duration, n)
    poses = np.tile(np.array(robot.params.home_pose, float), (n, 1))
    poses[:, 1] += 0.1 * np.sin(2 * (t - t0))
    return _Ik(t, inverse_kinematics(robot, poses, t=t).q, poses)


@pytest.fixture(scope="module")
def cell(robot):
    cells = [CellRobot("low"), CellRobot("high", (0.0, 0.75, 0.17), (0.0, 0.0, 30.0)),
             CellRobot("hung", (0.0, -0.8, 0.6), (180.0, 0.0, 0.0))]  # upside down
    iks = [_sway(robot, 0.0, 2.0, 81), _sway(robot, 1.0, 2.0, 41), _sway(robot, 0.5, 1.0, 21)]
    members = []
    for c, ik in zip(cells, iks):
        base = np.eye(4)
        base[:3, :3], base[:3, 3] = c.R, c.origin
        members.append(CellMember(c.name, base, ik))
    return cells, members


def test_key_samples_on_one_clock(cell):
    _, members = cell
    key_t, idx = cell_key_samples(members, 10.0)
    np.testing.assert_allclose(key_t, np.arange(31) / 10.0, atol=1e-12)
    # 'high' starts at 1 s: held at its first sample before, its nearest after
    assert (idx[1][key_t <= 1.0] == 0).all()
    assert np.abs(members[1].ik.t[idx[1]] - np.clip(key_t, 1.0, 3.0)).max() <= 0.025 + 1e-12
    assert (idx[0][key_t >= 2.0] == 80).all()


def _transform(cmd):
    return np.array(cmd["matrix"], float).reshape(4, 4).T


def test_the_page_places_each_robot_at_its_base(robot, cell):
    cells, members = cell
    cmds = meshcat_page.page_commands(cell_html(robot, members, fps=10.0))
    placed = {c["path"]: _transform(c) for c in cmds if c["type"] == "set_transform"}
    (anim,) = [c for c in cmds if c["type"] == "set_animation"]
    clips = {a["path"]: a["clip"] for a in anim["animations"]}
    key_t, idx = cell_key_samples(members, 10.0)
    gun = next(g for g in viewer.viewer_geometry(robot).geometryObjects if g.name == "gun_1")
    tip_local = np.array([0.0, 0.0, gun.geometry.halfLength, 1.0])  # the nozzle's front end
    for c, m, ix in zip(cells, members, idx):
        root = f"/meshcat/{viewer.ROOT}/{c.name}"
        np.testing.assert_allclose(placed[root][:3, :3], c.R, atol=1e-12)
        np.testing.assert_allclose(placed[root][:3, 3], c.origin, atol=1e-12)
        clip = clips[f"{root}/visuals/gun_1"]
        keys = {t["name"]: t["keys"] for t in clip["tracks"]}
        pos = np.array([k["value"] for k in keys[".position"]])
        quat = np.array([k["value"] for k in keys[".quaternion"]])  # x, y, z, w
        assert len(pos) == len(key_t)
        R = Rotation.from_quat(quat).as_matrix()
        tip_base = np.einsum("nij,j->ni", R, tip_local[:3]) + pos
        tip_world = c.to_world(tip_base)
        # the nozzle's front end is the tool tip (x1918 from the wrist): achieved 1e-15 m
        expect = c.to_world(m.ik.poses[ix, :3])
        np.testing.assert_allclose(tip_world, expect, atol=1e-9)
    paths = [c["path"] for c in cmds if c["type"] == "set_object"]
    assert {f"/meshcat/{viewer.ROOT}/{c.name}/tool_path" for c in cells} <= set(paths)
