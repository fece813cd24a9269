"""The MeshCat viewer (viz/viewer.py): static page contents, and the page rendered in Chromium.
(The command and its live server: tests/cli/test_view.py.)"""
import os

import numpy as np
import pytest
from browser import capture_meshcat, find_chromium

import pollard_pin as pp
from pollard_pin.cli import main
from pollard_pin.run import run_pipeline
from pollard_pin.viz import meshcat_page, viewer

SAMPLES = 401  # thesis curve, 20 s: dense enough for the IK's branch check, quick to solve
CHAINS = {  # chain → (geometry nodes drawn in its colour, pixel test for that colour)
    "chain0": ("arm0_0", "arm0_1", "cross0_0", "platform_0", "wrist1_0", "wrist2_0"),
    "leg1": ("arm_1_0", "arm_1_1", "arm_1_2", "cross_1_0", "link_1_0"),
    "leg2": ("arm_2_0", "arm_2_1", "arm_2_2", "cross_2_0", "link_2_0"),
}


def _solid(m):
    """Pixels whose 4 neighbours share the colour: bodies, not 1–2 px lines (axes, frames)."""
    out = np.zeros_like(m)
    out[1:-1, 1:-1] = (m[1:-1, 1:-1] & m[:-2, 1:-1] & m[2:, 1:-1] & m[1:-1, :-2]
                       & m[1:-1, 2:])
    return out


def _colour_masks(img):
    r, g, b = (img[..., i].astype(int) for i in range(3))
    return {
        "chain0": _solid((b > r + 60) & (b > g + 30)),  # (0.16, 0.40, 0.80) shaded
        "leg1": _solid((r > g + 40) & (g > b + 30) & (r > 150)),  # (0.90, 0.45, 0.10)
        "leg2": _solid((g > r + 40) & (g > b + 20)),  # (0.15, 0.65, 0.30)
        "path": (r > g + 80) & (b > g + 60),  # magenta tool path (thin lines)
    }


@pytest.fixture(scope="module")
def robot():
    return pp.load()


@pytest.fixture(scope="module")
def ik(robot):
    return run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES), dynamics=False).ik


@pytest.fixture(scope="module")
def html_file(tmp_path_factory):
    """The page written by the command line, with frames."""
    path = tmp_path_factory.mktemp("view") / "pollard.html"
    assert main(["view", "--samples", str(SAMPLES), "--quiet", "--frames",
                 "--html", str(path)]) == 0
    return path


def _by_type(cmds, kind):
    return [c for c in cmds if c["type"] == kind]


def _track(clip, prop):
    (tr,) = [t for t in clip["tracks"] if t["name"] == "." + prop]
    return np.array([k["time"] for k in tr["keys"]]), np.array([k["value"] for k in tr["keys"]])


def test_static_page_has_robot_geometry(html_file, robot):
    cmds = meshcat_page.page_commands(html_file.read_text())
    objects = {c["path"]: c["object"] for c in _by_type(cmds, "set_object")}
    gm = viewer.viewer_geometry(robot)
    kinds = {"Sphere": "SphereGeometry", "Cylinder": "CylinderGeometry", "Box": "BoxGeometry"}
    for g in gm.geometryObjects:
        obj = objects[f"/meshcat/{viewer.ROOT}/visuals/{g.name}"]
        assert obj["geometries"][0]["type"] == kinds[type(g.geometry).__name__], g.name
    # Every body of the URDF is drawn, plus both halves of each closure.
    names = {g.name for g in gm.geometryObjects}
    for link in ("base", "arm0", "platform", "wrist1", "wrist2", "gun", "arm_1", "link_1",
                 "arm_2", "link_2"):
        assert f"{link}_0" in names
    for i in (1, 2):
        assert {f"closure{i}_A_marker", f"closure{i}_B_marker"} <= names
    assert len(names) >= 25


def test_static_page_has_tool_path(html_file, ik):
    cmds = meshcat_page.page_commands(html_file.read_text())
    (line,) = [c for c in _by_type(cmds, "set_object") if c["path"].endswith("/tool_path")]
    geom = line["object"]["geometries"][0]
    pts = np.frombuffer(geom["data"]["attributes"]["position"]["array"].data
                        if hasattr(geom["data"]["attributes"]["position"]["array"], "data")
                        else geom["data"]["attributes"]["position"]["array"], dtype=np.float32)
    np.testing.assert_allclose(pts.reshape(-1, 3), ik.poses[:, :3], atol=1e-6)
    assert line["object"]["object"]["type"] == "Line"


