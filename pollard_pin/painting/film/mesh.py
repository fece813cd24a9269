"""The film a gun path leaves on a part's mesh (docs/model.md §20): the deposition rate at
each film point with its own normal, zero where the part shades the point from the nozzle
(:mod:`.spray.occlusion`), times the gun's trigger, integrated by the trapezoid rule in time
(as :func:`.spray.deposition.film`, in blocks of samples of bounded memory), with the steps where
a point's shade switches integrated apart (:mod:`.spray.shadow_edges`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...dynamics.averages import trapezoid_weights
from ..errors import MeshError
from ..progress import bar
from ..spray.deposition import (
    Gun,
    Reach,
    coarse_weights,
    may_reach,
    sources,
    spot_block,
)
from ..spray.occlusion import in_spot, open_pairs, visible
from ..spray.shadow_edges import shadow_edges
from ..workpiece.mesh import Part
from .points import SurfacePoints

# The film is computed over chunks of points near each other (docs/model.md §23): at most
# CHUNK_POINTS (a chunk the spot does not reach in a block of samples is skipped whole) and
# at most CHUNK_PAIRS points × sprayed samples, so a chunk's shaded pairs (8 bytes each) and
# its shadow edges stay within ~0.5 GB whatever the part and the program's length. Samples go
# BLOCK_SAMPLES at a time: the spot moves ≤ σ/4 a sample, so a block's cull widens by ≤ 4σ.
CHUNK_POINTS = 8192
CHUNK_PAIRS = 20_000_000
BLOCK_SAMPLES = 16
GROUP_POINTS = 32  # a chunk's points tested by balls of about this many before one by one
SHADE_PAIRS = 50_000_000  # shaded pairs kept for a moved path's film (8 bytes each): 0.4 GB


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class Shade:
    """Where the part shaded the points from the nozzle, chunk by chunk (:func:`mesh_film`'s
    chunks of ``points`` points and ``samples`` time samples): each chunk's shaded pairs as
    sorted keys sample × (chunk's points) + point and its shadow edges' ``cuts`` (where in
    its step each switch lies, :func:`.spray.shadow_edges.shadow_edges`; empty: found again
    by bisection)."""

    points: int
    samples: int
    keys: tuple
    cuts: tuple


def film_chunks(points: np.ndarray, samples: int) -> list[np.ndarray]:
    """The points' indices (P,) cut into chunks of at most CHUNK_POINTS and CHUNK_PAIRS /
    ``samples`` points, each a cube of the part's space (so a chunk lies together)."""
    P = len(points)
    size = int(max(1, min(CHUNK_POINTS, CHUNK_PAIRS // max(samples, 1))))
    if P <= size:
        return [np.arange(P)]
    cell = _cubes(points, size)
    order = np.lexsort((cell[:, 2], cell[:, 1], cell[:, 0]))
    return [order[i:i + size] for i in range(0, P, size)]


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
    shade: Shade | None = None  # where the points were shaded: reused by a moved path
    robots: tuple = ()  # a cell's: each robot's own film, whose sum this is

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


def _cubes(points: np.ndarray, size: int) -> np.ndarray:
    """Each point's cube (P, 3) of cubes holding ~``size`` points if the points filled their
    box's largest face evenly: the chunks' and their groups' one rule."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    span = np.sort(hi - lo)[::-1]
    side = max(math.sqrt(span[0] * span[1] * size / len(points)),
               span[0] * size / len(points), 1e-12)
    return np.floor((points - lo) / side).astype(np.int64)


def _bounding_balls(s, labels, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The bounding balls' centres (n, 3) and radii (n,) of the points ``s`` labelled
    ``labels`` (0..n−1): the centre the middle of the group's box."""
    lower, upper = np.full((n, 3), np.inf), np.full((n, 3), -np.inf)
    np.minimum.at(lower, labels, s)
    np.maximum.at(upper, labels, s)
    centres = 0.5 * (lower + upper)
    radii = np.zeros(n)
    np.maximum.at(radii, labels, np.linalg.norm(s - centres[labels], axis=1))
    return centres, radii


def _balls(s, groups) -> tuple[np.ndarray, np.ndarray]:
    """The bounding balls' centres (G, 3) and radii (G,) of groups of the points ``s``."""
    labels = np.repeat(np.arange(len(groups)), [len(g) for g in groups])
    return _bounding_balls(s[np.concatenate(groups)], labels, len(groups))


def film_groups(s, chunks, size: int = GROUP_POINTS) -> tuple:
    """Each chunk's points cut into cubes of about ``size`` points (the chunks' rule,
    :func:`film_chunks`): (per chunk its points' group (global ids), the groups' bounding
    balls' centres (G, 3) and radii (G,))."""
    labels, first = [], 0
    for idx in chunks:
        _, g = np.unique(_cubes(s[idx], size), axis=0, return_inverse=True)
        labels.append(g.ravel() + first)
        first = int(labels[-1].max()) + 1
    centres, radii = _bounding_balls(s[np.concatenate(chunks)], np.concatenate(labels), first)
    return labels, centres, radii


def _reach(gun: Gun, s, o, chunks, summary) -> np.ndarray:
    """(blocks, chunks) True where a block of samples (:func:`.spray.deposition.spot_block`'s
    ``summary``, positions less ``o``) may reach a chunk of the points ``s`` (its bounding
    ball): each block's test of every chunk at once."""
    centres, radii = _balls(s - o, chunks)
    out = np.zeros((len(summary), len(chunks)), dtype=bool)
    for j, (pm, am, dp, da) in enumerate(summary):
        out[j] = may_reach(gun, pm, am, dp, da, centres, radii)
    return out


def mesh_film(gun: Gun, t, p, a, points: SurfacePoints, part: Part, spray=None,
              origin=None, intersector=None, shade: Shade | None = None) -> MeshFilm:
    """Film at ``points`` (their own positions and normals) after the gun passes through the
    tips ``p`` (T, 3) with axes ``a`` (T, 3) at times ``t`` (T,), spraying ``spray`` (T,) ×
    flow (the trigger, in [0, 1]; None: 1 throughout). Pairs inside the spray spot whose
    segment to the nozzle crosses the part get nothing (:mod:`.spray.occlusion`). ``origin`` (3,):
    subtracted from every position for the rate's matrix products (default: the points'
    mean); ``intersector``: the ray engine (default ``part.mesh.ray``). ``shade``: the
    :class:`Shade` of a film of the same points, times and trigger (a path moved by a
    deflection of tenths of a millimetre, docs/model.md §27.7): its shaded pairs are taken as
    they are, no pair's ray is cast, and its shadow edges in time too where it carries their
    cuts (else they are bisected again). Computed in chunks of points
    (:func:`film_chunks`); the film keeps its :class:`Shade` when its shaded pairs number at
    most SHADE_PAIRS."""
    t = np.asarray(t, dtype=float)
    p, a = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, a))
    # a: the axes (T, 3) or the rotations (T, 3, 3) a spot that is not round needs (§20)
    if not (p.shape == a.shape[:2] == (len(t), 3) and a.shape[2:] in ((), (3,))):
        raise MeshError(f"gun positions {p.shape} and axes {a.shape} must be ({len(t)}, 3) "
                        f"(axes: or ({len(t)}, 3, 3) rotations), one per time sample")
    trig = _spray(spray, len(t))
    s, n = points.points, points.normals
    o = s.mean(axis=0) if origin is None else np.asarray(origin, dtype=float)
    w, w2 = trapezoid_weights(t) * trig, coarse_weights(t) * trig
    W = np.column_stack([w, w2])
    total, coarse = np.zeros(len(s)), np.zeros(len(s))
    err = np.full(len(s), np.nan)
    live = np.flatnonzero(trig > 0)  # a closed trigger deposits nothing: skipped
    blocks = [live[i:i + BLOCK_SAMPLES] for i in range(0, len(live), BLOCK_SAMPLES)]
    po = p - o  # the tips for the rate's products
    summary = [spot_block(po[b], a[b]) for b in blocks]
    # each block's sources, weights W[b].T and cone, made once for every chunk it meets
    src, wt, cull = {}, {}, {}
    chunks = film_chunks(s, len(live))
    if shade is not None and (shade.points, shade.samples, len(shade.keys)) != (
            len(s), len(t), len(chunks)):
        raise MeshError(f"a shade of {shade.points} points × {shade.samples} samples "
                        f"({len(shade.keys)} chunks) for a film of {len(s)} × {len(t)} "
                        f"({len(chunks)} chunks)")
    keys, cuts = [], []
    pairs = shaded = switches = 0
    reach = _reach(gun, s, o, chunks, summary)
    groups, centres, radii = film_groups(s - o, chunks)
    group_range = [(int(g.min()), int(g.max()) + 1) for g in groups]  # each chunk's labels
    held = {}  # each block's groups that may hold a point it reaches
    for c, idx in enumerate(bar(chunks, "film")):
        sc, nc, faces = s[idx] - o, n[idx], points.faces[idx]
        # the rule and the coarse rule, shaded (rows: one fancy-indexed add each, ~5x faster
        # than a column pair's); smooth the same on the unshaded rate, acc itself until the
        # first shaded pair (the same additions in the same order)
        acc, smooth = np.zeros((2, len(idx))), None
        dark_t, dark_p = [], []
        given = None if shade is None else shade.keys[c]
        first, last = group_range[c]
        for j in np.flatnonzero(reach[:, c]):
            b = blocks[j]
            # near_spot: the rest get < 3e-18 of the spot's rate (§20)
            if j not in cull:
                cull[j] = Reach(gun, *summary[j])
                held[j] = cull[j].holds(centres, radii)
            if not held[j][first:last].any():  # no group of the chunk: none kept
                continue
            if j not in src:
                src[j] = sources(gun, po[b], a[b])
                wt[j] = W[b].T
            # keep's test, point by point, on the points of the groups that may hold one,
            # and the rate of those kept (samples, points)
            k, r, height = cull[j].rate_near(gun, src[j], sc, nc, groups[c], held[j])
            if not len(k):
                continue
            part_sum = wt[j] @ r  # (2, points)
            if given is None:
                spot = in_spot(gun, r)
                pairs += int(np.count_nonzero(spot))
                ti, ri = np.nonzero(spot & ~open_pairs(part, faces[k], height))
                if len(ti):
                    q = idx[k[ri]]
                    vis = visible(part, p[b[ti]], s[q], n[q], intersector)
                    ti, ri = ti[~vis], ri[~vis]
                    dark_t.append(b[ti].astype(np.int32))
                    dark_p.append(k[ri].astype(np.int32))
            else:  # the shaded pairs of this block, among the points near the spot
                lo, hi = np.searchsorted(given, [b[0] * len(idx), (b[-1] + 1) * len(idx)])
                kb = given[lo:hi]
                col = np.full(len(idx), -1)
                col[k] = np.arange(len(k))
                row = np.searchsorted(b, kb // len(idx))
                ci = col[kb % len(idx)]
                inside = (ci >= 0) & (row < len(b))
                inside[inside] &= b[row[inside]] == kb[inside] // len(idx)
                ti, ri = row[inside], ci[inside]
            if len(ti) and smooth is None:
                smooth = acc.copy()
            if smooth is not None:  # the unshaded sums: for the shadow edges
                smooth[0][k] += part_sum[0]
                smooth[1][k] += part_sum[1]
            if len(ti):
                r[ti, ri] = 0.0
                part_sum = wt[j] @ r
            acc[0][k] += part_sum[0]
            acc[1][k] += part_sum[1]
        smooth = acc if smooth is None else smooth
        chunk_total, chunk_coarse = acc[0], acc[1]
        e = np.abs(chunk_total - chunk_coarse)
        if given is None:
            dt_, dp_ = (np.concatenate(x) if x else np.zeros(0, np.int32)
                        for x in (dark_t, dark_p))
            del dark_t, dark_p
            key = dt_.astype(np.int64) * len(idx) + dp_  # sorted: sample, then point
            del dt_, dp_
            fix_cuts = None
        else:
            key, fix_cuts = given, shade.cuts[c] if shade.cuts else None
        if len(key):
            fix, bound, m, cut = shadow_edges(gun, t, p, a, trig, s[idx], nc, part,
                                              key // len(idx), key % len(idx), intersector,
                                              fix_cuts)
            chunk_total = chunk_total + fix
            edge = bound > 0
            e = np.where(edge, np.abs(smooth[0] - smooth[1]) + bound, e)
            switches += m
        else:
            cut = np.zeros(0)
        shaded += len(key)
        total[idx], coarse[idx], err[idx] = chunk_total, chunk_coarse, e
        if shade is None and len(keys) == c and shaded <= SHADE_PAIRS:
            keys.append(key)
            cuts.append(cut)
    if len(t) <= 2:
        err = np.full(len(s), np.nan)
    kept = shade if shade is not None else (
        Shade(len(s), len(t), tuple(keys), tuple(cuts)) if len(keys) == len(chunks) else None)
    whole = np.array_equal(np.unique(points.covered), np.arange(len(part.faces)))
    return MeshFilm(total, err, pairs, shaded, float(gun.flow * w.sum()),
                    float(total @ points.areas), bool(whole), switches, kept)


__all__ = ["BLOCK_SAMPLES", "CHUNK_PAIRS", "CHUNK_POINTS", "MeshFilm", "SHADE_PAIRS", "Shade",
           "film_chunks", "mesh_film"]
