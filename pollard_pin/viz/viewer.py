"""MeshCat viewer: the robot animated along a trajectory, live in a browser or as a static page.

The scene holds

* the robot's visual geometry (``models/pollard.urdf``), loaded by Pinocchio's
  :class:`~pinocchio.visualize.MeshcatVisualizer`;
* both sides of each cut spherical joint (docs/model.md §4): a translucent sphere on the leg
  (``closure{i}_A``, leg colour) and a small solid red sphere on the platform (``closure{i}_B``).
  When the loop is closed the red sphere sits at the centre of the translucent one;
* the tool path, a magenta line through the commanded tip positions;
* optionally the tool (``tip``) and platform frames as RGB triads (x red, y green, z blue);
* a MeshCat animation: one key frame per ``1/fps`` s of trajectory time, played in real time,
  with MeshCat's own controls (Open Controls → Animations: play, pause, reset, time scrubber,
  time scale).

:func:`serve` starts MeshCat's server on localhost and keeps serving. :func:`static_html`
builds the same scene offline, without a server or sockets, and returns MeshCat's static
export: one self-contained HTML page (MeshCat's viewer bundle plus the scene commands) that any
browser opens from disk.
"""
from __future__ import annotations

import io
import signal
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..checks import file_path, instance
from ..errors import InputError
from ..kinematics.ik import IKResult
from ..model.build import check_robot
from .meshcat_page import OfflineWindow, import_meshcat

ROOT = "pollard"  # scene node of everything this module draws
PATH_COLOUR = 0xD0208C  # tool path (magenta)
CLOSURE_B_COLOUR = (0.85, 0.05, 0.05, 1.0)  # platform side of the ball joint
CLOSURE_A_ALPHA = 0.45
CLOSURE_A_RADIUS = 0.016  # m
CLOSURE_B_RADIUS = 0.006  # m
FRAME_SCALE = 0.06  # m, length of the frame triads
MAX_KEY_FRAMES = 100_000  # ≈ 1.5 KB each in a static page: beyond, the page is unusable
MIN_FPS = 1.0  # key frames/s: fewer make the animation straight jumps between far-off poses
MAX_SCENE = 1e3  # m: a point read back farther from the base is a damaged file (reach < 1 m)


class ViewerError(InputError):
    """An animation the viewer cannot build (one line: which value, why)."""
DEFAULT_FPS = 25.0
FLOOR_SIZE = 1.0  # m, the floor grid drawn at z = 0
FLOOR_ORIGIN = (-0.3, -0.5)
FLOOR_Z = -0.05  # m, just below the legs' lowest point
BACKGROUND = (0.96, 0.96, 0.96)
CLOUD_POINT_SIZE = 0.004  # m, a workspace map's reachable points
# Camera: orbit centre (world) and camera offset from it (world axes), chosen to frame the
# robot and the painting curve in front of it.
CAMERA_TARGET = (0.34, -0.03, 0.08)
CAMERA_OFFSET = (0.34, -0.58, 0.30)


# --- scene ----------------------------------------------------------------------------------
@dataclass
class Scene:
    """What :func:`build_scene` drew: node paths and the animation's key frames."""

    geometry_nodes: dict[str, str]  # geometry object name → meshcat path
    frame_nodes: dict[str, str]  # frame name → meshcat path (empty without frames)
    path_node: str
    samples: np.ndarray  # IK sample index shown at each key frame
    fps: float
    duration: float  # s


def _rgba_int(rgba) -> int:
    return int(rgba[0] * 255) * 65536 + int(rgba[1] * 255) * 256 + int(rgba[2] * 255)


def viewer_geometry(robot) -> pin.GeometryModel:
    """The robot's visual model with the closure spheres restyled as the two-sided markers.

    The URDF's own closure spheres are replaced by a translucent sphere on ``closure{i}_A``
    (leg side) and a small solid red sphere on ``closure{i}_B`` (platform side), each with an
    explicit parent joint and frame.
    """
    import coal

    from ..model.urdf import CHAIN_COLOURS

    gm = robot.visual_model.copy()
    model = robot.model
    for c in robot.closures:
        for frame in (c.frame_a, c.frame_b):
            for g in list(gm.geometryObjects):
                if g.name.startswith(frame + "_"):
                    gm.removeGeometryObject(g.name)
    for i, c in enumerate(robot.closures, start=1):
        leg_rgba = np.array(CHAIN_COLOURS[f"leg{i}"][:3] + (CLOSURE_A_ALPHA,))
        for frame, radius, rgba in ((c.frame_a, CLOSURE_A_RADIUS, leg_rgba),
                                    (c.frame_b, CLOSURE_B_RADIUS, np.array(CLOSURE_B_COLOUR))):
            fid = model.getFrameId(frame)
            f = model.frames[fid]
            g = pin.GeometryObject(f"{frame}_marker", f.parentJoint, fid, f.placement,
                                   coal.Sphere(radius))
            g.meshColor = rgba
            g.overrideMaterial = True
            gm.addGeometryObject(g)
    return gm


