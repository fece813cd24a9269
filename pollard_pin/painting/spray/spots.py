"""Spray spots: the areal density of the paint on the plane across the spray axis
(docs/model.md §20).

A spot is given at the reference standoff h0 (the gun's ``standoff``) in the gun's own frame:
u along R·e_y, v along R·e_z (the spray axis is R·e_x). Every spot integrates to 1 (unit
flow). At another distance h along the axis it is the same spot scaled by
:meth:`Spot.scale` = (h − apex)/(h0 − apex): paint flies in straight lines from a virtual
source ``apex`` in front of the nozzle (0: the nozzle itself; negative: behind it), so the
spot's angular shape is the same at every distance.

A stroke at speed w through the spot's centre at normal incidence, at the standoff, leaves
the stripe q·stripe(x)/w, with stripe(x) = ∫ density dy, x across the stroke. Every model
has its stripe in closed form, its cumulative stripe (the film at a straight edge of passes)
and its Fourier transform (the ripple between passes, by Poisson summation).

Directions: ``"along"`` is a stroke moving along the spot's long axis (its profile is the
short one), ``"across"`` a stroke moving across it (its profile is the long one). The
planner's passes move along the gun's y axis (horizontal passes), so its strokes are
``"across"`` for the elliptic spot, whose long axis is the gun's z axis.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import ClassVar

import numpy as np
from scipy import special

DIRECTIONS = ("along", "across")
# The job's pass direction → the stroke's direction to the spot's long axis (the gun's z):
# horizontal passes move along the gun's y axis, vertical ones along its z axis.
STROKES = {"horizontal": "across", "vertical": "along"}
REACH_SIGMAS = 10.0  # a Gaussian's culling radius in σ (e^(−50) ≈ 2e-22 of its peak)


def _direction(direction: str) -> str:
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, not {direction!r}")
    return direction


@dataclass(frozen=True)
class Spot:
    """A spray spot at the reference standoff (module docstring); subclasses give the shape.

    Sizes are lengths [m] at the gun's standoff."""

    name: ClassVar[str] = ""
    round: ClassVar[bool] = True  # the density depends on u² + v² alone

    def scale(self, h, standoff: float, apex: float = 0.0) -> np.ndarray:
        """The spot's size factor at distance ``h`` [m] along the axis: (h − apex)/(standoff −
        apex), a cone whose apex is ``apex`` [m] in front of the nozzle (0: a point source).

        Parameters
        ----------
        h : float or ndarray
            Distances along the spray axis from the nozzle [m].
        standoff : float
            The reference standoff [m], where the factor is 1.
        apex : float, optional
            The cone's apex in front of the nozzle [m] (negative: behind it).

        Returns
        -------
        ndarray
            The factor by which every length of the spot is multiplied.
        """
        return (np.asarray(h, dtype=float) - apex) / (standoff - apex)

    def density(self, u, v) -> np.ndarray:
        """Areal density [1/m²] of unit flow at (``u``, ``v``) [m] in the spot plane at the
        standoff (u along the gun's y axis, v along its z axis); integrates to 1.

        Parameters
        ----------
        u, v : float or ndarray
            Coordinates in the plane across the spray axis [m] (broadcast together).

        Returns
        -------
        ndarray
            The density [1/m²].
        """
        raise NotImplementedError

    def stripe(self, x, direction: str = "across") -> np.ndarray:
        """∫ density dy [1/m] across a straight stroke, at ``x`` [m] from its centre line;
        integrates to 1 over x.

        Parameters
        ----------
        x : float or ndarray
            Distance across the stroke [m].
        direction : {"along", "across"}, optional
            The stroke moves along or across the spot's long axis (module docstring).

        Returns
        -------
        ndarray
            The stripe [1/m]: a stroke at speed w with flow q at the standoff, normal
            incidence, leaves the thickness q·stripe(x)/w.
        """
        raise NotImplementedError

    def stripe_at(self, x, h, standoff: float, apex: float = 0.0,
                  direction: str = "across") -> np.ndarray:
        """The stripe [1/m] of a stroke at distance ``h`` along the axis: stripe(x/c)/c with
        c = :meth:`scale` (the spread law; normal incidence, the stroke at that distance).

        Parameters
        ----------
        x : float or ndarray
            Distance across the stroke [m].
        h : float
            The nozzle's distance to the surface [m].
        standoff : float
            The reference standoff [m], where the spot is given.
        apex : float, optional
            The cone's apex in front of the nozzle [m].
        direction : {"along", "across"}, optional
            As in :meth:`stripe`.

        Returns
        -------
        ndarray
            A stroke at speed w with flow q leaves q·stripe_at(x)/w.
        """
        c = self.scale(h, standoff, apex)
        return self.stripe(np.asarray(x, dtype=float) / c, direction) / c

    def stripe_cdf(self, x, direction: str = "across") -> np.ndarray:
        """∫_{−∞}^{x} stripe dx': the film beside the edge of a field of passes, relative.

        Parameters
        ----------
        x : float or ndarray
            Distance across the stroke [m].
        direction : {"along", "across"}, optional
            As in :meth:`stripe`.

        Returns
        -------
        ndarray
            In [0, 1].
        """
        raise NotImplementedError

    def transform(self, k, direction: str = "across") -> np.ndarray:
        """The stripe's Fourier transform ∫ stripe(x) cos(kx) dx (real: every stripe is even).

        Parameters
        ----------
        k : float or ndarray
            Angular wavenumber [rad/m].
        direction : {"along", "across"}, optional
            As in :meth:`stripe`.

        Returns
        -------
        ndarray
            1 at k = 0.
        """
        raise NotImplementedError

    def spread(self, direction: str = "across") -> float:
        """The stripe's standard deviation [m] (its σ-equivalent).

        Parameters
        ----------
        direction : {"along", "across"}, optional
            As in :meth:`stripe`.

        Returns
        -------
        float
            √(∫ x² stripe(x) dx).
        """
        raise NotImplementedError

    def ripple(self, spacing, direction: str = "across") -> np.ndarray:
        """The interior film's relative ripple for passes ``spacing`` [m] apart:
        max |Δ·Σ_k stripe(y − kΔ) − 1| over a period, sampled at Δ/512 (docs/model.md §20).

        Parameters
        ----------
        spacing : float or ndarray
            Distance between passes [m].
        direction : {"along", "across"}, optional
            As in :meth:`stripe`.

        Returns
        -------
        ndarray
            The largest |film/mean − 1| between long passes.
        """
        d = np.asarray(spacing, dtype=float)
        y = np.linspace(0.0, 0.5, 257)  # the film is even and periodic: half a period
        out = np.empty(d.shape)
        for i, di in np.ndenumerate(d):
            k = np.arange(-math.ceil(self.reach / di) - 1, math.ceil(self.reach / di) + 2)
            film = di * self.stripe(di * (y[:, None] - k[None, :]), direction).sum(axis=1)
            out[i] = np.abs(film - 1.0).max()
        return out

    def spacing(self, tolerance: float, direction: str = "across") -> float:
        """The widest pass spacing [m] below which the ripple (:meth:`ripple`) stays within
        ``tolerance``: scanned on a grid from 0.1 spread up, then bisected.

        Parameters
        ----------
        tolerance : float
            The largest interior ripple allowed (relative).
        direction : {"along", "across"}, optional
            As in :meth:`stripe`.

        Returns
        -------
        float
            The spacing [m].
        """
        s = self.spread(direction)
        grid = s * np.geomspace(0.1, 10.0, 300)
        bad = np.flatnonzero(self.ripple(grid, direction) > tolerance)
        if len(bad) == 0:
            return float(grid[-1])
        lo, hi = float(grid[max(bad[0] - 1, 0)]), float(grid[bad[0]])
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.ripple(mid, direction) <= tolerance else (lo, mid)
        return lo

    @property
    def width(self) -> float:
        """The spread [m] across the planner's strokes (:meth:`spread` ``"across"``): the σ of
        pass spacing, panel margins and the smallest panel."""
        return self.spread("across")

    @property
    def peak(self) -> float:
        """The density at the spot's centre [1/m²]."""
        return float(self.density(0.0, 0.0))

    @property
    def reach(self) -> float:
        """Radius [m] at the standoff beyond which the density is 0 or below 1e-18 of its
        peak: the culling cone (docs/model.md §20)."""
        raise NotImplementedError

    def params(self) -> dict[str, float]:
        """The spot's parameters by name, as the job's ``[gun]`` table takes them.

        Returns
        -------
        dict
            {name: value [m or 1]}.
        """
        return {f.name: float(getattr(self, f.name)) for f in fields(self)}

    @classmethod
    def from_params(cls, **p) -> Spot:
        """The spot of those parameters (the inverse of :meth:`params`).

        Parameters
        ----------
        **p : float
            The model's parameters by name.

        Returns
        -------
        Spot
            The spot.
        """
        return cls(**{k: float(v) for k, v in p.items()})


