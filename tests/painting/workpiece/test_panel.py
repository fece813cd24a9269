"""The panel's frame (paint/target/panel.py): orthonormal and right-handed, v the world z
projected on the plane, the spray rotation proper, world points on the plane; each against
numpy's cross product and norms."""
import numpy as np
import pytest

from pollard_pin.painting.job import PaintJob
from pollard_pin.painting.workpiece.panel import panel_frame


@pytest.mark.parametrize("normal", [(-1.0, 0.0, 0.0), (-0.866, 0.5, 0.0), (-0.6, 0.3, 0.5)])
def test_frame_is_orthonormal_with_v_up(normal):
    n = np.array(normal) / np.linalg.norm(normal)
    job = PaintJob(center=(0.7, 0.0, 0.16), normal=tuple(n), width=0.26, height=0.12,
                   standoff=0.15, sigma=0.01, flow=1.5e-7, thickness=25e-6)
    f = panel_frame(job)
    B = np.column_stack([f.u, f.v, f.n])
    assert np.abs(B.T @ B - np.eye(3)).max() < 1e-14  # achieved ≤ 4.5e-16 here and below
    assert np.abs(np.cross(f.n, f.v) - f.u).max() < 1e-14  # u = n × v
    up = np.array([0.0, 0.0, 1.0]) - n[2] * n
    assert np.abs(f.v - up / np.linalg.norm(up)).max() < 1e-14
    R = f.rotation
    assert abs(np.linalg.det(R) - 1) < 1e-14 and np.abs(R[:, 0] + n).max() < 1e-14
    p = f.world(np.array([0.1, -0.05]), np.array([0.02, 0.04]), offset=0.15)
    assert np.abs((p - f.c) @ f.n - 0.15).max() < 1e-14
    assert np.abs((p - f.c) @ f.u - [0.1, -0.05]).max() < 1e-14
