"""The MeshCat scene of a paint cell (docs/model.md §26): every robot drawn as its own model
instance under its base placement, each running its program on the cell's one clock, the
film on the part riding the line. Drawing only: the configurations and the film come in.

Each robot's nodes hang under ``pollard/<name>``, whose transform is the robot's base (world ←
base), so its shapes and its tool path (a magenta line) are animated in its own base frame.
Key frames run at ``fps`` over the union of the programs' times; each robot shows its sample
nearest each key time (its first or last before or after its program).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .meshcat_page import OfflineWindow
from .viewer import (
    BACKGROUND,
    CAMERA_OFFSET,
    CAMERA_TARGET,
    DEFAULT_FPS,
    FLOOR_Z,
    PATH_COLOUR,
    ROOT,
    Scene,
    aim_camera,
    check_frame_rate,
    floor_grid,
    viewer_geometry,
)

FLOOR_MARGIN = 0.6  # m: the floor grid reaches this far beyond the outermost bases


@dataclass(frozen=True, eq=False)
class CellMember:
    """One robot of the scene: ``name``, ``base`` (4, 4) world ← base, ``ik`` its solved
    program (``t``, ``q``, ``poses`` in its base frame)."""

    name: str
    base: np.ndarray
    ik: object


def cell_key_samples(members, fps: float):
    """Key-frame times on the cell's clock (K,) [s] and, per member, the sample shown at each
    (K,): the nearest, held before and after its program."""
    t0 = min(float(m.ik.t[0]) for m in members)
    t1 = max(float(m.ik.t[-1]) for m in members)
    check_frame_rate(np.array([t0, t1]), fps)
    key_t = t0 + np.arange(int(np.floor((t1 - t0) * fps + 1e-9)) + 1) / fps
    if key_t[-1] < t1:
        key_t = np.append(key_t, t1)
    out = []
    for m in members:
        t = np.asarray(m.ik.t, float)
        hi = np.clip(np.searchsorted(t, key_t), 0, len(t) - 1)
        lo = np.clip(hi - 1, 0, len(t) - 1)
        out.append(np.where(np.abs(t[lo] - key_t) < np.abs(t[hi] - key_t), lo, hi))
    return key_t, out


def _camera(vis, members, view) -> None:
    if view is not None:
        aim_camera(vis, view.centre, view.offset)
        return
    bases = np.array([m.base[:3, 3] for m in members])
    spread = float(np.ptp(bases, axis=0).max()) if len(bases) > 1 else 0.0
    aim_camera(vis, bases.mean(axis=0) + CAMERA_TARGET,
               np.asarray(CAMERA_OFFSET) * (1.0 + spread / np.linalg.norm(CAMERA_OFFSET)))


def _floor(vis, members) -> None:
    bases = np.array([m.base[:3, 3] for m in members])
    lo, hi = bases[:, :2].min(axis=0) - FLOOR_MARGIN, bases[:, :2].max(axis=0) + FLOOR_MARGIN
    size = float(np.ceil((hi - lo).max() * 10) / 10)
    vis["/Grid"].set_property("visible", False)
    vis[f"{ROOT}/floor"].set_object(floor_grid(size=size, z=float(bases[:, 2].min())
                                               + FLOOR_Z, origin=tuple(lo)))


def _robot_nodes(vis, robot, gm, m: CellMember) -> dict:
    """Draw one robot under ``pollard/<name>`` at its base; its shapes' node names."""
    import meshcat.geometry as mg
    import pinocchio as pin
    from pinocchio.visualize import MeshcatVisualizer

    viz = MeshcatVisualizer(robot.model, None, gm)
    viz.initViewer(viewer=vis)
    viz.loadViewerModel(rootNodeName=f"{ROOT}/{m.name}")
    vis[f"{ROOT}/{m.name}"].set_transform(np.asarray(m.base, float))
    pts = np.asarray(m.ik.poses[:, :3], dtype=np.float32).T
    vis[f"{ROOT}/{m.name}/tool_path"].set_object(
        mg.Line(mg.PointsGeometry(pts), mg.LineBasicMaterial(color=PATH_COLOUR, linewidth=2)))
    return {g.name: viz.getViewerNodeName(g, pin.GeometryType.VISUAL)
            for g in gm.geometryObjects}


def build_cell_scene(vis, robot, members, *, fps: float = DEFAULT_FPS, play: bool = True,
                     camera: bool = True, overlay=None) -> Scene:
    """Draw every member's robot at its base, its tool path and ``overlay`` (a callable(vis),
    its ``moving`` {node: callable(t) -> 4×4} riding the clock, its ``view`` the camera),
    and animate them on the cell's clock (:func:`cell_key_samples`)."""
    import pinocchio as pin
    from meshcat.animation import Animation

    members = list(members)
    key_t, idx = cell_key_samples(members, fps)  # checks the frame rate before any drawing
    gm = viewer_geometry(robot)
    view = getattr(overlay, "view", None)
    top, bottom = (BACKGROUND, BACKGROUND) if view is None else view.background
    vis["/Background"].set_property("top_color", list(top))
    vis["/Background"].set_property("bottom_color", list(bottom))
    if camera:
        _camera(vis, members, view)
    _floor(vis, members)
    nodes = [_robot_nodes(vis, robot, gm, m) for m in members]
    if overlay is not None:
        overlay(vis)
    moving = getattr(overlay, "moving", None) or {}
    model, data, gdata = robot.model, robot.model.createData(), gm.createData()

    def place(k: int) -> dict:
        out = {}
        for m, names, ix in zip(members, nodes, idx):
            pin.forwardKinematics(model, data, m.ik.q[ix[k]])
            pin.updateGeometryPlacements(model, data, gm, gdata)
            out.update({names[g.name]: gdata.oMg[i].homogeneous
                        for i, g in enumerate(gm.geometryObjects)})
        out.update({node: f(float(key_t[k])) for node, f in moving.items()})
        return out

    for node, T in place(0).items():
        vis[node].set_transform(T)
    anim = Animation(default_framerate=fps)
    for k in range(len(key_t)):
        with anim.at_frame(vis, float((key_t[k] - key_t[0]) * fps)) as frame:
            for node, T in place(k).items():
                frame[node].set_transform(T)
    vis.set_animation(anim, play=play, repetitions=1)
    shapes = {f"{m.name}/{g}": n for m, names in zip(members, nodes) for g, n in names.items()}
    return Scene(geometry_nodes=shapes, frame_nodes={}, path_node=f"{ROOT}/{members[0].name}"
                 "/tool_path", samples=idx[0], fps=fps, duration=float(key_t[-1] - key_t[0]))


def cell_html(robot, members, *, fps: float = DEFAULT_FPS, title: str | None = None,
              overlay=None) -> str:
    """The scene of :func:`build_cell_scene` as a self-contained HTML page."""
    window = OfflineWindow()  # imports meshcat without its deprecation warning
    import meshcat

    vis = meshcat.Visualizer(window=window)
    build_cell_scene(vis, robot, members, fps=fps, overlay=overlay)
    legend = getattr(getattr(overlay, "view", None), "legend", "")
    return window.get_scene(title or "Pollard paint cell (MeshCat)", legend)


def write_cell_html(path, robot, members, **kwargs):
    from pathlib import Path

    from ..io.atomic import atomic_open

    html = cell_html(robot, members, **kwargs)
    with atomic_open(path) as f:
        f.write(html)
    return Path(path)


__all__ = ["CellMember", "build_cell_scene", "cell_html", "cell_key_samples",
           "write_cell_html"]
