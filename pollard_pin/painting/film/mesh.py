"""The film a gun path leaves on a part's mesh (docs/model.md §20): the deposition rate at
each film point with its own normal, zero where the part shades the point from the nozzle
(:mod:`.spray.occlusion`), times the gun's trigger, integrated by the trapezoid rule in time
(as :func:`.spray.deposition.film`, in blocks of samples of bounded memory), with the steps where
a point's shade switches integrated apart (:mod:`.spray.shadow_edges`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...dynamics.averages import trapezoid_weights
from ..errors import MeshError
from ..progress import bar
from ..spray.deposition import BLOCK_ELEMENTS, Gun, coarse_weights, deposition_rate, near_spot
from ..spray.occlusion import in_spot, visible
from ..spray.shadow_edges import shadow_edges
from ..workpiece.mesh import Part
from .points import SurfacePoints


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class MeshFilm:
    """Film ``thickness`` (P,) [m] at the points and its error estimate (P,) [m]: the
    trapezoid rule's |T − T₂| (as :class:`.spray.deposition.Film`), at points whose shade switches
    that of the unshaded rate plus the shadow edges' bound (:mod:`.spray.shadow_edges`);
    ``switches`` (point, step) pairs integrated apart; ``pairs`` (sample, point) inside the
    spray spot tested for shade and ``shaded`` of them; ``sprayed`` = ∫ flow·spray dt [m³];
    ``landed`` = Σ thickness × area [m³] over the points."""

    thickness: np.ndarray
    error_estimate: np.ndarray
    pairs: int
    shaded: int
    sprayed: float
    landed: float
    whole_part: bool  # the points cover every face of the part
    switches: int = 0

    @property
    def transfer_efficiency(self) -> float | None:
        """Volume landing on the part over volume sprayed (None unless the points cover
        every face: film points made with faces="all")."""
        if not self.whole_part or self.sprayed <= 0:
            return None
        return self.landed / self.sprayed


def _spray(spray, n: int) -> np.ndarray:
    if spray is None:
        return np.ones(n)
    s = np.asarray(spray, dtype=float)
    if s.shape != (n,):
        raise MeshError(f"spray has shape {s.shape}, expected ({n},): one trigger fraction "
                        "per time sample")
    bad = ~(np.isfinite(s) & (s >= 0) & (s <= 1))
    if bad.any():
        k = int(np.argmax(bad))
        raise MeshError(f"spray[{k}] = {s[k]:.4g} must lie in [0, 1] (the fraction of the "
                        "flow the trigger lets through)")
    return s


def mesh_film(gun: Gun, t, p, a, points: SurfacePoints, part: Part, spray=None,
              origin=None, intersector=None) -> MeshFilm:
    """Film at ``points`` (their own positions and normals) after the gun passes through the
    tips ``p`` (T, 3) with axes ``a`` (T, 3) at times ``t`` (T,), spraying ``spray`` (T,) ×
    flow (the trigger, in [0, 1]; None: 1 throughout). Pairs inside the spray spot whose
    segment to the nozzle crosses the part get nothing (:mod:`.spray.occlusion`). ``origin`` (3,):
    subtracted from every position for the rate's matrix products (default: the points'
    mean); ``intersector``: the ray engine (default ``part.mesh.ray``)."""
    t = np.asarray(t, dtype=float)
    p, a = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, a))
    if not (p.shape == a.shape == (len(t), 3)):
        raise MeshError(f"gun positions {p.shape} and axes {a.shape} must both be "
                        f"({len(t)}, 3), one per time sample")
    trig = _spray(spray, len(t))
    s, n = points.points, points.normals
    o = s.mean(axis=0) if origin is None else np.asarray(origin, dtype=float)
    w, w2 = trapezoid_weights(t) * trig, coarse_weights(t) * trig
    total, coarse = np.zeros(len(s)), np.zeros(len(s))
    smooth, smooth2 = np.zeros(len(s)), np.zeros(len(s))  # the rule on the unshaded rate
    dark_t, dark_p = [], []  # the shaded pairs
    pairs = shaded = 0
    block = max(1, BLOCK_ELEMENTS // max(len(s), 1))
    for start in bar(range(0, len(t), block), "film"):
        sl = slice(start, start + block)
        live = np.flatnonzero(trig[sl] > 0)  # a closed trigger deposits nothing: skip it
        if not len(live):
            continue
        ps, as_ = p[sl][live], a[sl][live]
        k = near_spot(gun, ps, as_, s)  # the rest get < 3e-18 of the spot's rate (§20)
        r = deposition_rate(gun, ps - o, as_, s[k] - o, n[k])
        ti, ri = np.nonzero(in_spot(gun, r))
        pi = k[ri]
        smooth[k] += w[sl][live] @ r
        smooth2[k] += w2[sl][live] @ r
        if len(ti):
            vis = visible(part, ps[ti], s[pi], n[pi], intersector)
            r[ti[~vis], ri[~vis]] = 0.0
            dark_t.append(start + live[ti[~vis]])
            dark_p.append(pi[~vis])
            pairs, shaded = pairs + len(ti), shaded + int((~vis).sum())
        total[k] += w[sl][live] @ r
        coarse[k] += w2[sl][live] @ r
    err = np.abs(total - coarse) if len(t) > 2 else np.full(len(s), np.nan)
    if dark_t:
        fix, bound, switches = shadow_edges(gun, t, p, a, trig, s, n, part,
                                            np.concatenate(dark_t), np.concatenate(dark_p),
                                            intersector)
        total += fix
        edge = bound > 0
        if len(t) > 2:
            err = np.where(edge, np.abs(smooth - smooth2) + bound, err)
    else:
        switches = 0
    whole = np.array_equal(np.unique(points.covered), np.arange(len(part.faces)))
    return MeshFilm(total, err, pairs, shaded, float(gun.flow * w.sum()),
                    float(total @ points.areas), bool(whole), switches)


__all__ = ["MeshFilm", "mesh_film"]