@dataclass(frozen=True)
class RoundGaussian(Spot):
    """The round Gaussian spot: exp(−r²/2σ²)/(2πσ²).

    Parameters
    ----------
    sigma : float
        Spread at the standoff [m].
    """

    sigma: float
    name: ClassVar[str] = "gaussian"

    def __post_init__(self):
        _positive(self, "sigma")

    def density(self, u, v):
        return _gauss(np.asarray(u, dtype=float), self.sigma) * _gauss(
            np.asarray(v, dtype=float), self.sigma)

    def stripe(self, x, direction="across"):
        _direction(direction)
        return _gauss(np.asarray(x, dtype=float), self.sigma)

    def stripe_cdf(self, x, direction="across"):
        _direction(direction)
        return special.ndtr(np.asarray(x, dtype=float) / self.sigma)

    def transform(self, k, direction="across"):
        _direction(direction)
        return np.exp(-0.5 * (np.asarray(k, dtype=float) * self.sigma) ** 2)

    def spread(self, direction="across"):
        _direction(direction)
        return self.sigma

    def ripple(self, spacing, direction="across"):
        # Poisson summation's first term, 2·exp(−2π²σ²/Δ²): the rest are below its 4th power
        return 2.0 * np.exp(-2.0 * (math.pi * self.spread(direction)
                                    / np.asarray(spacing, dtype=float)) ** 2)

    def spacing(self, tolerance, direction="across"):
        # the first Poisson term alone, 2·exp(−2π²σ²/Δ²), as the planner always had
        _direction(direction)
        return self.sigma * math.pi * math.sqrt(2.0 / math.log(2.0 / tolerance))

    @property
    def reach(self):
        return REACH_SIGMAS * self.sigma


