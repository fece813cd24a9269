"""Conservative capsules around the robot's links, stacked over samples (docs/model.md §26.4).

Each collision or visual shape of the model (the URDF's ``<collision>`` and ``<visual>``
elements, model/urdf.py; the ball joints are drawn only) is held by one capsule, the points
within ``r`` of a segment a–b fixed in its joint's frame:

- a cylinder (radius r, along its axis): the capsule of its axis, radius r (its end caps add
  at most r beyond the flat ends);
- a sphere: a capsule of one point;
- a box: the capsule of its longest centre line, radius half the diagonal of the other two
  sides (every point of the box lies within that of the line);
- a capsule: itself.

The gun link's box and nozzle give the two capsules of the paint gun's body
(paint/spray/gun_body.py holds the same two). Segment–segment distances are vectorised
(:func:`segment_distance`, the clamped closest points of Ericson, *Real-Time Collision
Detection* §5.1.9).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .tree import joint_placements

SHAPES = ("Cylinder", "Sphere", "Box", "Capsule")
_EPS = 1e-18  # m²: a segment shorter than 1 nm is a point


@dataclass(frozen=True, eq=False)
class CapsuleLayout:
    """The robot's capsules (L of them) in their joints' frames: ``names`` (the collision
    shapes'), ``joint`` (L,) the joint moving each (0: the base), ends ``a``, ``b`` (L, 3)
    [m] and radii ``r`` (L,) [m]; ``gun`` (L,) marks the capsules of the tool's link."""

    names: tuple[str, ...]
    joint: np.ndarray
    a: np.ndarray
    b: np.ndarray
    r: np.ndarray
    gun: np.ndarray

    def __len__(self) -> int:
        return len(self.names)


def _ends(geometry) -> tuple[np.ndarray, np.ndarray, float]:
    """A shape's capsule in the shape's own frame: (a, b, r)."""
    kind = type(geometry).__name__
    if kind in ("Cylinder", "Capsule"):
        h = float(geometry.halfLength)
        return np.array([0.0, 0.0, -h]), np.array([0.0, 0.0, h]), float(geometry.radius)
    if kind == "Sphere":
        return np.zeros(3), np.zeros(3), float(geometry.radius)
    half = np.abs(np.asarray(geometry.halfSide, float))
    k = int(np.argmax(half))
    a = np.zeros(3)
    a[k] = -half[k]
    return a, -a, math.hypot(*np.delete(half, k))


def capsule_layout(robot) -> CapsuleLayout:
    """The capsules of ``robot``'s collision and visual shapes (module notes; a visual shape
    that repeats a collision one counted once: the ball joints are drawn only); one line
    naming a shape that is not a cylinder, sphere, box or capsule."""
    tip_joint = int(robot.model.frames[robot.tip_frame].parentJoint)
    seen, names, joints, a, b, r = set(), [], [], [], [], []
    for g in (*robot.collision_model.geometryObjects, *robot.visual_model.geometryObjects):
        if type(g.geometry).__name__ not in SHAPES:
            raise InputError(f"shape {g.name!r} is a {type(g.geometry).__name__}: the "
                             f"clearance check takes {', '.join(SHAPES[:-1])} or "
                             f"{SHAPES[-1]} shapes")
        ea, eb, er = _ends(g.geometry)
        R, p = g.placement.rotation, g.placement.translation
        ends = (R @ ea + p, R @ eb + p)
        key = (int(g.parentJoint), *np.round(np.concatenate(ends), 9), round(er, 9))
        if key in seen:
            continue
        seen.add(key)
        names.append(g.name)
        joints.append(int(g.parentJoint))
        a.append(ends[0])
        b.append(ends[1])
        r.append(er)
    joint = np.array(joints, dtype=np.int64)
    return CapsuleLayout(tuple(names), joint, np.array(a).reshape(-1, 3),
                         np.array(b).reshape(-1, 3), np.array(r, float), joint == tip_joint)


def link_capsules(robot, q, layout: CapsuleLayout | None = None):
    """Conservative capsules around the links at closed configurations, the geometry of a
    cell's clearance check (docs/model.md §26.4).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    q : numpy.ndarray
        Configurations (N, nq), loops closed (an IK's ``q``).
    layout : CapsuleLayout or None, optional
        Which links and radii (default: ``capsule_layout(robot)``'s).

    Returns
    -------
    a, b : numpy.ndarray
        The capsules' end points (N, L, 3) [m] in the base frame.
    r : numpy.ndarray
        Their radii (L,) [m].
    """
    lay = capsule_layout(robot) if layout is None else layout
    q = np.atleast_2d(np.asarray(q, float))
    model = robot.model
    moving = sorted({int(j) for s in lay.joint if s for j in model.supports[int(s)][1:]})
    pl = joint_placements(model, q, moving)
    n = len(q)
    a, b = np.empty((n, len(lay), 3)), np.empty((n, len(lay), 3))
    for j in np.unique(lay.joint):
        cols = np.flatnonzero(lay.joint == j)
        if j == 0:  # the base: fixed in the base frame
            a[:, cols], b[:, cols] = lay.a[cols], lay.b[cols]
            continue
        R, o = pl[int(j)]
        a[:, cols] = np.einsum("nij,cj->nci", R, lay.a[cols]) + o[:, None]
        b[:, cols] = np.einsum("nij,cj->nci", R, lay.b[cols]) + o[:, None]
    return a, b, lay.r.copy()


def segment_distance(p1, q1, p2, q2) -> np.ndarray:
    """The distance between segments p1–q1 and p2–q2 (each (..., 3), broadcast): the
    clamped closest points of both (Ericson §5.1.9), points (p = q) included."""
    p1, q1, p2, q2 = (np.asarray(x, float) for x in (p1, q1, p2, q2))
    d1, d2, w = q1 - p1, q2 - p2, p1 - p2
    a = np.einsum("...i,...i->...", d1, d1)
    e = np.einsum("...i,...i->...", d2, d2)
    b = np.einsum("...i,...i->...", d1, d2)
    c = np.einsum("...i,...i->...", d1, w)
    f = np.einsum("...i,...i->...", d2, w)
    pa, pe = a <= _EPS, e <= _EPS
    sa, se = np.where(pa, 1.0, a), np.where(pe, 1.0, e)
    denom = a * e - b * b  # ≥ 0; 0: parallel, any s is as good: s = 0
    s = np.where(denom > 0, np.clip((b * f - c * e) / np.where(denom > 0, denom, 1.0), 0, 1), 0)
    t = (b * s + f) / se
    # t outside [0, 1]: clamp it and recompute s for the clamped t
    s = np.where(t < 0, np.clip(-c / sa, 0, 1), np.where(t > 1, np.clip((b - c) / sa, 0, 1), s))
    t = np.clip(t, 0.0, 1.0)
    # a point for either segment
    s = np.where(pe, np.clip(-c / sa, 0, 1), s)
    t = np.where(pe, 0.0, t)
    s = np.where(pa, 0.0, s)
    t = np.where(pa, np.where(pe, 0.0, np.clip(f / se, 0, 1)), t)
    gap = p1 + s[..., None] * d1 - p2 - t[..., None] * d2
    return np.sqrt(np.einsum("...i,...i->...", gap, gap))


def axis_spheres(a, b, r, step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Spheres whose union holds each capsule: for capsules with ends a, b (L, 3) in one
    frame and radii r (L,), centres on each axis at spacing h ≤ min(step, r) (ends
    included), radius √(r² + (h/2)²) (the rule of paint/spray/gun_body.py). Returns the
    (S, 3) centres' weights as (owner (S,), fraction along the axis (S,), radii (S,))."""
    length = np.linalg.norm(np.asarray(b, float) - np.asarray(a, float), axis=-1)
    owner, frac, radii = [], [], []
    for i, (ln, ri) in enumerate(zip(length.reshape(-1), np.asarray(r, float))):
        h_max = min(step, ri) if ri > 0 else step
        k = max(2, math.ceil(ln / h_max) + 1) if ln > 0 else 1
        owner.append(np.full(k, i))
        frac.append(np.linspace(0.0, 1.0, k) if k > 1 else np.zeros(1))
        radii.append(np.full(k, math.hypot(ri, ln / max(k - 1, 1) / 2)))
    return np.concatenate(owner), np.concatenate(frac), np.concatenate(radii)


__all__ = ["CapsuleLayout", "axis_spheres", "capsule_layout", "link_capsules",
           "segment_distance"]
