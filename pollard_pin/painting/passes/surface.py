"""Spray passes on a part's painted surface (docs/model.md §23): where the gun goes, not yet
when (:mod:`.plan.part` times it against the motors).

Frame. n = the part's ``facing`` (towards the robot), v = world z projected off n, u = n × v
(as the panel's frame, :func:`.passes.raster.panel_frame`); world x instead of z for a part
facing nearer vertical than horizontal (:func:`reference_axis`). Horizontal passes run along
e_p = u and are stacked along e_s = v; vertical ones swap the two.

Passes. Pass k is the section of the painted faces by the plane e_s·x = level_k. With every
painted face within max_angle < 90° of n, the section is a graph over e_p: at each e_p the
point nearest the robot (largest ·n) is kept, and e_p is sampled every SAMPLE_STEP. The arc
length along it, ds = |e_s × N| / |(e_s × N)·e_p| de_p (N the face normal), counts surface
only: a wall hidden along e_p (a rib's side) adds no length, a hole is crossed as if flat.
The pass runs on past both ends by EXTENSION σ along the end tangent: the film a pass leaves
on an edge then lacks Φ(−3) = 0.13 % of a pass run on for ever (the panel's SPOT_RADIUS = 4σ
takes 1 cm more of reach at each end: the curved example's corners lie at the edge of it);
the turnarounds lie beyond, off the part.

Spacing on the surface. The levels are chosen by the arc length w of the section across
the passes (the plane e_p·x through the painted faces' centroid): level_k = e_s(w_k) with
w_k spaced as on a flat panel of width the arc length (:func:`.passes.raster.pass_offsets`), so
neighbouring passes lie ``spacing`` apart along the surface where it tilts across them; a
pass beyond an edge lies on along the edge face's tangent, so the outer ones keep it too.
(Exact for a part that is a prism along e_s, as the examples; to first order elsewhere.)

Gun pose. The tip lies at standoff h along the normal: tip = S + h·N, spray axis −N. A
faceted mesh's normal jumps at every edge, a rib's top steps off the plate and a concave
fillet tighter than h folds the offset path back (tip' = (1 − hκ)·S'); so S and N are both
averaged along the pass by a Gaussian of standard deviation w (in arc length, Ñ
renormalised), the smallest w of SMOOTHING for which the tip moves forwards at least FORWARD
× the surface arc and at most STRETCH × it, on every pass. The largest angle between the
spray axis and a painted point's −N (the incidence) is reported.

Speed. A pass's parameter s is the surface arc of the spot's footprint (where the averaged
spray axis meets the pass: :func:`footprint`; the normal's foot where the gun is normal), run
at a constant rate ṡ = v, so the spot crosses every pass at the same surface speed wherever
the tip is stretched by convexity, shortened by concavity or tilted off the normal, and
film = flow/(v·spacing) with the spacing on the surface.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d

from ..errors import BudgetError, PlanError
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..spray.spots import STROKES
from ..workpiece.mesh import Part
from .raster import job_spacing, pass_offsets, spot_runon

SAMPLE_STEP = 1e-3  # m of surface between pass samples (σ/10 for the example gun)
# m: the Gaussian averages of the normal tried along a pass, smallest first (a faceted mesh
# needs a few facets' worth; a 30 mm concave fillet at 0.15 m standoff some 4 cm)
SMOOTHING = (0.004, 0.006, 0.01, 0.015, 0.02, 0.03, 0.04, 0.05, 0.06, 0.08)
FORWARD = 0.25  # the tip advances at least this fraction of the surface arc ...
STRETCH = 3.0  # ... and at most this multiple of it
EXTENSION = 3.0  # σ: the passes run on this far past the painted faces' edges
MAX_PASS_SPEED = 10.0  # m/s: beyond any spray robot's pass (the example's motors: 1.8)
MAX_SAMPLES = 200_000  # pass samples over all passes (each a small spline knot)


@dataclass(frozen=True)
class SurfaceFrame:
    """Unit ``n`` (facing, towards the robot), ``along`` (e_p) the passes' direction,
    ``across`` (e_s) the slicing planes' normal, ``centre`` the painted area's centroid."""

    n: np.ndarray
    along: np.ndarray
    across: np.ndarray
    centre: np.ndarray


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class SurfacePass:
    """One pass, sampled every ``step`` of surface arc ``s`` (K,) from its extended start:
    ``surface`` (K, 3) the points on (or, beyond the ends, tangent to) the surface,
    ``normal`` (K, 3) their faces' outward normals, ``tip`` (K, 3) and ``axis`` (K, 3) the
    smoothed gun, ``on_part`` (K,) the samples on painted faces, ``level`` the plane's
    e_s coordinate [m]."""

    s: np.ndarray
    surface: np.ndarray
    normal: np.ndarray
    tip: np.ndarray
    axis: np.ndarray
    on_part: np.ndarray
    level: float

    @property
    def length(self) -> float:
        return float(self.s[-1])


@dataclass(frozen=True, eq=False)
class SurfaceLayout:
    """The passes (in painting order of one coat, each run forwards) with their ``spacing``
    on the surface [m], the Gaussian ``smoothing`` w [m], the largest ``incidence`` [deg],
    the ``extension`` past each end [m] and the across-pass arc length ``extent`` [m]."""

    frame: SurfaceFrame
    passes: tuple[SurfacePass, ...]
    spacing: float
    smoothing: float
    incidence: float
    extension: float
    extent: float


def reference_axis(n) -> np.ndarray:
    """The world axis the part's frame and the gun's roll are referred to: z (up), unless
    the facing ``n`` lies nearer vertical than horizontal (a table top), then x (away from
    the robot): at least 45° off ``n`` either way, so projecting it off n never divides by
    nearly zero."""
    n = np.asarray(n, dtype=float)
    return np.array([1.0, 0.0, 0.0] if abs(n[2]) > math.sqrt(0.5) else [0.0, 0.0, 1.0])


def surface_frame(part: Part, direction: str = "horizontal") -> SurfaceFrame:
    n = np.asarray(part.facing, dtype=float)
    ref = reference_axis(n)
    v = ref - (ref @ n) * n
    v /= np.linalg.norm(v)
    u = np.cross(n, v)
    idx = np.flatnonzero(part.painted)
    tri = part.vertices[part.faces[idx]].mean(axis=1)
    centre = (tri * part.areas[idx, None]).sum(0) / part.areas[idx].sum()
    along, across = (u, v) if direction == "horizontal" else (v, u)
    return SurfaceFrame(n, along, across, centre)


def _painted_mesh(part: Part):
    import trimesh

    idx = np.flatnonzero(part.painted)
    return trimesh.Trimesh(part.vertices, part.faces[idx], process=False), part.normals[idx]


def section(part_mesh, normals, frame_n, along, across, level: float, step: float):
    """The section of the painted faces by the plane across·x = level, as a graph over
    ``along``: (coordinate c (J,), surface points (J, 3), normals (J, 3), on (J,) covered by
    a face, arc length (J,)), or None if the plane misses them."""
    import trimesh

    with np.errstate(all="ignore"):
        lines, faces = trimesh.intersections.mesh_plane(
            part_mesh, across, level * across, return_faces=True)
    if len(lines) == 0:
        return None
    a = lines @ along  # (K, 2)
    keep = np.abs(a[:, 1] - a[:, 0]) > 1e-12
    lines, faces, a = lines[keep], faces[keep], a[keep]
    if len(lines) == 0:
        return None
    lo, hi = a.min(), a.max()
    m = max(2, int(math.ceil((hi - lo) / step)) + 1)
    c = np.linspace(lo, hi, m)
    frac = (c[None, :] - a[:, :1]) / (a[:, 1:] - a[:, :1])  # (K, J)
    cover = (frac >= -1e-9) & (frac <= 1 + 1e-9)
    pts = lines[:, None, 0, :] + frac[..., None] * (lines[:, None, 1, :] - lines[:, None, 0, :])
    depth = np.where(cover, pts @ frame_n, -np.inf)
    best = depth.argmax(axis=0)  # the face nearest the robot at each c
    on = cover[best, np.arange(m)]
    S = pts[best, np.arange(m)]
    N = normals[faces[best]]
    if not on.all():  # holes: crossed straight, normals interpolated
        for x in (S, N):
            for k in range(3):
                x[~on, k] = np.interp(c[~on], c[on], x[on, k])
        N /= np.linalg.norm(N, axis=1, keepdims=True)
    # surface arc per unit of c (the module notes), mid-interval normals of covered samples
    t = np.cross(across, N)
    rate = np.linalg.norm(t, axis=1) / np.maximum(np.abs(t @ along), 1e-6)
    rate = np.where(on, rate, 1.0)
    ds = np.diff(c) * 0.5 * (rate[:-1] + rate[1:])
    return c, S, N, on, np.concatenate([[0.0], np.cumsum(ds)])


def _tangent(N, across, along):
    t = np.cross(across, N)
    t /= np.linalg.norm(t)
    return t if t @ along > 0 else -t


def _extended(sec, across, along, extension: float, step: float):
    """The pass resampled every ~``step`` of arc, run on by ``extension`` past both ends."""
    _, S, N, on, arc = sec
    arc = arc + 1e-9 * np.arange(len(arc))  # a hidden wall: strictly increasing still
    t0, t1 = _tangent(N[0], across, along), _tangent(N[-1], across, along)
    length = arc[-1] + 2 * extension
    k = max(4, int(math.ceil(length / step)) + 1)
    s = np.linspace(0.0, length, k)
    q = s - extension  # arc from the section's start
    inside = (q >= 0) & (q <= arc[-1])
    surf = np.empty((k, 3))
    nrm = np.empty((k, 3))
    for i in range(3):
        surf[:, i] = np.interp(q, arc, S[:, i])
        nrm[:, i] = np.interp(q, arc, N[:, i])
    before, after = q < 0, q > arc[-1]
    surf[before] = S[0] + q[before, None] * t0
    surf[after] = S[-1] + (q[after] - arc[-1])[:, None] * t1
    nrm[before], nrm[after] = N[0], N[-1]
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    covered = np.interp(q, arc, on.astype(float)) > 0.5
    return s, surf, nrm, inside & covered


def _gun(s, surf, nrm, standoff: float, w: float):
    """(tip, axis) of the pass with S and N averaged over a Gaussian of std ``w`` [m]; the
    points run on straight (the normals constant) for 4w past both ends first, so that the
    average does not pull the ends back."""
    step = s[1] - s[0]
    m = int(math.ceil(4 * w / step))
    ramp = np.arange(1, m + 1)[:, None] * step
    t0 = (surf[1] - surf[0]) / step
    t1 = (surf[-1] - surf[-2]) / step
    padded = np.concatenate([surf[0] - ramp[::-1] * t0, surf, surf[-1] + ramp * t1])
    S = gaussian_filter1d(padded, w / step, axis=0, mode="nearest")[m:m + len(s)]
    N = gaussian_filter1d(nrm, w / step, axis=0, mode="nearest")
    N /= np.linalg.norm(N, axis=1, keepdims=True)
    return S + standoff * N, -N


def _follows(s, surf, tip) -> bool:
    """The tip advances between FORWARD and STRETCH × the surface arc everywhere, along the
    (averaged) surface ``surf``."""
    ds = np.diff(s)[:, None]
    dt, dS = np.diff(tip, axis=0) / ds, np.diff(surf, axis=0) / ds
    dS /= np.maximum(np.linalg.norm(dS, axis=1, keepdims=True), 1e-12)
    forward = np.einsum("ij,ij->i", dt, dS)
    return bool(forward.min() >= FORWARD and np.linalg.norm(dt, axis=1).max() <= STRETCH)


def footprint(s, surf, tip, axis, across) -> np.ndarray:
    """The surface arc (K,) at which each sample's spray axis meets the pass (the spot's
    centre), where the averaged gun looks off the normal foot S; ``s`` itself where that is
    not strictly increasing (the pass is then timed by its foot)."""
    b = np.cross(across, axis)  # in the pass plane, across the axis
    b /= np.linalg.norm(b, axis=1, keepdims=True)
    b *= np.sign(np.einsum("ij,ij->i", b, np.gradient(surf, axis=0)))[:, None]
    # e[i, j]: sample j's side of sample i's axis (negative before it, positive after)
    e = np.einsum("jx,ix->ij", surf, b) - np.einsum("ix,ix->i", tip, b)[:, None]
    crossing = (e[:, :-1] <= 0) & (e[:, 1:] > 0)
    hit = crossing.any(axis=1)
    if hit.sum() < 2:
        return s
    rows = np.flatnonzero(hit)
    j = np.argmax(crossing[rows], axis=1)
    f = -e[rows, j] / (e[rows, j + 1] - e[rows, j])
    # the axis off either end (the run-on's last sample): the neighbours' offset from s
    shift = np.interp(np.arange(len(s)), rows, s[j] + f * (s[j + 1] - s[j]) - s[rows])
    q = s + shift
    if not (np.diff(q) > 0.2 * np.diff(s)).all():
        return s
    return q


def pass_spacing(job) -> float:
    """The spacing on the surface: the job's, else the widest of ripple ≤ tolerance/2."""
    return job.spacing if job.spacing is not None else job_spacing(job)


