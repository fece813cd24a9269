"""The painted mesh refined to the film points (paint/film/ply_mesh.py)."""
import numpy as np
import trimesh

from pollard_pin.painting.film.ply_mesh import refined_mesh
from pollard_pin.painting.film.points import surface_points
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import make_part


def test_refined_mesh_covers_the_painted_faces():
    mesh = shapes.bent_plate(flat=0.12, wing=0.11, angle_deg=30.0, fillet=0.030, height=0.10)
    part = make_part(mesh.vertices, mesh.faces, max_angle=45.0)
    pts = surface_points(part, 0.004)
    used, tris = refined_mesh(part, pts)
    m = trimesh.Trimesh(pts.points[used], tris, process=False)
    # the same surface: its area, every film point a vertex, wound as the faces
    assert abs(m.area / part.painted_area - 1) < 1e-12
    assert len(used) == len(pts)
    assert (np.einsum("ij,ij->i", m.face_normals, pts.normals[used][tris[:, 0]]) > 0.999).all()
    # no sub-triangle edge longer than the resolution
    e = np.linalg.norm(m.vertices[m.edges[:, 0]] - m.vertices[m.edges[:, 1]], axis=1)
    assert e.max() <= 0.004 * (1 + 1e-9)


def test_refined_mesh_of_some_faces():
    tri = np.array([[0.7, 0, 0], [0.7, 0.1, 0], [0.7, 0, 0.1]])
    part = make_part(tri, np.array([[0, 2, 1]]))
    pts = surface_points(part, 0.1 * np.sqrt(2) / 4)  # the longest edge in 4
    used, tris = refined_mesh(part, pts)
    assert len(tris) == 16 and len(used) == 15
