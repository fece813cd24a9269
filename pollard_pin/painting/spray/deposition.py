"""Spray deposition: the film a moving gun leaves on a surface (docs/model.md §20).

Point source at the tool tip p, spray axis a = R·e_x. For a surface point s with unit normal
n (towards the gun), d = s − p, h = d·a, ρ = |d − h a|, σ(h) = sigma·h/standoff,
cos α = h/|d|, cos i = max(0, −d·n)/|d|; the film grows at

    dT/dt = flow / (2π σ(h)²) · exp(−ρ² / (2 σ(h)²)) · cos i / cos α        (h > 0)

and the film is its time integral over the path (the gun sprays throughout). Any other spot
(:mod:`.spray.spots`) replaces the Gaussian by flow·D(u/c, v/c)/c², c = h/standoff its
scale, (u, v) = (d·R e_y, d·R e_z); a cone apex in front of the nozzle moves the source to
p + apex·a (h, standoff measured from it). The round Gaussian keeps its own fast form, a
compiled pass over each block (:mod:`.kernel`). The elliptic spot turns with the gun: its
callers pass the gun's rotations (T, 3, 3) where the others may pass the axes (T, 3) alone
(:func:`gun_axes`). The integral is the trapezoid rule over the path's samples: for a spot
crossing a point at constant speed its error is ≈ 2·exp(−2π²(σ/Δx)²) relative (Poisson
summation, Δx the gun's travel per step), so Δx ≤ σ/2 gives < 1e-33 and Δx ≤ σ gives < 6e-9;
:func:`film` also returns the difference from the rule on every second sample, an
a-posteriori bound on the error.

Each block of samples evaluates only the points :func:`near_spot` keeps: those inside the
cone of half-angle atan(CULL_SIGMAS·σ/standoff) around some sample's axis, or close to a
nozzle. For a point outside, tan θ ≥ c·k (k = σ/standoff, c = CULL_SIGMAS) and |d| > standoff/4,
so its rate is below flow/(2πσ²) · 16 (1 + c²k²)^{3/2} exp(−c²/2) ≤ 3e-18 of the spot's centre
(c = 10, c·k ≤ 4; the bound falls with θ beyond the cone): dropped, it changes no film by more
than round-off. Every spot culls by its own reach (c·σ = :attr:`.spots.Spot.reach`: 10 σ_long
for the elliptic spot, the radius R for the β spot, beyond which it deposits exactly 0).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...dynamics.averages import trapezoid_weights
from ..progress import bar
from . import kernel
from .spots import REACH_SIGMAS, RoundGaussian, Spot

# Time samples per vectorised block: (block × points) float64 arrays of ~8 MB each.
BLOCK_ELEMENTS = 1_000_000
CULL_SIGMAS = REACH_SIGMAS  # the cone kept around the spray axis, in σ(h)/h (module docstring)
CULL_WIDEST = 4.0  # tan of the widest cone culled: a wider spray evaluates every point
HOLD_PAD = 1e-9  # rad and m: Reach.holds' margin over round-off (a ball's test a superset)


@dataclass(frozen=True)
class Gun:
    """The spray gun (SI, docs/model.md §20).

    Parameters
    ----------
    standoff : float
        Nozzle to surface along the spray axis [m], where the spot has spread ``sigma``.
    sigma : float or None
        The spot's spread at the standoff [m]: the round Gaussian's σ, or for another
        ``spot`` its :attr:`~.spots.Spot.width` (None: taken from ``spot``).
    flow : float
        Film volume deposited [m³/s] (flow × transfer efficiency × solids).
    spot : pollard_pin.painting.spray.Spot or None, optional
        The spray pattern at the standoff (None: the round Gaussian of ``sigma``).
    apex : float, optional
        The spray cone's apex in front of the nozzle [m] (negative: behind it), below the
        standoff; the spot's size is ∝ the distance from it (default 0: the nozzle).
    """

    standoff: float
    sigma: float | None
    flow: float
    spot: Spot | None = None
    apex: float = 0.0

    def __post_init__(self):
        if self.spot is None:
            object.__setattr__(self, "spot", RoundGaussian(self.sigma))
        elif self.sigma is None:
            object.__setattr__(self, "sigma", self.spot.width)
        elif self.sigma != self.spot.width:
            raise ValueError(f"sigma = {self.sigma!r} m is not the spot's width "
                             f"{self.spot.width!r} m (give sigma=None with a spot)")
        if not (math.isfinite(self.apex) and self.apex < self.standoff):
            raise ValueError(f"apex = {self.apex!r} m must lie before the standoff "
                             f"{self.standoff!r} m")

    @property
    def peak_rate(self) -> float:
        """The film's growth rate at the spot's centre at the standoff, normal incidence
        [m/s]: flow × the spot's peak density."""
        if type(self.spot) is RoundGaussian:
            return self.flow / (2.0 * math.pi * self.sigma ** 2)
        return self.flow * self.spot.peak