def pass_speed(job, spacing: float) -> float:
    """Surface speed [m/s] of the spot: film per coat = flow/(speed·spacing) (§21), the one
    formula of a panel's and a part's passes. The job's speed, or the whole film's in one
    coat, over :data:`MAX_PASS_SPEED` is a :class:`PlanError` (a unit slip, not a pass any
    robot runs); more coats only multiply a speed that is not, and too many are the motors'
    to refuse (the panel's "at most N coat(s)")."""
    coats = job.coats or 1
    v = job.speed if job.speed is not None else job.flow * coats / (job.thickness * spacing)
    # the motors' check would square it (1e300 overflows); coats are bounded by the passes'
    one = v if job.speed is not None else v / coats
    if not one <= MAX_PASS_SPEED:
        given = ("job.speed" if job.speed is not None else
                 f"gun.flow {job.flow:.3g} m³/s, {coats} coat(s) of "
                 f"{job.thickness / coats * 1e6:.4g} µm at spacing {spacing * 1e3:.4g} mm")
        spaced = " and job.spacing" if getattr(job, "spacing", None) is not None else ""
        raise PlanError(f"{job.source}: the target needs a gun speed of {v:.4g} m/s ({given}),"
                        f" {v / MAX_PASS_SPEED:.3g} times the {MAX_PASS_SPEED:g} m/s of any "
                        f"spray pass: gun.flow in m³/s, job.thickness{spaced} in m?")
    return v


