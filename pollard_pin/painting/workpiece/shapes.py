"""Example parts as closed triangle meshes: thin profiles in the world x–y plane extruded
along z (``examples/parts/make_parts.py`` writes them; the tests paint them).

A profile is its front polyline (the side facing the robot, −x) and its back polyline, point
for point; the closed outline front + reversed back is extruded over ``height`` in ``nz``
layers. The caps are the strips between front[i] and back[i] (valid for these profiles: the
back is the front offset by the sheet's thickness, corners mitred). Faces wind
counter-clockwise seen from outside, so their normals (right-hand rule) point outwards.
"""
from __future__ import annotations

import math

import numpy as np
import trimesh

# Where the examples stand (docs/model.md §21's panel, examples/paint.toml): the painted
# front near x = 0.70 m, centred at y = 0, z = 0.16 m, facing the robot (−x).
FRONT_X = 0.70
CENTRE_Z = 0.16
THICKNESS = 0.002  # m, sheet thickness


def extrude(front, back, height: float, nz: int, z0: float = CENTRE_Z) -> trimesh.Trimesh:
    """The closed mesh of the profile between ``front`` and ``back`` ((k, 2) x–y polylines,
    same k), extruded over z0 ± height/2 in ``nz`` layers."""
    front, back = np.asarray(front, float), np.asarray(back, float)
    outline = np.vstack([front, back[::-1]])
    x, y = outline[:, 0], outline[:, 1]
    signed = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    ccw = signed > 0  # seen from +z
    m = len(outline)
    zs = z0 + np.linspace(-height / 2, height / 2, nz + 1)
    verts = np.column_stack([np.tile(outline, (nz + 1, 1)), np.repeat(zs, m)])
    faces = []
    i = np.arange(m)
    j = (i + 1) % m
    for layer in range(nz):
        a, b = layer * m + i, layer * m + j
        c, d = b + m, a + m
        quads = np.column_stack([a, b, c, d]) if ccw else np.column_stack([b, a, d, c])
        faces += [quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]
    k = len(front)
    fi, bi = np.arange(k - 1), 2 * k - 1 - np.arange(k - 1)  # front[i], back[i] in outline
    strips = np.column_stack([fi, fi + 1, bi - 1, bi])  # front[i], front[i+1], back[i+1], back[i]
    for offset, up in ((nz * m, True), (0, False)):
        q = strips + offset
        tris = np.vstack([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
        p = verts[tris]
        nzc = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])[:, 2]
        keep = np.abs(nzc) > 1e-18
        tris, nzc = tris[keep], nzc[keep]
        flip = (nzc < 0) if up else (nzc > 0)
        tris[flip] = tris[flip][:, ::-1]
        faces.append(tris)
    mesh = trimesh.Trimesh(verts, np.vstack(faces), process=False)
    mesh.merge_vertices()
    return mesh


def _offset(front, distance: float) -> np.ndarray:
    """The polyline moved by ``distance`` to its +x side (away from the robot), corners
    mitred (each corner moves along the sum of its two segments' normals, so that both
    segments keep the distance)."""
    front = np.asarray(front, float)
    seg = np.diff(front, axis=0)
    seg /= np.linalg.norm(seg, axis=1)[:, None]
    normal = np.column_stack([seg[:, 1], -seg[:, 0]])
    normal *= 1.0 if normal[:, 0].sum() > 0 else -1.0  # the side of +x
    a = np.vstack([normal[:1], normal])  # before each point (the first: its segment's)
    b = np.vstack([normal, normal[-1:]])  # after each point
    return front + distance * (a + b) / (1.0 + np.einsum("ij,ij->i", a, b))[:, None]


def curved_panel(radius: float = 0.4, width: float = 0.24, height: float = 0.10,
                 step: float = 0.005, z0: float = CENTRE_Z) -> trimesh.Trimesh:
    """A cylinder section (axis vertical), convex towards the robot, its apex at FRONT_X:
    ``width`` is the arc length across y, centred at height ``z0``."""
    half = width / 2 / radius
    k = int(math.ceil(width / step)) + 1
    ang = np.linspace(-half, half, k)
    front = np.column_stack([FRONT_X + radius * (1 - np.cos(ang)), radius * np.sin(ang)])
    return extrude(front, _offset(front, THICKNESS), height, int(math.ceil(height / step)),
                   z0)


