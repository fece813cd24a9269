"""The capsules' spheres made where asked are the whole array's, to the bit, and each is on
its capsule's axis with a radius that holds the capsule's cross-section."""
from types import SimpleNamespace

import numpy as np
import pytest

from pollard_pin.kinematics.capsules import axis_spheres
from pollard_pin.painting.checks.spheres import CapsuleSpheres
from pollard_pin.painting.spray.gun_body import AXIS_STEP


@pytest.fixture(scope="module")
def spheres():
    rng = np.random.default_rng(7)
    n, caps = 37, 6
    layout = SimpleNamespace(a=rng.normal(size=(caps, 3)) * 0.1,
                             b=rng.normal(size=(caps, 3)) * 0.1,
                             r=rng.uniform(0.005, 0.03, caps))
    a = rng.normal(size=(n, caps, 3))
    b = a + rng.normal(size=(n, caps, 3)) * 0.08
    chosen = np.array([0, 2, 3, 5])  # some capsules, as the part check asks
    return layout, a, b, chosen, CapsuleSpheres.of(a, b, layout, chosen)


def test_made_where_asked_is_the_whole_array(spheres):
    layout, a, b, chosen, s = spheres
    whole = s[:]
    owner, frac, radii = axis_spheres(layout.a[chosen], layout.b[chosen], layout.r[chosen],
                                      AXIS_STEP)
    cap = chosen[owner]
    # the formula written out, sphere by sphere: a + frac·(b − a) of its capsule
    direct = a[:, cap] + frac[None, :, None] * (b[:, cap] - a[:, cap])
    assert s.shape == whole.shape == (len(a), len(cap), 3) and len(s) == len(a)
    np.testing.assert_allclose(whole, direct, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(s.radii, radii)
    # a block of samples, the gathered pairs and one sphere: the same bits as the whole
    np.testing.assert_array_equal(s[5:20], whole[5:20])
    rows = np.array([0, 3, 3, 36, 17])
    ks = np.array([0, len(cap) - 1, 4, 2, 9])
    np.testing.assert_array_equal(s[rows, ks], whole[rows, ks])
    np.testing.assert_array_equal(s[11, 3], whole[11, 3])


def test_each_sphere_is_on_its_capsules_axis(spheres):
    layout, a, b, chosen, s = spheres
    whole = s[:]
    cap = s.cap
    ab = b[:, cap] - a[:, cap]
    t = np.einsum("nsk,nsk->ns", whole - a[:, cap], ab) / np.einsum("nsk,nsk->ns", ab, ab)
    off = np.linalg.norm(whole - (a[:, cap] + t[..., None] * ab), axis=-1)
    assert off.max() < 1e-14 and t.min() > -1e-12 and t.max() < 1 + 1e-12
    assert np.all(s.radii >= layout.r[cap])  # each holds its capsule's radius