def gun_axes(a) -> tuple:
    """(spray axes (T, 3), the spot's u axes (T, 3) or None) of ``a``: the unit spray axes
    (T, 3), or the gun's rotations (T, 3, 3) whose columns are the spray axis R·e_x and the
    spot's u axis R·e_y (made orthogonal to the first: interpolated frames drift)."""
    a = np.asarray(a, dtype=float)
    if a.ndim != 3:
        return np.atleast_2d(a), None
    ax = np.ascontiguousarray(a[:, :, 0])
    b = a[:, :, 1] - np.einsum("ij,ij->i", a[:, :, 1], ax)[:, None] * ax
    return ax, b / np.linalg.norm(b, axis=1)[:, None]


def _spot_axes(gun: Gun, a, b):
    """The spot's (u, v) axes (T, 3) each, None for a round spot; a ValueError for a spot
    that turns with the gun given the axes alone."""
    if gun.spot.round:
        return None
    if b is None:
        raise ValueError(f"the {gun.spot.name} spot turns with the gun about its axis: give "
                         "the gun's rotations (T, 3, 3), not its spray axes alone")
    return b, np.cross(a, b)


def _source(gun: Gun, p, a):
    """The spray's point source: the tips, or the cone's apex in front of them."""
    return p + gun.apex * a if gun.apex else p


def deposition_rate(gun: Gun, p, a, s, n) -> np.ndarray:
    """dT/dt [m/s] for gun tips ``p`` (T, 3) spraying along unit axes ``a`` (T, 3) at surface
    points ``s`` (P, 3) of unit normals ``n`` ((P, 3) or (3,), towards the gun): (T, P).

    The round Gaussian takes each pair's d = s − p (:mod:`.kernel`); for the other spots every
    pairwise quantity is a product of small matrices (h = s·a − p·a, …), so coordinates
    should be centred near the scene (the caller's origin) to keep |d|² − h² exact enough.
    The model: a point source with a self-similar Gaussian spot, cos i / cos α on tilted
    surfaces (docs/model.md §20).

    Parameters
    ----------
    gun : Gun
        Standoff, spot and flow.
    p, a : ndarray
        Gun tips (T, 3) [m] and unit spray axes (T, 3), or the gun's rotations (T, 3, 3)
        (:func:`gun_axes`; needed by a spot that is not round).
    s, n : ndarray
        Surface points (P, 3) [m] and unit normals ((P, 3) or (3,)) towards the gun.

    Returns
    -------
    ndarray
        (T, P) the film growth rate [m/s].

    Examples
    --------
    At the standoff, the spot's centre grows at flow / (2πσ²), and σ away by e^(−1/2) less:

    >>> import math
    >>> from pollard_pin.painting.spray import Gun, deposition_rate
    >>> gun = Gun(standoff=0.15, sigma=0.01, flow=1.5e-7)
    >>> rate = deposition_rate(gun, [[0, 0, 0.15]], [[0, 0, -1]],
    ...                        [[0, 0, 0], [0.01, 0, 0]], [0, 0, 1])
    >>> math.isclose(rate[0, 0], gun.flow / (2 * math.pi * gun.sigma**2), rel_tol=1e-12)
    True
    >>> math.isclose(rate[0, 1] / rate[0, 0], math.exp(-0.5), rel_tol=1e-12)
    True
    """
    return rate_and_height(gun, p, a, s, n)[0]


