"""The links' capsules (docs/model.md §26.4): the segment distance against brute force (dense
points of both segments, of both capsules' surfaces), the capsules at a configuration against
Pinocchio's own geometry placements, every shape held by its capsule."""
import math

import numpy as np
import pinocchio as pin
import pytest
from scipy.spatial import cKDTree

from pollard_pin.kinematics.capsules import (
    axis_spheres,
    capsule_layout,
    link_capsules,
    segment_distance,
)
from pollard_pin.kinematics.ik import inverse_kinematics


def _dense(p, q, n=401):
    s = np.linspace(0.0, 1.0, n)
    return p[:, None] + s[None, :, None] * (q - p)[:, None]


def test_segment_distance_against_dense_points():
    rng = np.random.default_rng(7)
    p1, q1, p2, q2 = rng.normal(size=(4, 600, 3))
    q1[:60] = p1[:60]  # points
    q2[60:120] = p2[60:120]
    q1[120:180] = p1[120:180]
    q2[120:180] = p2[120:180]
    q2[180:240] = p2[180:240] + 0.7 * (q1 - p1)[180:240]  # parallel
    q2[240:260] = p2[240:260] = p1[240:260] + [0.0, 0.0, 0.3]  # a point over a segment's end
    d = segment_distance(p1, q1, p2, q2)
    a, b = _dense(p1, q1), _dense(p2, q2)
    # the nearest pair of dense points (an exact nearest-neighbour search: the same numbers
    # as every pair's distance, 12× faster)
    brute = np.array([cKDTree(b[i]).query(a[i])[0].min() for i in range(len(d))])
    # dense points never beat the exact distance (achieved: 4e-16); they approach it within
    # half a step of each segment (≤ 2.5e-3 × length), achieved 1.5e-3
    assert (brute - d).min() > -1e-13
    steps = (np.linalg.norm(q1 - p1, axis=1) + np.linalg.norm(q2 - p2, axis=1)) / 400
    assert ((brute - d) <= steps / 2 + 1e-13).all()


def test_capsule_distance_against_surface_points():
    # two capsules' surfaces sampled densely: their least gap is the segment distance less
    # both radii (achieved within 4e-5 m at these samplings; bound 4e-3)
    rng = np.random.default_rng(3)

    def surface(p, q, r, n=60, m=48):
        d = q - p
        u = d / np.linalg.norm(d)
        e1 = np.cross(u, [0.3, 0.5, 0.8])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(u, e1)
        th, ph = np.meshgrid(np.linspace(0, 2 * np.pi, m), np.linspace(-1, 1, n))
        ring = (np.cos(th)[..., None] * e1 + np.sin(th)[..., None] * e2) * r
        cyl = (p + (ph[..., None] + 1) / 2 * d + ring).reshape(-1, 3)
        sph = rng.normal(size=(4000, 3))
        sph = r * sph / np.linalg.norm(sph, axis=1, keepdims=True)
        return np.concatenate([cyl, p + sph, q + sph])

    seen = 0
    for _ in range(5):
        p1, q1, p2, q2 = rng.normal(size=(4, 3)) * 0.3
        r1, r2 = rng.uniform(0.01, 0.05, 2)
        exact = segment_distance(p1, q1, p2, q2) - r1 - r2
        s1, s2 = surface(p1, q1, r1), surface(p2, q2, r2)
        brute = cKDTree(s2).query(s1)[0].min()
        if exact > 0:
            assert exact - 1e-12 <= brute <= exact + 4e-3
            seen += 1
    assert seen >= 4


@pytest.fixture(scope="module")
def configurations(robot):
    rng = np.random.default_rng(5)
    poses = np.array(robot.params.home_pose) + rng.uniform(-1, 1, (40, 6)) * [
        0.03, 0.15, 0.08, 0.2, 0.2, 0.3]
    return inverse_kinematics(robot, poses, t=np.arange(40.0)).q