def test_static_page_animation(html_file, ik):
    cmds = meshcat_page.page_commands(html_file.read_text())
    (anim,) = _by_type(cmds, "set_animation")
    assert anim["options"]["play"] is True
    clips = {a["path"]: a["clip"] for a in anim["animations"]}
    root = f"/meshcat/{viewer.ROOT}"
    # Real time: key times are frame numbers at the clip's fps, 0 … 20 s every 1/25 s.
    times, tip = _track(clips[f"{root}/frames/tip"], "position")
    fps = clips[f"{root}/frames/tip"]["fps"]
    assert fps == viewer.DEFAULT_FPS
    np.testing.assert_allclose(times / fps, np.arange(len(times)) / fps)
    assert times[-1] / fps == pytest.approx(ik.t[-1] - ik.t[0])
    # The tool frame follows the commanded tip position (nearest sample at each key).
    key_t, idx = viewer._key_samples(ik.t, fps)
    np.testing.assert_allclose(key_t, times / fps)
    assert np.max(np.abs(ik.t[idx] - key_t)) <= 0.5 * np.diff(ik.t).max() + 1e-12
    np.testing.assert_allclose(tip, ik.poses[idx, :3], rtol=0, atol=1e-13)  # achieves 4.6e-16
    # Each closure's two spheres coincide in every key frame: the loops are closed.
    for i in (1, 2):
        _, a = _track(clips[f"{root}/visuals/closure{i}_A_marker"], "position")
        _, b = _track(clips[f"{root}/visuals/closure{i}_B_marker"], "position")
        assert np.max(np.abs(a - b)) < 1e-13  # achieves 5.6e-16

        assert np.ptp(a, axis=0).max() > 0.05  # and they move with the robot
    # Every robot shape and both frames are animated.
    shapes = [p for p in clips if "/visuals/" in p]
    assert len(shapes) == len(viewer.viewer_geometry(pp.load()).geometryObjects)
    for p in shapes + [f"{root}/frames/platform"]:
        t_p, q_p = _track(clips[p], "quaternion")
        assert len(t_p) == len(times)
        np.testing.assert_allclose(np.linalg.norm(q_p, axis=1), 1.0, rtol=0, atol=1e-13)  # 6.7e-16


# --- the static page in a real browser ------------------------------------------------------
def _chromium_or_skip():
    exe = find_chromium()
    if exe is None:
        pytest.skip("Chromium is not installed (Debian: apt-get install chromium; .ci/run "
                    "installs it) — cannot render the MeshCat page")
    return exe


def test_static_page_renders_robot_in_chromium(html_file, tmp_path):
    from PIL import Image

    _chromium_or_skip()
    visuals = f"/meshcat/{viewer.ROOT}/visuals"
    nodes = tuple(f"{visuals}/{n}" for names in CHAINS.values() for n in names)
    shot = tmp_path / "viewer.png"
    facts = capture_meshcat(html_file, shot, time_s=10.0, controls=False, project=nodes)
    # The scene and its animation arrived in the browser's viewer.
    assert facts["duration"] == pytest.approx(20.0)
    assert facts["actions"] == 27  # 25 shapes + 2 frames
    assert facts["meshes"] >= 25
    w, h = facts["canvas"]
    img = np.asarray(Image.open(shot).convert("RGB"))
    assert img.shape[:2] == (h, w)
    bg = np.all(np.abs(img.astype(int) - np.round(255 * np.array(viewer.BACKGROUND))) <= 3,
                axis=2)
    assert (~bg).sum() > 0.02 * bg.size, "almost nothing drawn"
    masks = _colour_masks(img)
    minimum = {"chain0": 2000, "leg1": 1000, "leg2": 500, "path": 1000}
    for chain, names in CHAINS.items():
        mask = masks[chain]
        assert mask.sum() > minimum[chain], f"{chain}: only {mask.sum()} pixels of its colour"
        # Where the geometry projects (the viewer's own camera), with a margin.
        xy = np.array([facts["screen"][f"{visuals}/{n}"] for n in names])
        x0, y0 = np.maximum(xy.min(0) - 60, 0).astype(int)
        x1, y1 = (xy.max(0) + 60).astype(int)
        assert 0 <= x0 < x1 <= w + 60 and 0 <= y0 < y1 <= h + 60, f"{chain} off screen: {xy}"
        inside = mask[y0:y1, x0:x1].sum()
        assert inside > 0.85 * mask.sum(), f"{chain}: colour outside its projected region"
    assert masks["path"].sum() > minimum["path"]

    # Negative control: the same page with the robot hidden has (almost) none of its colours,
    # so the counts above measure the robot.
    empty = tmp_path / "empty.png"
    capture_meshcat(html_file, empty, time_s=10.0, controls=False, hide=(visuals,))
    img0 = np.asarray(Image.open(empty).convert("RGB"))
    masks0 = _colour_masks(img0)
    for chain in CHAINS:
        assert masks0[chain].sum() < 0.2 * minimum[chain], chain
    assert masks0["path"].sum() > minimum["path"]
    if os.environ.get("POLLARD_KEEP_SCREENSHOT"):
        shot.replace(os.environ["POLLARD_KEEP_SCREENSHOT"])


def test_write_html_refuses_wrong_arguments_before_writing(robot, tmp_path):
    """None for the robot, a string for the IK, a number for the path: one InputError line
    (not an AttributeError or TypeError from inside), and no page written."""
    ik = pp.inverse_kinematics(robot, [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]])
    page = tmp_path / "v.html"
    for args, says in (((page, None, ik), "^robot = None: expected a Robot"),
                       ((page, robot, "x"), "^ik = 'x': expected an IKResult"),
                       ((3, robot, ik), r"^path = 3: expected a file path")):
        with pytest.raises(pp.InputError, match=says):
            pp.write_html(*args)
    assert list(tmp_path.iterdir()) == []