def rate_and_height(gun: Gun, p, a, s, n) -> tuple[np.ndarray, np.ndarray]:
    """(:func:`deposition_rate` (T, P), each source's height (p − s)·n above each point's
    tangent plane (T, P) [m]), from the same products."""
    return sources(gun, p, a).rate_and_height(gun, s, n)


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class Sources:
    """A block of samples' spray sources (:func:`sources`): what :func:`rate_and_height`
    needs of them, made once for every set of points the block meets."""

    p: np.ndarray  # (T, 3) the sources (the tips, or the cone's apex in front of them)
    a: np.ndarray  # (T, 3) the unit spray axes
    pa: np.ndarray  # (T,) p·a
    pp: np.ndarray  # (T,) p·p
    axes: tuple | None  # the spot's (u, v) axes (T, 3) each with their p·u, p·v; None: round

    def rate_and_height(self, gun: Gun, s, n) -> tuple[np.ndarray, np.ndarray]:
        """:func:`rate_and_height` of these sources at points ``s`` (P, 3), normals ``n``: the
        compiled loop for the round Gaussian spot (:mod:`.kernel`), numpy's for the others."""
        if type(gun.spot) is RoundGaussian:
            s = np.atleast_2d(np.asarray(s, dtype=float))
            return kernel.round_rate(self.p, self.a, s, n, *_round(gun))
        return self.numpy_rate_and_height(gun, s, n)

    def numpy_rate_and_height(self, gun: Gun, s, n) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`rate_and_height` by numpy's matrix products and elementwise passes, for
        every spot: the compiled loop's reference."""
        s = np.atleast_2d(np.asarray(s, dtype=float))
        p, a = self.p, self.a
        n = np.asarray(n, dtype=float)
        h = s @ a.T - self.pa[None, :]  # (P, T)
        d2 = np.einsum("ij,ij->i", s, s)[:, None] + self.pp[None, :] - 2.0 * s @ p.T
        if n.ndim == 1:
            dn = (s @ n)[:, None] - (p @ n)[None, :]
        else:
            dn = np.einsum("ij,ij->i", s, n)[:, None] - n @ p.T
        if self.axes is None:
            return _rate(gun, h, d2, dn).T, -dn.T
        u, v = (s @ e.T - pe[None, :] for e, pe in self.axes)
        return _rate(gun, h, d2, dn, u, v).T, -dn.T


def sources(gun: Gun, p, a) -> Sources:
    """The :class:`Sources` of tips ``p`` (T, 3) spraying along ``a`` (the unit axes (T, 3)
    or the gun's rotations (T, 3, 3), :func:`gun_axes`)."""
    p = np.atleast_2d(np.asarray(p, dtype=float))
    a, b = gun_axes(a)
    p = _source(gun, p, a)
    axes = _spot_axes(gun, a, b)
    if axes is not None:
        axes = tuple((e, np.einsum("ij,ij->i", p, e)) for e in axes)
    return Sources(p, a, np.einsum("ij,ij->i", p, a), np.einsum("ij,ij->i", p, p), axes)


def near_spot(gun: Gun, p, a, s) -> np.ndarray:
    """Indices of the points ``s`` (P, 3) that tips ``p`` (T, 3) spraying along unit axes
    ``a`` (T, 3) may reach: a superset of those inside any sample's cone (module docstring)
    or within standoff/4 of a nozzle, found from the block's mean tip and axis (the angle to
    each sample's widened by the tips' spread δp and the axes' δa). All points when the
    spray is wider than CULL_WIDEST. ``a`` may be the rotations (T, 3, 3) (:func:`gun_axes`)."""
    p, s = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, s))
    pm, am, dp, da = spot_block(p, a)
    return np.flatnonzero(may_reach(gun, pm, am, dp, da, s))


def spot_block(p, a) -> tuple:
    """(mean tip (3,), mean axis (3,) unnormalised, the tips' spread δp, the axes' spread δa
    [rad] about the normalised mean) of a block of samples: :func:`may_reach`'s summary.
    ``a``: the axes (T, 3) or the rotations (T, 3, 3) (:func:`gun_axes`)."""
    p = np.atleast_2d(np.asarray(p, dtype=float))
    a = gun_axes(a)[0]
    am = a.mean(axis=0)
    pm = p.mean(axis=0)
    dp = float(np.sqrt(((p - pm) ** 2).sum(axis=1).max()))
    norm = np.linalg.norm(am)
    da = float(np.arccos(np.clip(a @ (am / norm), -1.0, 1.0)).max()) if norm > 0 else np.pi
    return pm, am, dp, da


