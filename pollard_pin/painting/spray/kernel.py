"""The compiled loops of the film's hot path: the round Gaussian spot's deposition rate and
each source's height over each point's tangent plane for a block of sources × points, in one
pass with no temporaries, and the cull's cone test point by point, alone or before the rate
on the points it keeps (docs/model.md §20).

The loop is C (the repository's ``csrc/deposit.c``), compiled into ``_deposit`` when the
package is installed (as :mod:`pollard_pin.kinematics.kernels`). It takes each pair's
d = s − p as :func:`.deposition.pair_rate` does and then does ``_rate``'s operations in their
order without FMA contraction, so it differs from numpy's block formulation
(:meth:`.deposition.Sources.numpy_rate_and_height`, whose expanded |d|² = s·s + p·p − 2 s·p
rounds worse the further the coordinates lie from their origin) only by round-off. This front
makes the inputs C-contiguous float64, allocates the outputs and checks the shapes; the C side
checks every buffer's size.
"""
from __future__ import annotations

import numpy as np

from ...compiled import extension, f64

_c = extension("pollard_pin.painting.spray._deposit")


def round_rate(p, a, s, n, k: float, coef: float) -> tuple[np.ndarray, np.ndarray]:
    """(rate (T, P), height (T, P)) of sources ``p`` (T, 3) on unit axes ``a`` (T, 3) at
    points ``s`` (P, 3) of unit normals ``n`` ((P, 3) or (3,)): the round Gaussian spot of
    σ(h) = ``k``·h and flow/2π = ``coef`` (docs/model.md §20); the height is each source's
    (p − s)·n."""
    p, a, s, n = f64(p), f64(a), f64(s), f64(n)
    T, P = len(p), len(s)
    if not (p.shape == a.shape == (T, 3) and s.shape == (P, 3) and n.shape in ((3,), (P, 3))):
        raise ValueError(f"round_rate: sources {p.shape}, axes {a.shape}, points {s.shape} "
                         f"and normals {n.shape}: expected (T, 3), (T, 3), (P, 3), and (P, 3) "
                         "or (3,)")
    rate, height = np.empty((T, P)), np.empty((T, P))
    _c.round_rate(s, n, n.ndim == 2, p, a, T, P, float(k), float(coef), rate, height)
    return rate, height


def cone_keep(s, cone, radius=0.0) -> np.ndarray:
    """(P,) True where the cone ``cone`` keeps a point of ``s`` (P, 3) (or a ball of
    ``radius`` (one, or (P,)) about it): :meth:`.deposition.Reach.keep`'s test point by point,
    its numpy formula's operations in their order (docs/model.md §20). ``cone``: (10,) the
    mean tip p̄, unit mean axis ā, δp, δa, the cone's half-angle and throw/4 + δp."""
    s, cone = f64(s), f64(cone)
    radius = f64(np.ravel(radius))
    if not (s.ndim == 2 and s.shape[1] == 3 and len(radius) in (1, len(s))):
        raise ValueError(f"cone_keep: points {s.shape} and radii {radius.shape}: expected "
                         "(P, 3) and (P,) or one")
    keep = np.empty(len(s), dtype=bool)
    _c.cone_keep(s, len(s), radius, len(radius) > 1, cone, keep)
    return keep


def round_near(p, a, s, n, group, held, cone, k: float, coef: float) -> tuple:
    """(kept (K,), rate (T, K), height (T, K)): the points of ``s`` (P, 3) whose group
    (``group`` (P,) into ``held`` (G,) bool) may hold a kept point and that the cone ``cone``
    keeps (:func:`cone_keep`'s (10,); None: every such point), in ascending order, with
    :func:`round_rate` of them (normals ``n`` (P, 3) or (3,)), in one compiled call."""
    p, a, s, n = f64(p), f64(a), f64(s), f64(n)
    group = np.ascontiguousarray(group, dtype=np.int64)
    held = np.ascontiguousarray(held, dtype=bool)
    T, P = len(p), len(s)
    if not (p.shape == a.shape == (T, 3) and s.shape == (P, 3) and n.shape in ((3,), (P, 3))
            and group.shape == (P,) and held.ndim == 1):
        raise ValueError(f"round_near: sources {p.shape}, axes {a.shape}, points {s.shape}, "
                         f"normals {n.shape}, groups {group.shape} and held {held.shape}: "
                         "expected (T, 3), (T, 3), (P, 3), (P, 3) or (3,), (P,) and (G,)")
    kept, rate, height = np.empty(P, dtype=np.int64), np.empty(T * P), np.empty(T * P)
    K = _c.round_near(s, n, n.ndim == 2, group, held, P, len(held),
                      b"" if cone is None else f64(cone), p, a, T, float(k), float(coef),
                      kept, rate, height)
    return kept[:K], rate[:T * K].reshape(T, K), height[:T * K].reshape(T, K)


__all__ = ["cone_keep", "round_near", "round_rate"]
