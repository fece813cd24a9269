"""Shadow edges in time: a gun passing a rib, the point behind it lit until the segment to
the nozzle meets the rib's top edge; the film against the exact integral up to that time."""
import math

import numpy as np
from scipy.integrate import quad

from pollard_pin.painting.spray.deposition import Gun, deposition_rate
from pollard_pin.painting.spray.occlusion import offset, visible
from pollard_pin.painting.spray.shadow_edges import shadow_edges
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import make_part

GUN = Gun(standoff=0.15, sigma=0.010, flow=1.5e-7)
X0, ZC = shapes.FRONT_X, shapes.CENTRE_Z


def _rate(s, yg):
    """docs/model.md §20 term by term: the gun at (X0 − standoff, yg, ZC) spraying along +x,
    the plate point s facing −x."""
    d = s - np.array([X0 - GUN.standoff, yg, ZC])
    h = d[0]
    rho2 = d[1] ** 2 + d[2] ** 2
    sig = GUN.sigma * h / GUN.standoff
    return GUN.flow / (2 * math.pi * sig ** 2) * math.exp(-rho2 / (2 * sig ** 2))


def test_film_behind_a_rib_is_the_exact_integral_to_its_edge():
    """Points on the plate at y_p left of the 6 mm wide, 15 mm high rib (walls y = ±3 mm):
    the segment to a gun at y_g passes the near wall's top once y_p + 0.1(y_g − y_p) = −3 mm
    (0.015/0.15 of the way, from the point moved off the plate as the segment test does).
    The gun moves σ/4 per sample along y; the trapezoid rule with the segment test at the
    samples plus shadow_edges' correction against quad of the rate up to that y_g: achieved
    1e-5 of the film (Embree's float32 places the edge to ~1e-6 m of gun travel: 4e-5 of
    the film at the spot's centre; 12 or 20 halvings, 3 to 7 slope points, alike); asserted
    1e-4 (the samples alone: 1.2 %)."""
    m = shapes.ribbed_plate(width=0.10, height=0.04, step=0.005)
    part = make_part(m.vertices, m.faces)
    yp = np.array([-0.0035, -0.0045, -0.006, -0.0081, -0.011])
    s = np.column_stack([np.full(len(yp), X0), yp, np.full(len(yp), ZC)])
    n = np.tile([-1.0, 0.0, 0.0], (len(yp), 1))
    y = np.arange(-0.08, 0.08 + 1e-12, GUN.sigma / 4)
    t = (y - y[0]) / 0.3
    p = np.column_stack([np.full(len(y), X0 - GUN.standoff), y, np.full(len(y), ZC)])
    a = np.tile([1.0, 0.0, 0.0], (len(y), 1))
    r = deposition_rate(GUN, p, a, s, n)  # (T, P)
    ti, pi = np.meshgrid(np.arange(len(t)), np.arange(len(yp)), indexing="ij")
    ti, pi = ti.ravel(), pi.ravel()
    vis = visible(part, p[ti], s[pi], n[pi]).reshape(r.shape)
    w = np.zeros(len(t))
    w[1:] += np.diff(t) / 2
    w[:-1] += np.diff(t) / 2
    samples = w @ (r * vis)
    fix, bound, switches, _ = shadow_edges(GUN, t, p, a, np.ones(len(t)), s, n, part,
                                        ti[~vis.ravel()], pi[~vis.ravel()])
    assert switches == len(yp)
    # where the segment meets the near wall's top, from the point moved eps off the plate
    # (occlusion.offset: 10 µm; it moves the edge by 10 µm of gun travel here)
    eps = offset(part)
    y_edge = yp + (-0.003 - yp) * (GUN.standoff - eps) / (0.015 - eps)
    exact = np.array([quad(lambda yg, si=si: _rate(si, yg), y[0], ye, points=[si[1]],
                           epsabs=0, epsrel=1e-12, limit=200)[0] / 0.3
                      for si, ye in zip(s, y_edge)])
    got = samples + fix
    assert np.abs(got / exact - 1).max() < 1e-4, got / exact - 1
    assert np.abs(samples / exact - 1).max() > 0.01
    assert (bound < 1e-3 * exact).all()