def surface_layout(part: Part, job, step: float = SAMPLE_STEP, min_smoothing: float = 0.0,
                   policy: PlannerPolicy = DEFAULT_POLICY) -> SurfaceLayout:
    """The passes over the painted faces of ``part`` for ``job`` (standoff, sigma, spacing,
    direction): see the module notes; the smoothing at least ``min_smoothing`` [m] (the
    planner asks for more where the motors cannot follow); the passes within
    ``policy.max_passes``. Raises :class:`PlanError` if no smoothing in SMOOTHING lets the
    gun follow the surface."""
    frame = surface_frame(part, job.direction)
    mesh, normals = _painted_mesh(part)
    spacing = pass_spacing(job)
    # across: the section by the plane through the centroid normal to the passes
    cross = section(mesh, normals, frame.n, frame.across, frame.along,
                    float(frame.centre @ frame.along), step)
    if cross is None:
        raise PlanError(f"{part.source}: the painted faces have no section through their "
                        "centroid across the passes")
    c, _, _, _, w = cross
    extent = float(w[-1])
    span = np.ptp(part.vertices[part.faces[part.painted]].reshape(-1, 3) @ frame.along)
    if min(extent, span) < job.sigma:  # the job's rule for panels (MIN_PANEL_SIGMAS)
        # under a tenth of the spot: more likely a unit slip than a part that small
        why = ("a mesh in metres read as millimetres (part.units)?"
               if max(span, extent) < job.sigma / 10 else "a smaller spot (gun.sigma)")
        raise PlanError(f"{part.source}: the part is smaller than the spray spot: its painted "
                        f"faces span {span:.3g} × {extent:.3g} m, σ = {job.sigma:.3g} m (the "
                        f"film would be the spot's own profile): {why}")
    coats = job.coats or 1
    passes = (extent / spacing + 1) * coats
    if passes > policy.max_passes:  # before the cross profile, which grows with their square
        raise BudgetError(f"{job.source}: {passes:.3g} passes ({coats} coat(s) at spacing "
                          f"{spacing:.3g} m over {extent:.3g} m of surface), budget "
                          f"{policy.max_passes}: a wider job.spacing or fewer coats")
    try:
        offsets = pass_offsets(extent, spacing, job.sigma, spot=job.spot,
                               direction=STROKES[job.direction]) + extent / 2
    except ValueError as exc:
        raise PlanError(f"{job.source}: {exc}") from None
    # arc w → the plane coordinate; a pass beyond an edge: the section at the edge moved on
    # along the surface's tangent across the passes there, the edge face's (as w counts arc
    # and a pass runs on): a chord between samples would take a hidden wall's step (a lip
    # narrower than the step at the edge) for the slope and bunch the outer passes
    N_cross = cross[2]
    t_lo = -_tangent(N_cross[0], frame.along, frame.across)
    t_hi = _tangent(N_cross[-1], frame.along, frame.across)
    extension = spot_runon(job.sigma, job.spot, EXTENSION)
    lo, hi = c[0] + 1e-6, c[-1] - 1e-6
    raw = []
    for off in offsets:
        at = float(np.clip(np.interp(off, w, c), lo, hi))
        gap = off - float(np.interp(at, c, w))  # the arc left beyond a clipped plane
        beyond = (gap * t_hi if at == hi and gap > 0 else -gap * t_lo if at == lo and gap < 0
                  else np.zeros(3))
        sec = section(mesh, normals, frame.n, frame.along, frame.across, at, step)
        if sec is None:
            raise PlanError(f"{part.source}: the pass plane at {at:.4g} m across misses the "
                            "painted faces (a part in pieces?)")
        s, surf, nrm, on = _extended(sec, frame.across, frame.along, extension, step)
        level = at + float(beyond @ frame.across)
        raw.append((s, surf + beyond, nrm, on, level))
    if sum(len(r[0]) for r in raw) > MAX_SAMPLES:
        raise PlanError(f"{part.source}: the passes need more than {MAX_SAMPLES} samples at "
                        f"{step:.3g} m")
    for width in (w for w in SMOOTHING if w >= min_smoothing):
        guns = [_gun(s, surf, nrm, job.standoff, width) for s, surf, nrm, _, _ in raw]
        if all(_follows(r[0], g[0] + job.standoff * g[1], g[0]) for r, g in zip(raw, guns)):
            break
    else:
        raise PlanError(f"{part.source}: the surface turns faster than a gun at "
                        f"{job.standoff:g} m standoff can follow even averaging its normal "
                        f"over {SMOOTHING[-1]:g} m: a smaller standoff or a gentler part")
    passes, worst = [], 0.0
    for (s, surf, nrm, on, level), (tip, axis) in zip(raw, guns):
        s = footprint(s, surf, tip, axis, frame.across)
        cosi = np.clip(-np.einsum("ij,ij->i", axis[on], nrm[on]), -1, 1)
        if len(cosi):
            worst = max(worst, math.degrees(math.acos(cosi.min())))
        arrays = (s, surf, nrm, tip, axis, on)
        for x in arrays:
            x.flags.writeable = False
        passes.append(SurfacePass(*arrays, level))
    return SurfaceLayout(frame, tuple(passes), spacing, width, worst, extension, extent)


__all__ = ["EXTENSION", "FORWARD", "MAX_PASS_SPEED", "SAMPLE_STEP", "SMOOTHING", "STRETCH",
           "SurfaceFrame", "SurfaceLayout", "SurfacePass", "pass_spacing", "pass_speed",
           "reference_axis", "section", "surface_frame", "surface_layout"]
