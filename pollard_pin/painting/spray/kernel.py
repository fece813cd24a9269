"""The compiled loop of the film's hot path: the round Gaussian spot's deposition rate and
each source's height over each point's tangent plane for a block of sources × points, in one
pass with no temporaries (docs/model.md §20).

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

try:
    from . import _deposit as _c
except ImportError as exc:  # a source tree used without installing it
    raise ImportError(f"pollard_pin's compiled kernels are missing ({exc}); install the "
                      "package (`pip install .` or `pip install -e .`, which needs a C "
                      "compiler) instead of importing it from the source tree") from None


def _f64(x):
    return np.ascontiguousarray(x, dtype=np.float64)


def round_rate(p, a, s, n, k: float, coef: float) -> tuple[np.ndarray, np.ndarray]:
    """(rate (T, P), height (T, P)) of sources ``p`` (T, 3) on unit axes ``a`` (T, 3) at
    points ``s`` (P, 3) of unit normals ``n`` ((P, 3) or (3,)): the round Gaussian spot of
    σ(h) = ``k``·h and flow/2π = ``coef`` (docs/model.md §20); the height is each source's
    (p − s)·n."""
    p, a, s, n = _f64(p), _f64(a), _f64(s), _f64(n)
    T, P = len(p), len(s)
    if not (p.shape == a.shape == (T, 3) and s.shape == (P, 3) and n.shape in ((3,), (P, 3))):
        raise ValueError(f"round_rate: sources {p.shape}, axes {a.shape}, points {s.shape} "
                         f"and normals {n.shape}: expected (T, 3), (T, 3), (P, 3), and (P, 3) "
                         "or (3,)")
    rate, height = np.empty((T, P)), np.empty((T, P))
    _c.round_rate(s, n, n.ndim == 2, p, a, T, P, float(k), float(coef), rate, height)
    return rate, height


__all__ = ["round_rate"]