@dataclass(frozen=True)
class EllipticGaussian(Spot):
    """The elliptic Gaussian spot: exp(−u²/2σs² − v²/2σl²)/(2π σl σs), its long axis along
    the gun's z axis (turned with the gun about its spray axis).

    Parameters
    ----------
    sigma_long : float
        Spread along the long axis (the gun's z) at the standoff [m].
    sigma_short : float
        Spread along the short axis (the gun's y) at the standoff [m], ≤ ``sigma_long``.
    """

    sigma_long: float
    sigma_short: float
    name: ClassVar[str] = "elliptic"
    round: ClassVar[bool] = False

    def __post_init__(self):
        _positive(self, "sigma_long")
        _positive(self, "sigma_short")
        if self.sigma_short > self.sigma_long:
            raise ValueError(f"sigma_short ({self.sigma_short:g} m) must not exceed "
                             f"sigma_long ({self.sigma_long:g} m)")

    def density(self, u, v):
        return _gauss(np.asarray(u, dtype=float), self.sigma_short) * _gauss(
            np.asarray(v, dtype=float), self.sigma_long)

    def stripe(self, x, direction="across"):
        return _gauss(np.asarray(x, dtype=float), self.spread(direction))

    def stripe_cdf(self, x, direction="across"):
        return special.ndtr(np.asarray(x, dtype=float) / self.spread(direction))

    def transform(self, k, direction="across"):
        return np.exp(-0.5 * (np.asarray(k, dtype=float) * self.spread(direction)) ** 2)

    def spread(self, direction="across"):
        return self.sigma_long if _direction(direction) == "across" else self.sigma_short

    def ripple(self, spacing, direction="across"):
        return RoundGaussian(self.spread(direction)).ripple(spacing)

    def spacing(self, tolerance, direction="across"):
        return RoundGaussian(self.spread(direction)).spacing(tolerance)

    @property
    def reach(self):
        return REACH_SIGMAS * self.sigma_long