def test_capsules_follow_pinocchios_geometry(robot, configurations):
    """Each shape's placement by Pinocchio (updateGeometryPlacements, a replay outside the
    batched tree) carries the shape's own ends to the capsule's (achieved 2e-16 m)."""
    lay = capsule_layout(robot)
    a, b, r = link_capsules(robot, configurations)
    model, data = robot.model, robot.model.createData()
    shapes = {g.name: (i, g) for i, g in enumerate(robot.collision_model.geometryObjects)}
    shapes.update({g.name: (i, g) for i, g in enumerate(robot.visual_model.geometryObjects)
                   if g.name not in shapes})
    for n, q in enumerate(configurations):
        pin.framesForwardKinematics(model, data, q)
        for c, name in enumerate(lay.names):
            _, g = shapes[name]
            M = data.oMi[g.parentJoint] * g.placement
            G = g.geometry
            kind = type(G).__name__
            if kind == "Sphere":
                ends = [M.translation, M.translation]
            elif kind == "Cylinder":
                ends = [M.act(np.array([0, 0, s * G.halfLength])) for s in (-1, 1)]
            else:
                k = int(np.argmax(G.halfSide))
                e = np.zeros(3)
                e[k] = G.halfSide[k]
                ends = [M.act(-e), M.act(e)]
            assert np.allclose([a[n, c], b[n, c]], ends, atol=1e-12)
    assert np.array_equal(r, lay.r)


def test_every_shape_is_held(robot):
    """Random points of every box, cylinder and sphere (in its own frame) lie within the
    capsule's radius of its segment (by 1e-12 m round-off)."""
    lay = capsule_layout(robot)
    rng = np.random.default_rng(11)
    by_name = {g.name: g for g in (*robot.collision_model.geometryObjects,
                                   *robot.visual_model.geometryObjects)}
    for c, name in enumerate(lay.names):
        g = by_name[name]
        G, M = g.geometry, g.placement
        u = rng.uniform(-1, 1, (3000, 3))
        kind = type(G).__name__
        if kind == "Box":
            local = u * G.halfSide
        elif kind == "Cylinder":
            local = np.column_stack([u[:, :2] / np.sqrt(2) * G.radius, u[:, 2] * G.halfLength])
            local = local[np.hypot(local[:, 0], local[:, 1]) <= G.radius]
        else:
            local = u[np.linalg.norm(u, axis=1) <= 1] * G.radius
        pts = local @ M.rotation.T + M.translation
        d = segment_distance(pts, pts, lay.a[c], lay.b[c])
        assert d.max() <= lay.r[c] + 1e-12, name
    assert len(lay) == 25 and lay.gun.sum() == 2


def test_axis_spheres_hold_their_capsules():
    """A point of a capsule lies in a sphere of its axis (20,000 random points each)."""
    rng = np.random.default_rng(2)
    a = np.array([[0.0, 0, 0], [0.1, 0.2, 0.0], [0.3, 0, 0]])
    b = np.array([[0.33, 0, 0], [0.1, 0.2, 0.0], [0.3, 0.05, 0.01]])
    r = np.array([0.008, 0.014, 0.0186])
    owner, frac, radii = axis_spheres(a, b, r, 0.02)
    centres = a[owner] + frac[:, None] * (b - a)[owner]
    for c in range(3):
        s = rng.uniform(0, 1, 20000)[:, None]
        off = rng.normal(size=(20000, 3))
        off *= r[c] * rng.uniform(0, 1, (20000, 1)) ** (1 / 3) / np.linalg.norm(
            off, axis=1, keepdims=True)
        pts = a[c] + s * (b[c] - a[c]) + off
        mine = owner == c
        inside = (np.linalg.norm(pts[:, None] - centres[mine][None], axis=2)
                  <= radii[mine][None] + 1e-12).any(axis=1)
        assert inside.all()
        spacing = np.linalg.norm(b[c] - a[c]) / max(mine.sum() - 1, 1)
        assert spacing <= r[c] + 1e-12
        assert np.allclose(radii[mine], math.hypot(r[c], spacing / 2) if mine.sum() > 1
                           else r[c])
