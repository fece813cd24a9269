"""Points on a shadow's edge (docs/model.md §27.7): what a film that reuses another path's
shadows (:class:`.film.mesh.Shade`) may miss.

A gun path moved by δ (a deflection of tenths of a millimetre) moves each segment from a point
to the nozzle by at most δ, and the edge of the shadow a part casts on itself by at most δ
where the occluder lies nearer the point than the nozzle (a rib, a hole's wall: the shadow
moves by δ·λ/(L − λ), λ the occluder's distance from the point along a segment of length L).
A pair (sample k, point q) can change from lit to shaded or back only if q lies that close to
sample k's shadow edge. While δ is below the film point spacing h, such a point has a
neighbour (a point within h) on the other side of the edge at sample k: it is found from the
shade alone. A point's **edge film** E_q = Σ w_k·r_kq over the samples k where q or a
neighbour is shaded and the other is not (w the trapezoid weights with the trigger, r the
unshaded rate) bounds what the moved shadows change there: |T′_full − T′_reused| ≤ E_q. A
point that is never beside a shadow's edge has E_q = 0 and its reused film is the full one
(up to pairs at the spot's rim, e^(−12.5) of its centre, that enter or leave the ray test).
A shadow narrower than h is missed, as the film itself does not resolve it (§23).
"""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from ...dynamics.averages import trapezoid_weights
from ..spray.deposition import pair_rate
from ..spray.occlusion import visible
from .mesh import Shade, film_chunks
from .points import SurfacePoints

EDGE_BLOCK = 1_000_000  # shaded pairs × neighbours per vectorised block (~100 MB)
EDGE_PAIRS = 30_000_000  # pairs beside an edge kept at most (8 bytes each, sorted twice)


def neighbours(points: SurfacePoints) -> tuple[np.ndarray, np.ndarray]:
    """(indptr (P + 1,), indices) of each film point's neighbours: the points within the
    spacing h (every sub-triangle's edge is at most h, docs/model.md §23), the point itself
    left out; a crease's points at one place with two normals are neighbours."""
    s = points.points
    pairs = cKDTree(s).query_pairs(points.resolution * (1 + 1e-9), output_type="ndarray")
    a = np.r_[pairs[:, 0], pairs[:, 1]]
    b = np.r_[pairs[:, 1], pairs[:, 0]]
    order = np.argsort(a, kind="stable")
    indptr = np.r_[0, np.cumsum(np.bincount(a, minlength=len(s)))]
    return indptr, b[order]


class _ShadeIndex:
    """Looks pairs (sample k, point q) up among a :class:`.film.mesh.Shade`'s shaded pairs,
    its chunks those of the film of ``points`` with ``live`` sprayed samples."""

    def __init__(self, points: SurfacePoints, live: int, shade: Shade):
        P = len(points.points)
        self.chunks = film_chunks(points.points, live)
        self.chunk_of, self.local = np.empty(P, dtype=np.int64), np.empty(P, dtype=np.int64)
        for c, idx in enumerate(self.chunks):
            self.chunk_of[idx], self.local[idx] = c, np.arange(len(idx))
        self.shade = shade

    def dark(self, k, q) -> np.ndarray:
        out = np.zeros(len(k), dtype=bool)
        cq = self.chunk_of[q]
        order = np.argsort(cq, kind="stable")  # the pairs chunk by chunk, in their order
        ends = np.searchsorted(cq[order], np.arange(len(self.chunks) + 1))
        for c in range(len(self.chunks)):
            sel = order[ends[c]:ends[c + 1]]
            if not len(sel):
                continue
            out[sel] = _member(k[sel] * len(self.chunks[c]) + self.local[q[sel]],
                               self.shade.keys[c])
        return out