def may_reach(gun: Gun, pm, am, dp: float, da: float, s, radius=0.0) -> np.ndarray:
    """(P,) True where a block of samples summarised by :func:`spot_block` may reach a point
    of ``s`` (P, 3), or, with ``radius`` [m] (one, or (P,)), any point within that distance
    of it (the angle to it widened by arcsin((δp + radius)/r): a chunk of points in its
    bounding ball). The cone is the spot's: tan = reach/standoff, from the source (the apex:
    the block's sources p_j + apex·a_j lie within |apex|·(δa + 1 − |ā|) more of their mean)."""
    return Reach(gun, pm, am, dp, da).keep(s, radius)


class Reach:
    """:func:`may_reach` of one block of samples (:func:`spot_block`'s summary ``pm``,
    ``am``, ``dp``, ``da``), its cone made once for every set of points it is asked about."""

    def __init__(self, gun: Gun, pm, am, dp: float, da: float):
        self.throw = gun.standoff - gun.apex  # the source to the spot's reference plane
        tan_c = gun.spot.reach / self.throw
        norm = np.linalg.norm(am)
        self.everywhere = bool(tan_c > CULL_WIDEST or norm < 0.5)
        if gun.apex and not self.everywhere:
            pm = pm + gun.apex * am
            dp = dp + abs(gun.apex) * (da + 1.0 - norm)
        self.pm, self.dp, self.da = pm, dp, da
        self.am = am if self.everywhere else am / norm
        self.cone = math.atan(tan_c)
        # the compiled test's arguments (keep's scalars as numpy_keep combines them)
        self.cone_args = np.r_[self.pm, self.am, self.dp, self.da, self.cone,
                               self.throw / 4 + self.dp]

    def keep(self, s, radius=0.0) -> np.ndarray:
        """(P,) True where the block may reach a point of ``s`` (P, 3) (or a ball of
        ``radius`` about it): :func:`may_reach`, point by point in the compiled pass
        (:func:`.kernel.cone_keep`: :meth:`numpy_keep`'s operations)."""
        s = np.atleast_2d(np.asarray(s, dtype=float))
        if self.everywhere:
            return np.ones(len(s), dtype=bool)
        return kernel.cone_keep(s, self.cone_args, radius)

    def numpy_keep(self, s, radius=0.0) -> np.ndarray:
        """:meth:`keep` by numpy's elementwise passes: the compiled test's reference."""
        s = np.atleast_2d(np.asarray(s, dtype=float))
        if self.everywhere:
            return np.ones(len(s), dtype=bool)
        d = s - self.pm
        r = np.sqrt(np.einsum("ij,ij->i", d, d))
        with np.errstate(divide="ignore", invalid="ignore"):
            angle = d @ self.am
            angle /= r
            np.arccos(np.minimum(np.maximum(angle, -1.0), 1.0), out=angle)
            spread = (self.dp + radius) / r  # angle(s − p_j, s − p̄)
            np.arcsin(np.minimum(np.maximum(spread, 0.0), 1.0), out=spread)
        keep = (angle - self.da - spread <= self.cone) | (r <= self.throw / 4 + self.dp
                                                          + radius)
        return keep | ~np.isfinite(angle)

    def rate_near(self, gun: Gun, src: Sources, s, n, group, held) -> tuple:
        """(kept (K,), rate (T, K), height (T, K)): the points of ``s`` (P, 3) whose group's
        ball may hold a kept point (``held[group]``, :meth:`holds`) and that :meth:`keep`
        keeps, ascending, with :meth:`Sources.rate_and_height` of them (normals ``n`` (P, 3)
        or (3,)): for the round Gaussian one compiled call (:func:`.kernel.round_near`)."""
        if type(gun.spot) is RoundGaussian:
            return kernel.round_near(src.p, src.a, s, n, group, held,
                                     None if self.everywhere else self.cone_args, *_round(gun))
        near = np.flatnonzero(np.asarray(held)[group])
        k = near[self.keep(s[near])]
        n = np.asarray(n, dtype=float)
        return (k, *src.rate_and_height(gun, s[k], n if n.ndim == 1 else n[k]))

    def holds(self, centres, radii) -> np.ndarray:
        """(G,) True where :meth:`keep` may keep a point of a ball (``centres`` (G, 3),
        ``radii`` (G,)), wherever in it the point lies; False only where it keeps none. A
        point of a ball at r₀ from the block's mean tip lies at r ≥ r₀ − ρ and within
        arcsin(ρ/r₀) of its direction, so its angle is at least the centre's less that and
        its own spread at most arcsin(δp/(r₀ − ρ)); HOLD_PAD covers round-off."""
        c = np.atleast_2d(np.asarray(centres, dtype=float))
        if self.everywhere:
            return np.ones(len(c), dtype=bool)
        d = c - self.pm
        r = np.sqrt(np.einsum("ij,ij->i", d, d))
        near = r - radii  # the ball's least distance from the mean tip
        with np.errstate(divide="ignore", invalid="ignore"):
            angle = np.arccos(np.clip(d @ self.am / r, -1.0, 1.0))
            half = np.arcsin(np.clip(radii / r, 0.0, 1.0))
            spread = np.arcsin(np.clip(self.dp / near, 0.0, 1.0))
        hold = ((angle - half - self.da - spread <= self.cone + HOLD_PAD)
                | (near <= self.throw / 4 + self.dp + HOLD_PAD))
        return hold | (near <= HOLD_PAD) | ~np.isfinite(angle)