@dataclass(frozen=True)
class BetaSpot(Spot):
    """The β-distribution spot: β/(πR²)·(1 − r²/R²)^(β−1) for r ≤ R, 0 beyond (a finite
    footprint). β > 1: the density falls continuously to 0 at the rim (β = 1 is a flat disc
    with a step, β < 1 a rim of infinite density).

    Parameters
    ----------
    radius : float
        The footprint's radius R at the standoff [m].
    beta : float
        The exponent β (> 1); large β tends to a Gaussian of σ = R/√(2(β + 1)).
    """

    radius: float
    beta: float
    name: ClassVar[str] = "beta"

    def __post_init__(self):
        _positive(self, "radius")
        if not (math.isfinite(self.beta) and self.beta > 1.0):
            raise ValueError(f"beta must be a number > 1, not {self.beta!r}")

    def density(self, u, v):
        r2 = (np.asarray(u, dtype=float) ** 2 + np.asarray(v, dtype=float) ** 2) / self.radius**2
        inside = np.maximum(1.0 - r2, 0.0)
        return self.beta / (math.pi * self.radius**2) * inside ** (self.beta - 1.0)

    def stripe(self, x, direction="across"):
        # ∫ dy of the density: (1 − x²/R²)^(β−1/2) / (R·B(1/2, β + 1/2)) (docs/model.md §20)
        _direction(direction)
        inside = np.maximum(1.0 - (np.asarray(x, dtype=float) / self.radius) ** 2, 0.0)
        return (inside ** (self.beta - 0.5)
                * math.exp(-special.betaln(0.5, self.beta + 0.5)) / self.radius)

    def stripe_cdf(self, x, direction="across"):
        # t = (1 + x/R)/2 ∈ [0, 1] has density ∝ (t(1 − t))^(β−1/2): Beta(β + 1/2, β + 1/2)
        _direction(direction)
        t = np.clip(0.5 * (1.0 + np.asarray(x, dtype=float) / self.radius), 0.0, 1.0)
        return special.betainc(self.beta + 0.5, self.beta + 0.5, t)

    def transform(self, k, direction="across"):
        # Γ(β + 1)·(2/kR)^β·J_β(kR) (Poisson's integral for the Bessel function)
        _direction(direction)
        z = np.abs(np.asarray(k, dtype=float)) * self.radius
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            out = (np.exp(special.gammaln(self.beta + 1.0) + self.beta * np.log(2.0 / z))
                   * special.jv(self.beta, z))
        return np.where(z > 1e-8, out, 1.0 - z**2 / (4.0 * (self.beta + 1.0)))

    def spread(self, direction="across"):
        # x²/R² of the stripe is Beta(1/2, β + 1/2): E = 1/(2(β + 1))
        _direction(direction)
        return self.radius / math.sqrt(2.0 * (self.beta + 1.0))

    @property
    def reach(self):
        return self.radius


#: The spot models by name, as the job's ``[gun]`` ``model`` names them.
SPOTS: dict[str, type[Spot]] = {c.name: c for c in (RoundGaussian, EllipticGaussian, BetaSpot)}


def _gauss(x: np.ndarray, sigma: float) -> np.ndarray:
    return np.exp(-0.5 * (x / sigma) ** 2) / (math.sqrt(2.0 * math.pi) * sigma)


def _positive(spot: Spot, key: str) -> None:
    value = getattr(spot, key)
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise ValueError(f"{key} must be a positive length, not {value!r}")


__all__ = ["BetaSpot", "DIRECTIONS", "EllipticGaussian", "REACH_SIGMAS", "RoundGaussian",
           "SPOTS", "STROKES", "Spot"]