def chamfered_plate(length: float = 0.80, height: float = 0.33, chamfer: float = 0.04,
                    angle_deg: float = 40.0, z0: float = 0.18,
                    step: float = 0.01) -> trimesh.Trimesh:
    """A flat plate at x = FRONT_X, ``length`` along y and ``height`` along z (centred at
    height ``z0``), whose top and bottom ``chamfer`` [m of surface] bend away from the robot
    by ``angle_deg``: a door's bevelled edges across a horizontal line's travel. The profile
    is drawn in x–y and extruded, then turned +90° about x (y → z)."""
    a = math.radians(angle_deg)
    flat = height - 2 * chamfer * math.cos(a)
    k = int(math.ceil(flat / step)) + 1
    mid = np.column_stack([np.full(k, FRONT_X), np.linspace(-flat / 2, flat / 2, k)])
    s = np.linspace(0.0, chamfer, int(math.ceil(chamfer / step)) + 1)[1:]
    top = np.column_stack([FRONT_X + s * math.sin(a), flat / 2 + s * math.cos(a)])
    bottom = np.column_stack([FRONT_X + s * math.sin(a), -flat / 2 - s * math.cos(a)])[::-1]
    front = np.vstack([bottom, mid, top])
    mesh = extrude(front, _offset(front, THICKNESS), length, int(math.ceil(length / step)),
                   0.0)
    mesh.vertices = mesh.vertices @ np.array([[1.0, 0, 0], [0, 0, 1.0], [0, -1.0, 0]]) \
        + [0.0, 0.0, z0]  # (x, y, z) → (x, −z, y): +90° about x
    return mesh


def bent_plate(flat: float = 0.12, wing: float = 0.11, angle_deg: float = 30.0,
               fillet: float = 0.030, height: float = 0.10,
               step: float = 0.005) -> trimesh.Trimesh:
    """A plate at x = FRONT_X over y ∈ [−flat, 0], then a concave fillet of radius ``fillet``
    (seen from the robot) bending the ``wing`` towards the robot by ``angle_deg``."""
    ang = math.radians(angle_deg)
    pts = [np.column_stack([np.full(int(math.ceil(flat / step)) + 1, FRONT_X),
                            np.linspace(-flat, 0.0, int(math.ceil(flat / step)) + 1)])]
    # the fillet's centre lies on the robot's side (−x) of the plate
    c = np.array([FRONT_X - fillet, 0.0])
    arc = np.linspace(0.0, ang, max(3, int(math.ceil(fillet * ang / (step / 2)))) + 1)[1:]
    pts.append(c + fillet * np.column_stack([np.cos(arc), np.sin(arc)]))
    end = pts[-1][-1]
    direction = np.array([-math.sin(ang), math.cos(ang)])
    s = np.linspace(0.0, wing, int(math.ceil(wing / step)) + 1)[1:]
    pts.append(end + s[:, None] * direction)
    front = np.vstack(pts)
    return extrude(front, _offset(front, THICKNESS), height, int(math.ceil(height / step)))


def ribbed_plate(width: float = 0.24, height: float = 0.10, rib_height: float = 0.015,
                 rib_width: float = 0.006, rib_y: float = 0.0,
                 step: float = 0.005) -> trimesh.Trimesh:
    """A plate at x = FRONT_X over y ∈ ±width/2 with a vertical rib (running along z)
    ``rib_height`` towards the robot, ``rib_width`` wide, centred at y = ``rib_y``: a bead
    folded into the sheet (hollow behind, so ``rib_width`` > 2·THICKNESS)."""
    y1, y2 = rib_y - rib_width / 2, rib_y + rib_width / 2
    left = np.linspace(-width / 2, y1, int(math.ceil((y1 + width / 2) / step)) + 1)
    right = np.linspace(y2, width / 2, int(math.ceil((width / 2 - y2) / step)) + 1)
    top = FRONT_X - rib_height
    rib = [[top, y1], [top, y2]] if rib_height > 0 else np.zeros((0, 2))  # 0: a flat plate
    front = np.vstack([np.column_stack([np.full(len(left), FRONT_X), left]), rib,
                       np.column_stack([np.full(len(right), FRONT_X), right])])
    return extrude(front, _offset(front, THICKNESS), height, int(math.ceil(height / step)))


__all__ = ["CENTRE_Z", "FRONT_X", "THICKNESS", "bent_plate", "chamfered_plate", "curved_panel",
           "extrude", "ribbed_plate"]