def _triad_object(scale: float):
    import meshcat.geometry as mg

    pos = np.array([[0, 0, 0], [scale, 0, 0], [0, 0, 0], [0, scale, 0], [0, 0, 0], [0, 0, scale]],
                   dtype=np.float32).T
    col = np.array([[1, 0, 0], [1, 0, 0], [0, 0.7, 0], [0, 0.7, 0], [0, 0, 1], [0, 0, 1]],
                   dtype=np.float32).T
    return mg.LineSegments(mg.PointsGeometry(position=pos, color=col),
                           mg.LineBasicMaterial(vertexColors=True, linewidth=3))


def aim_camera(vis, target, offset) -> None:
    """The orbit centre at ``target``, the camera at ``offset`` from it (world, m): MeshCat
    0.3's orbit controls aim at the origin, so the drawn world is shifted by −target."""
    shift = pin.SE3(np.eye(3), -np.asarray(target, float)).homogeneous
    for node in ("/meshcat", "/Axes"):
        vis[node].set_transform(shift)
    off = np.asarray(offset, float)  # in MeshCat's y-up frame: (x, y, z) = (a, −c, b)
    vis["/Cameras/default/rotated/<object>"].set_property(
        "position", [float(off[0]), float(off[2]), float(-off[1])])


def floor_grid(size: float = FLOOR_SIZE, step: float = 0.1, z: float = 0.0,
               origin=FLOOR_ORIGIN):
    import meshcat.geometry as mg

    xs = np.arange(origin[0], origin[0] + size + 1e-9, step)
    ys = np.arange(origin[1], origin[1] + size + 1e-9, step)
    seg = [((x, ys[0], z), (x, ys[-1], z)) for x in xs] + [((xs[0], y, z), (xs[-1], y, z))
                                                          for y in ys]
    pts = np.array([p for s in seg for p in s], dtype=np.float32).T
    return mg.LineSegments(mg.PointsGeometry(pts), mg.LineBasicMaterial(color=0xB0B0B0))


def check_frame_rate(t: np.ndarray, fps: float) -> None:
    """Raise :class:`ViewerError` unless ``fps`` key frames per second over the times ``t``
    [s] make a positive number of at most :data:`MAX_KEY_FRAMES` key frames."""
    span = float(t[-1] - t[0])
    if not fps > 0:
        raise ViewerError(f"the frame rate must be positive, got {fps} key frames/s")
    if fps < MIN_FPS:
        raise ViewerError(f"{fps:.4g} key frames/s is below the least of {MIN_FPS:g}: the "
                          "animation would jump straight between poses "
                          f"{1 / fps:.4g} s apart; raise the frame rate")
    if not span * fps < MAX_KEY_FRAMES:
        raise ViewerError(f"{fps:g} key frames/s over {span:.4g} s make {span * fps:.3g} key "
                          f"frames, more than {MAX_KEY_FRAMES}: lower the frame rate")