def pair_rate(gun: Gun, p, a, s, n) -> np.ndarray:
    """dT/dt [m/s] pair by pair: gun tips ``p`` (K, 3), axes ``a`` (K, 3) or rotations
    (K, 3, 3), points ``s`` (K, 3), normals ``n`` (K, 3): (K,), the rate of
    :func:`deposition_rate` for each pair."""
    p, s, n = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, s, n))
    a, b = gun_axes(a)
    d = s - _source(gun, p, a)
    h, d2, dn = (np.einsum("ij,ij->i", d, x) for x in (a, d, n))
    axes = _spot_axes(gun, a, b)
    if axes is None:
        return _rate(gun, h, d2, dn)
    return _rate(gun, h, d2, dn, *(np.einsum("ij,ij->i", d, e) for e in axes))


def _round(gun: Gun) -> tuple[float, float]:
    """The round Gaussian spot's k (σ(h) = k·h) and flow/2π."""
    return gun.sigma / (gun.standoff - gun.apex), gun.flow / (2.0 * math.pi)


def _rate(gun: Gun, h, d2, dn, u=None, v=None) -> np.ndarray:
    """The rate from h = d·a, d2 = |d|², dn = d·n and, for a spot that is not round, the
    spot coordinates u, v (any one shape)."""
    h, d2, dn = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (h, d2, dn)))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if type(gun.spot) is RoundGaussian:  # in place (the compiled loop's reference)
            k, coef = _round(gun)
            sh2 = k * h
            sh2 *= sh2
            rho2 = d2 - h * h
            np.maximum(rho2, 0.0, out=rho2)
            rho2 *= -0.5
            rho2 /= sh2
            g = np.exp(rho2, out=rho2)  # exp(−ρ²/(2σ(h)²))
            rate = coef / sh2
            rate *= g
        else:
            c = h / (gun.standoff - gun.apex)  # the spot's scale
            if u is None:
                density = gun.spot.density(np.sqrt(np.maximum(d2 - h * h, 0.0)) / c, 0.0)
            else:
                density = gun.spot.density(u / c, v / c)
            rate = gun.flow * density / (c * c)
        # cos i / cos α = (−d·n / |d|) / (h / |d|) = −d·n / h
        rate *= np.maximum(-dn, 0.0)
        rate /= h
        rate[~((h > 0) & (rate < math.inf))] = 0.0  # NaN and inf (h → 0) too: nothing
    return rate


def coarse_weights(t) -> np.ndarray:
    """The trapezoid weights (∫ f dt) on every second sample and the last, zero elsewhere: the
    coarse rule whose difference from the full one is the film's error estimate."""
    t = np.asarray(t, dtype=float)
    idx = np.unique(np.r_[np.arange(0, len(t), 2), len(t) - 1])
    w = np.zeros_like(t)
    w[idx] = trapezoid_weights(t[idx])
    return w