def edge_pairs(index: _ShadeIndex, points: SurfacePoints) -> np.ndarray | None:
    """The pairs beside a shadow's edge, sorted keys sample × P + point: (k, q) where q or a
    neighbour is shaded at sample k and the other is not (module docstring); None when they
    number more than EDGE_PAIRS (memory bounded: the caller casts every ray instead)."""
    P = len(points.points)
    indptr, nb = neighbours(points)
    count = np.diff(indptr)
    marked = [np.zeros(0, dtype=np.int64)]
    for c, idx in enumerate(index.chunks):
        key = index.shade.keys[c]
        for start in range(0, len(key), EDGE_BLOCK // 8):
            kb = key[start:start + EDGE_BLOCK // 8]
            k, q = kb // len(idx), idx[kb % len(idx)]
            rep = count[q]
            kk, qq = np.repeat(k, rep), np.repeat(q, rep)
            first = np.repeat(indptr[q] - np.r_[0, np.cumsum(rep)[:-1]], rep)
            other = nb[first + np.arange(len(kk))]
            lit = ~index.dark(kk, other)  # a neighbour on the other side of the edge
            marked.append(_unique(np.r_[kk[lit] * P + qq[lit], kk[lit] * P + other[lit]]))
            if sum(len(m) for m in marked) > EDGE_PAIRS:
                return None
    return _unique(np.concatenate(marked))


def _unique(x) -> np.ndarray:
    """np.unique of integer keys by a sort (numpy's hash table is slower here)."""
    x = np.sort(x)
    return x[np.r_[True, x[1:] != x[:-1]]] if len(x) else x


def _member(x, sorted_keys) -> np.ndarray:
    """(len(x),) True where x is among ``sorted_keys``."""
    if not len(sorted_keys):
        return np.zeros(len(x), dtype=bool)
    i = np.minimum(np.searchsorted(sorted_keys, x), len(sorted_keys) - 1)
    return sorted_keys[i] == x


def moved_shade(gun, t, p, a, spray, points: SurfacePoints, part, shade: Shade,
                intersector=None) -> tuple[Shade | None, np.ndarray]:
    """(the shade of the path through tips ``p`` (T, 3), axes ``a``, at times ``t`` with
    trigger ``spray``, the points' edge film E (P,) [m] on it) from ``shade``, the shadows of
    the same points, times and trigger on a path nearby: the pairs beside an edge
    (:func:`edge_pairs`) tested again with a ray to this path's nozzles, every other pair's
    verdict kept; the shadow edges in time to be found again (the shade carries no cuts).
    (None, E = 0) when the pairs beside an edge are more than EDGE_PAIRS."""
    t = np.asarray(t, dtype=float)
    trig = np.asarray(spray, dtype=float)
    s, n = points.points, points.normals
    P = len(s)
    index = _ShadeIndex(points, int((trig > 0).sum()), shade)
    pair = edge_pairs(index, points)
    if pair is None:
        return None, np.zeros(P)
    k, q = pair // P, pair % P
    now = ~visible(part, p[k], s[q], n[q], intersector)
    w = trapezoid_weights(t) * trig
    edge = np.zeros(P)
    for i in range(0, len(k), EDGE_BLOCK):  # the rate's temporaries in blocks
        kb, qb = k[i:i + EDGE_BLOCK], q[i:i + EDGE_BLOCK]
        edge += np.bincount(qb, weights=w[kb] * pair_rate(gun, p[kb], a[kb], s[qb], n[qb]),
                            minlength=P)
    keys = []
    for c, idx in enumerate(index.chunks):
        mine = index.chunk_of[q] == c
        local = k[mine] * len(idx) + index.local[q[mine]]
        old = shade.keys[c]
        dark = old[~_member(old, np.sort(local[~now[mine]]))]
        keys.append(_unique(np.r_[dark, local[now[mine]]]))
    return Shade(shade.points, shade.samples, tuple(keys), ()), edge


__all__ = ["EDGE_BLOCK", "EDGE_PAIRS", "edge_pairs", "moved_shade", "neighbours"]