def check_scene_points(points, where: str, rows=None) -> None:
    """Raise :class:`ViewerError` if a point (n, 3) [m] read back for the scene lies beyond
    ±:data:`MAX_SCENE` of the base: ``where`` names the file, ``rows`` (n,) the table row of
    each point (default 1 … n)."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    far = ~(np.abs(points).max(axis=1) <= MAX_SCENE)
    if far.any():
        k = int(np.argmax(far))
        row = k + 1 if rows is None else int(rows[k])
        x, y, z = points[k]
        raise ViewerError(f"{where}: row {row}: point ({x:.4g}, {y:.4g}, {z:.4g}) m is beyond "
                          f"±{MAX_SCENE:g} m of the robot base (its reach is under 1 m): a "
                          "damaged file?")


def _key_samples(t: np.ndarray, fps: float) -> tuple[np.ndarray, np.ndarray]:
    """Key-frame times (from 0, real time at ``fps``) and the nearest IK sample of each."""
    check_frame_rate(t, fps)
    t = np.asarray(t, dtype=float) - t[0]
    n_keys = int(np.floor(t[-1] * fps + 1e-9)) + 1
    key_t = np.arange(n_keys) / fps
    if key_t[-1] < t[-1]:
        key_t = np.append(key_t, t[-1])
    idx = np.clip(np.searchsorted(t, key_t), 0, len(t) - 1)
    prev = np.clip(idx - 1, 0, len(t) - 1)
    idx = np.where(np.abs(t[prev] - key_t) < np.abs(t[idx] - key_t), prev, idx)
    return key_t, idx


def film_panel(vis, points, values, lo: float, hi: float, node: str = f"{ROOT}/paint"):
    """Draw a surface grid ``points`` (nv, nu, 3) [m] as triangles coloured by ``values``
    (nv, nu) from blue (``lo``) through white to red (``hi``): the painted film."""
    from .film_view import grid_faces

    faces = grid_faces(*np.shape(values))
    return film_mesh(vis, np.reshape(points, (-1, 3)), faces, np.ravel(values), lo, hi, node)


def film_mesh(vis, vertices, faces, values, lo: float, hi: float,
              node: str = f"{ROOT}/paint"):
    """Draw triangles ``faces`` (M, 3) over ``vertices`` (V, 3) [m] coloured per vertex by
    ``values`` (V,) on the film scale from ``lo`` (blue) through white to ``hi`` (red): a film
    on a part."""
    import meshcat.geometry as mg

    from ..film_scale import scale_rgba

    colour = scale_rgba(values, lo, hi)[:, :3]
    vis[node].set_object(mg.TriangularMeshGeometry(np.asarray(vertices, float),
                                                   np.asarray(faces), color=colour),
                         mg.MeshBasicMaterial(vertexColors=True, side=2))
    return node


def point_cloud(vis, points, colours, node: str = f"{ROOT}/workspace"):
    """Draw ``points`` (n, 3) [m] as a point cloud coloured per point by ``colours`` (n, 3)
    in [0, 1] (a workspace map's reachable points, :func:`.workspace.workspace_cloud`)."""
    import meshcat.geometry as mg

    pos, col = (np.asarray(a, dtype=np.float32).T for a in (points, colours))
    vis[node].set_object(mg.Points(mg.PointsGeometry(pos, color=col),
                                   mg.PointsMaterial(size=CLOUD_POINT_SIZE)))  # per-vertex
    return node


def build_scene(vis, robot, ik, *, frames: bool = False, fps: float = DEFAULT_FPS,
                play: bool = True, camera: bool = True, overlay=None) -> Scene:
    """Draw the robot, closure markers, tool path (and frames) into meshcat ``vis`` and set
    the animation of ``ik`` (an :class:`~pollard_pin.kinematics.ik.IKResult`) on it.
    ``overlay``: a callable(vis) drawing more (e.g. :func:`film_panel`); its optional
    attribute ``moving`` {node: callable(t) -> 4×4} moves those nodes with the animation (a
    part riding a line, docs/model.md §24)."""
    import meshcat.geometry as mg
    from meshcat.animation import Animation
    from pinocchio.visualize import MeshcatVisualizer

    key_t, idx = _key_samples(ik.t, fps)  # checks the frame rate before any drawing
    gm = viewer_geometry(robot)
    viz = MeshcatVisualizer(robot.model, None, gm)
    viz.initViewer(viewer=vis)
    viz.loadViewerModel(rootNodeName=ROOT)
    model, data, gdata = viz.model, viz.data, viz.visual_data

    view = getattr(overlay, "view", None)  # a film's view (.film_view.FilmView)
    top, bottom = (BACKGROUND, BACKGROUND) if view is None else view.background
    vis["/Background"].set_property("top_color", list(top))
    vis["/Background"].set_property("bottom_color", list(bottom))
    if camera:
        aim_camera(vis, CAMERA_TARGET if view is None else view.centre,
                   CAMERA_OFFSET if view is None else view.offset)

    # MeshCat's 20 m grid is replaced by a 1 m floor grid, 0.1 m squares, under the robot.
    vis["/Grid"].set_property("visible", False)
    vis[f"{ROOT}/floor"].set_object(floor_grid(z=FLOOR_Z))

    path_node = f"{ROOT}/tool_path"
    pts = np.asarray(ik.poses[:, :3], dtype=np.float32).T
    vis[path_node].set_object(mg.Line(mg.PointsGeometry(pts),
                                      mg.LineBasicMaterial(color=PATH_COLOUR, linewidth=2)))

    if overlay is not None:
        overlay(vis)
    frame_nodes = {}
    if frames:
        for name in ("tip", "platform"):
            frame_nodes[name] = f"{ROOT}/frames/{name}"
            vis[frame_nodes[name]].set_object(_triad_object(FRAME_SCALE))
    frame_ids = {name: model.getFrameId(name) for name in frame_nodes}

    geom_nodes = {g.name: viz.getViewerNodeName(g, pin.GeometryType.VISUAL)
                  for g in gm.geometryObjects}
    moving = getattr(overlay, "moving", None) or {}

    def place(k: int) -> dict[str, np.ndarray]:
        pin.forwardKinematics(model, data, ik.q[k])
        pin.updateGeometryPlacements(model, data, gm, gdata)
        out = {geom_nodes[g.name]: gdata.oMg[gid].homogeneous
               for gid, g in enumerate(gm.geometryObjects)}
        if frame_ids:
            pin.updateFramePlacements(model, data)
            out.update({frame_nodes[n]: data.oMf[f].homogeneous for n, f in frame_ids.items()})
        out.update({node: f(float(ik.t[k])) for node, f in moving.items()})
        return out

    # Initial pose (what a browser shows before the animation runs), then the key frames.
    for node, T in place(0).items():
        vis[node].set_transform(T)
    anim = Animation(default_framerate=fps)
    for j, k in enumerate(idx):
        with anim.at_frame(vis, float(key_t[j] * fps)) as frame:
            for node, T in place(int(k)).items():
                frame[node].set_transform(T)
    vis.set_animation(anim, play=play, repetitions=1)
    return Scene(geometry_nodes=geom_nodes, frame_nodes=frame_nodes, path_node=path_node,
                 samples=idx, fps=fps, duration=float(key_t[-1]))


def static_html(robot, ik, *, frames: bool = False, fps: float = DEFAULT_FPS,
                title: str | None = None, overlay=None) -> str:
    """The scene of :func:`build_scene` as a self-contained HTML page (no server needed)."""
    check_robot(robot)
    instance(ik, "ik", IKResult, "an IKResult (pollard_pin.inverse_kinematics)")
    meshcat = import_meshcat()

    window = OfflineWindow()
    vis = meshcat.Visualizer(window=window)
    build_scene(vis, robot, ik, frames=frames, fps=fps, overlay=overlay)
    legend = getattr(getattr(overlay, "view", None), "legend", "")
    return window.get_scene(title or "Pollard robot (MeshCat)", legend)


def write_html(path, robot, ik, **kwargs) -> Path:
    """Write the robot moving along ``ik`` as one self-contained MeshCat page (about 3 MB;
    any browser opens it from disk, offline): what ``pollard-pin view --html`` writes.

    Parameters
    ----------
    path : str or pathlib.Path
        The HTML file (replaced whole or not at all).
    robot : Robot
        The model.
    ik : IKResult
        The joint motion to animate (:func:`~pollard_pin.inverse_kinematics`, or a
        :class:`~pollard_pin.run.RunResult`'s ``ik``).
    **kwargs
        ``frames`` (bool: draw the tool and platform frames), ``fps`` (key frames per second
        of trajectory time, default 25), ``title`` (the page's), ``overlay`` (a callable
        drawing more into the scene).

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> ik = pp.run_pipeline(robot, pp.thesis_trajectory(samples=51), dynamics=False).ik
    >>> page = pp.write_html("pollard.html", robot, ik, frames=True)
    >>> page.name, page.stat().st_size > 1_000_000
    ('pollard.html', True)
    """
    from ..io.atomic import atomic_open

    path = file_path(path, "path")
    html = static_html(robot, ik, **kwargs)
    with atomic_open(path) as f:
        f.write(html)
    return Path(path)


def serve(robot, ik, *, frames: bool = False, fps: float = DEFAULT_FPS, out=sys.stdout,
          ready=None, overlay=None, build=None) -> None:
    """Start MeshCat's server on localhost, draw the scene (``build(vis)`` -> Scene, default
    :func:`build_scene` of ``robot`` along ``ik``) and serve until interrupted (Ctrl-C or
    SIGTERM); the server process is stopped on the way out."""
    from contextlib import redirect_stdout

    meshcat = import_meshcat()

    with redirect_stdout(io.StringIO()):  # meshcat's own URL banner: we print the URL once
        vis = meshcat.Visualizer()
    window = vis.window
    def _terminate(signum, frame):
        raise KeyboardInterrupt

    try:  # SIGTERM stops the server as Ctrl-C does (only possible in the main thread)
        previous = signal.signal(signal.SIGTERM, _terminate)
    except ValueError:
        previous = None
    try:
        scene = (build_scene(vis, robot, ik, frames=frames, fps=fps, overlay=overlay)
                 if build is None else build(vis))
        print(f"MeshCat viewer: {window.web_url}", file=out)
        print(f"(zmq {window.zmq_url}; {len(scene.geometry_nodes)} shapes, "
              f"{scene.duration:.3g} s animation at {scene.fps:g} key frames/s; "
              "Open Controls → Animations to play and scrub; Ctrl-C to stop)", file=out)
        out.flush()
        if ready is not None:
            ready(vis, scene)
        while True:
            time.sleep(0.5)
    except KeyboardInterrupt:
        print("stopping the MeshCat server", file=out)
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
        proc = getattr(window, "server_proc", None)
        if proc is not None and proc.poll() is None:
            proc.kill()
            proc.wait()