@dataclass(frozen=True)
class Film:
    """Film thickness [m] at each surface point, and the trapezoid rule's error estimate
    |T − T₂| (T₂: the rule on every second sample and the last, whose error is ≥ 4× larger)
    [m]; ``sprayed`` the dry volume the gun sprayed over the samples integrated, flow × their
    trapezoid weights [m³] (docs/model.md §29; nan: not given); ``robots`` a cell's
    films of each robot, whose sum this is (the name a part's :class:`.film.mesh.MeshFilm`
    gives them too: the compliance check reuses them)."""

    thickness: np.ndarray
    error_estimate: np.ndarray
    sprayed: float = math.nan
    robots: tuple = ()


def film(gun: Gun, t, p, a, s, n, origin=None) -> Film:
    """Film at surface points ``s`` (P, 3), normals ``n``, after the gun passes through the
    tips ``p`` (T, 3) with axes ``a`` (T, 3) at times ``t`` (T,): trapezoid rule in time,
    vectorised in blocks of samples. ``origin`` (3,): subtracted from every position first
    (default: the mean of ``s``), for the accuracy of the matrix products.

    Parameters
    ----------
    gun : Gun
        Standoff, spot and flow.
    t : ndarray
        Times (T,) [s].
    p, a : ndarray
        Gun tips (T, 3) [m] and unit spray axes (T, 3), or the gun's rotations (T, 3, 3)
        (:func:`gun_axes`; needed by a spot that is not round).
    s, n : ndarray
        Surface points (P, 3) [m] and unit normals ((P, 3) or (3,)) towards the gun.
    origin : ndarray or None, optional
        (3,) [m].

    Returns
    -------
    pollard_pin.painting.spray.deposition.Film
        ``thickness`` (P,) [m] and the trapezoid rule's ``error_estimate`` (P,) [m].

    Examples
    --------
    A straight pass at speed v over a point leaves flow / (√(2π) σ v):

    >>> import math
    >>> import numpy as np
    >>> from pollard_pin.painting.spray import Gun, film
    >>> gun = Gun(standoff=0.15, sigma=0.01, flow=1.5e-7)
    >>> t = np.linspace(-1.0, 1.0, 2001)
    >>> v = 0.5                                          # m/s, along x
    >>> tips = np.column_stack([v * t, 0 * t, 0 * t + 0.15])
    >>> axes = np.tile([0.0, 0.0, -1.0], (len(t), 1))
    >>> f = film(gun, t, tips, axes, [[0.0, 0.0, 0.0]], [0.0, 0.0, 1.0])
    >>> math.isclose(f.thickness[0], gun.flow / (math.sqrt(2 * math.pi) * gun.sigma * v),
    ...              rel_tol=1e-9)
    True
    """
    t = np.asarray(t, dtype=float)
    p, a, s = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, a, s))
    n = np.asarray(n, dtype=float)
    o = s.mean(axis=0) if origin is None else np.asarray(origin, dtype=float)
    p, s = p - o, s - o
    w, w2 = trapezoid_weights(t), coarse_weights(t)
    total, coarse = np.zeros(len(s)), np.zeros(len(s))
    block = max(1, BLOCK_ELEMENTS // max(len(s), 1))
    for start in bar(range(0, len(t), block), "film"):
        sl = slice(start, start + block)
        k = near_spot(gun, p[sl], a[sl], s)
        r = deposition_rate(gun, p[sl], a[sl], s[k], n if n.ndim == 1 else n[k])
        total[k] += w[sl] @ r
        coarse[k] += w2[sl] @ r
    err = np.abs(total - coarse) if len(t) > 2 else np.full(len(s), np.nan)
    return Film(total, err, float(gun.flow * w.sum()))


def gun_of(job) -> Gun:
    """The gun of a job, a panel's or a part's (its standoff, spot, flow and apex)."""
    return Gun(job.standoff, job.sigma, job.flow, job.spot, job.apex or 0.0)


__all__ = ["CULL_SIGMAS", "Film", "Gun", "coarse_weights", "deposition_rate", "film",
           "Reach", "Sources", "gun_axes", "gun_of", "may_reach", "near_spot", "pair_rate",
           "rate_and_height", "sources", "spot_block"]
