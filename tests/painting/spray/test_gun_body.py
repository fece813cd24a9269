"""The gun's body (docs/model.md §25): the shipped gun link by hand, and the spheres holding
their capsules (random points of each capsule, brute force)."""
import math

import numpy as np
import pytest

from pollard_pin.errors import InputError
from pollard_pin.model.params import load_params
from pollard_pin.painting.spray.gun_body import GunBody, gun_body

# model/urdf.py's gun link by hand (x1918 = 0.06 m): the nozzle, r 4 mm over 18 mm, sampled
# every 3.6 mm (ceil(18/4) = 5 steps); the box 22 × 30 mm over 42 mm, held by r = √(11² +
# 15²) mm, sampled every 14 mm (ceil(42/18.6) = 3 steps).
NOZZLE_SPHERE = math.hypot(0.004, 0.0018)
BODY_SPHERE = math.hypot(math.hypot(0.011, 0.015), 0.007)


def test_the_default_body_is_the_gun_link_by_hand():
    offs, radii = GunBody().axis_points()
    np.testing.assert_allclose(offs, [0, 0.0036, 0.0072, 0.0108, 0.0144, 0.018,
                                      0.018, 0.032, 0.046, 0.06], atol=1e-15)
    np.testing.assert_allclose(radii[:6], NOZZLE_SPHERE, rtol=1e-14)
    np.testing.assert_allclose(radii[6:], BODY_SPHERE, rtol=1e-14)
    assert gun_body() == GunBody() == gun_body(load_params())
    assert GunBody().reach == pytest.approx(0.06, abs=1e-15)


@pytest.mark.parametrize("body", [GunBody(), GunBody(0.01, 0.05, 0.002, 0.031, 0.007)])
def test_the_spheres_hold_the_capsules(body):
    offs, radii = body.axis_points()
    rng = np.random.default_rng(5)
    for a, b, r in ((0.0, body.nozzle_length, body.nozzle_radius),
                    (body.nozzle_length, body.nozzle_length + body.length, body.radius)):
        n = 20000  # points of the capsule: within r of its axis segment
        x = rng.uniform(a - r, b + r, n)
        yz = rng.normal(size=(n, 2))
        yz *= (r * rng.uniform(0, 1, n) ** 0.5 / np.linalg.norm(yz, axis=1))[:, None]
        inside = np.hypot(np.clip(x, a, b) - x, np.linalg.norm(yz, axis=1)) <= r
        p = np.column_stack([x, yz])[inside]
        d = np.linalg.norm(p[:, None] - np.column_stack([offs, 0 * offs, 0 * offs])[None],
                           axis=2) - radii
        assert d.min(axis=1).max() <= 1e-12


@pytest.mark.parametrize("field, value", [("radius", -1.0), ("length", float("nan")),
                                          ("step", 0.0), ("nozzle_radius", True),
                                          ("nozzle_length", 2.0)])
def test_bad_values_are_one_line(field, value):
    with pytest.raises(InputError, match=f"GunBody.{field}"):
        GunBody(**{field: value})
