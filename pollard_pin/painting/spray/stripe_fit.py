"""One spot model fitted to measured stripes by nonlinear least squares (docs/model.md §30).

The stripe a gun leaves on a flat panel at normal incidence, at standoff h, speed v and liquid
flow q, of a paint of volume solids φ and transfer efficiency η, is

    T(x) = η φ q / v · stripe((x − c)/s, direction) / s,    s = (h − apex)/(h₀ − apex),

``stripe`` the spot's own (integrating to 1) at the reference standoff h₀ and c the stripe's
centre on the panel. The unknowns, all fitted together by ``scipy.optimize.least_squares``
(trust-region reflective, within bounds): the spot's sizes at h₀, the apex of its spread law
(two standoffs or more), η (unless given) and each stripe's centre. Standard errors: the
covariance s²(JᵀJ)⁻¹ at the solution, s² = RSS/(N − k), J the Jacobian of the residuals.
A fit counts only if the method converged, no parameter rests on a bound and JᵀJ is well
conditioned (the parameters are identifiable from the stripes).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from ..gun_table import MAX_APEX, MAX_ELONGATION
from .spots import SPOTS

# The β spot's exponent: > 1 (a density falling to 0 at the rim); β → ∞ is the Gaussian,
# which the Gaussian model fits
BETA_BOUNDS = (1.0 + 1e-6, 60.0)
BETA_START = 3.0
SHAPE_NEAR = 0.01  # a shape this share of its interval from its upper bound tends to it
RATIO_LOWEST = 1.0 / MAX_ELONGATION  # σ_short/σ_long: the longest spot a job takes
LIMITS = {"ratio": "a round spot: the gaussian model's",  # a shape at its upper bound
          "beta": "a Gaussian profile: the gaussian model's"}
MAX_EVALUATIONS = 300  # least squares iterations: a good fit takes 10-50
UNDETERMINED = 0.5  # a size whose standard error is over half of it is not determined
ILL_CONDITIONED = 1e12  # cond(JᵀJ) in scaled parameters beyond which they are not identified


@dataclass(frozen=True)
class StripeData:
    """What a fit needs of one stripe: positions [m], film [m], standoff [m], the film
    per unit of transfer efficiency ``amount`` = φ q / v [m²], its direction."""

    x: np.ndarray
    t: np.ndarray
    standoff: float
    amount: float
    direction: str


@dataclass(frozen=True)
class ModelFit:
    """One spot model fitted to the stripes (:func:`fit_model`).

    Attributes
    ----------
    name : str
        The model (``gaussian``, ``elliptic``, ``beta``).
    standoff : float
        The reference standoff [m], where the spot has its sizes.
    spot : object or None
        The fitted spot at the reference standoff (a spot of
        :mod:`pollard_pin.painting.spray.spots`).
    params, errors : dict
        The spot's parameters at the reference standoff and their standard errors (also
        ``apex`` [m] and ``efficiency`` where fitted).
    offsets, offset_errors : tuple of float
        Each stripe's centre on its positions [m] and its standard error.
    apex, efficiency : float
        The spread law's apex [m] and the transfer efficiency (fitted or given).
    rss : float
        The residuals' sum of squares [m²].
    points, k : int
        The points fitted and the parameters fitted.
    aic, bic : float
        The information criteria N ln(RSS/N) + 2k and N ln(RSS/N) + k ln N.
    rms_share : float
        The residuals' RMS over the highest stripe's peak.
    usable : bool
        Converged, within its bounds, identifiable.
    why : str
        Why not usable ("" when it is).
    """

    name: str
    standoff: float
    spot: object | None
    params: dict
    errors: dict
    offsets: tuple
    offset_errors: tuple
    apex: float
    efficiency: float
    rss: float
    points: int
    k: int
    aic: float
    bic: float
    rms_share: float
    usable: bool
    why: str = ""
    stripe_rms: tuple = field(default=(), repr=False)  # per stripe, over its own peak

    def thickness(self, data: StripeData, x, offset: float) -> np.ndarray:
        """The film [m] the fitted spot leaves at ``x`` across the stripe ``data``."""
        return _stripe(self.spot, data, np.asarray(x, float), offset, self.apex,
                       self.efficiency, self.standoff)


def _stripe(spot, d: StripeData, x, offset, apex, efficiency, h0) -> np.ndarray:
    return efficiency * d.amount * spot.stripe_at(x - offset, d.standoff, h0, apex,
                                                  d.direction)


def fit_variables(name: str, spread: dict, width: float) -> list[tuple]:
    """The model's fit variables: (name, start, scale, lower, upper) each, from each
    direction's measured spread ``spread[direction]`` [m] at the reference standoff.

    The elliptic spot is fitted as σ_long and the ratio σ_short/σ_long ≤ 1, so that no step
    leaves the model (a ratio on its bound 1 is a round spot: the Gaussian's)."""
    mean = float(np.mean(list(spread.values())))
    length = (1e-3 * width, 1e3 * width)
    if name == "gaussian":
        return [("sigma", mean, width, *length)]
    if name == "elliptic":  # a stroke across the long axis shows the long size across it
        long, short = spread.get("across", mean), spread.get("along", mean)
        return [("sigma_long", long, width, *length),
                ("ratio", min(max(short / long, 0.1), 0.95), 1.0, RATIO_LOWEST, 1.0)]
    if name == "beta":  # the stripe's σ is R/√(2(β + 1))
        return [("radius", mean * math.sqrt(2.0 * (BETA_START + 1.0)), width, *length),
                ("beta", BETA_START, 1.0, *BETA_BOUNDS)]
    raise KeyError(name)


def spot_params(name: str, v: dict) -> dict:
    """The spot's parameters (:meth:`Spot.params`) of the fit variables ``v``."""
    if name == "elliptic":
        return {"sigma_long": v["sigma_long"], "sigma_short": v["ratio"] * v["sigma_long"]}
    return dict(v)


def fit_model(name: str, data: list[StripeData], h0: float, centres, spread: dict, *,
              fit_apex: bool, efficiency: float | None, efficiency0: float) -> ModelFit:
    """Fit the spot model ``name`` to the stripes ``data`` (module docstring).

    Parameters
    ----------
    name : str
        A key of :data:`pollard_pin.painting.spray.spots.SPOTS`.
    data : list of StripeData
        The stripes.
    h0 : float
        The reference standoff [m].
    centres : sequence of float
        Each stripe's first moment [m] (the centres' start).
    spread : dict
        Each direction's measured spread at ``h0`` [m] (the sizes' start).
    fit_apex : bool
        Fit the spread law's apex (else 0: a cone from the nozzle).
    efficiency : float or None
        The transfer efficiency, or None to fit it.
    efficiency0 : float
        Its start (the stripes' integrals).

    Returns
    -------
    ModelFit
    """
    cls = SPOTS[name]
    width = max(spread.values())
    unknowns = fit_variables(name, spread, width)
    n_shape = len(unknowns)
    hmin = min(d.standoff for d in data)
    if fit_apex:  # apex below the nearest standoff; a virtual apex behind the nozzle may be
        unknowns.append(("apex", 0.0, h0, -10.0 * h0, MAX_APEX * min(hmin, h0)))
    if efficiency is None:  # > 1 allowed here: the stripes' own integrals were checked
        unknowns.append(("efficiency", efficiency0, 1.0, 1e-4, 10.0))
    for i, (d, c) in enumerate(zip(data, centres)):
        span = d.x[-1] - d.x[0]
        unknowns.append((f"offset{i}", c, width, d.x[0] - span, d.x[-1] + span))
    names = [u[0] for u in unknowns]
    scale = np.array([u[2] for u in unknowns])
    lo = np.array([u[3] for u in unknowns]) / scale
    hi = np.array([u[4] for u in unknowns]) / scale
    z0 = np.clip(np.array([u[1] for u in unknowns]) / scale, lo + 1e-3 * (hi - lo),
                 hi - 1e-3 * (hi - lo))
    tscale = max(float(d.t.max()) for d in data)
    k, m = len(names), len(data)

    def unpack(z):
        theta = z * scale
        p = dict(zip(names, theta))
        params = spot_params(name, {n: float(p[n]) for n in names[:n_shape]})
        return (cls.from_params(**params), float(p.get("apex", 0.0)),
                float(p["efficiency"]) if efficiency is None else efficiency, theta[k - m:])

    def residuals(z):
        spot, apex, eta, offs = unpack(z)
        return np.concatenate([_stripe(spot, d, d.x, o, apex, eta, h0) - d.t
                               for d, o in zip(data, offs)]) / tscale

    # tr_solver "lsmr": the exact solver's SVD of the (N × k) Jacobian runs multi-threaded
    # BLAS, hundreds of times slower on a loaded machine than this
    res = least_squares(residuals, z0, bounds=(lo, hi), method="trf", jac="2-point",
                        tr_solver="lsmr", xtol=1e-10, ftol=1e-10, gtol=1e-10,
                        max_nfev=MAX_EVALUATIONS)
    spot, apex, eta, offs = unpack(res.x)
    theta = res.x * scale
    n = sum(len(d.x) for d in data)
    rss = float(np.sum(res.fun ** 2)) * tscale ** 2
    jtj = res.jac.T @ res.jac
    cond = np.linalg.cond(jtj)
    cov = np.full((k, k), np.nan)
    if n > k and np.isfinite(cond):
        cov = float(np.sum(res.fun ** 2)) / (n - k) * np.linalg.pinv(jtj) * np.outer(scale,
                                                                                      scale)
    params, errors = _with_errors(name, dict(zip(names[:n_shape], theta[:n_shape])),
                                  cov[:n_shape, :n_shape])
    for extra in ("apex", "efficiency"):
        if extra in names:
            errors[extra] = _se(cov, names.index(extra))
    why = _unusable(res, cond, names, theta, lo, hi, params, errors)
    ll = n * math.log(max(rss, 1e-300) / n)
    per = tuple(float(np.sqrt(np.mean((_stripe(spot, d, d.x, o, apex, eta, h0) - d.t) ** 2))
                      / d.t.max()) for d, o in zip(data, offs))
    return ModelFit(name=name, standoff=h0, spot=spot, params=params, errors=errors,
                    offsets=tuple(float(o) for o in offs),
                    offset_errors=tuple(_se(cov, i) for i in range(k - m, k)),
                    apex=apex, efficiency=eta, rss=rss, points=n, k=k, aic=ll + 2 * k,
                    bic=ll + k * math.log(n), rms_share=math.sqrt(rss / n) / tscale,
                    usable=not why, why=why, stripe_rms=per)


def _se(cov: np.ndarray, i: int) -> float:
    return float(math.sqrt(max(cov[i, i], 0.0))) if np.isfinite(cov[i, i]) else math.nan


def _with_errors(name: str, v: dict, cov: np.ndarray) -> tuple[dict, dict]:
    """The spot's parameters and their standard errors: the fit variables' covariance
    carried through the map :func:`spot_params` (its Jacobian by central differences)."""
    keys = list(v)
    params = spot_params(name, v)
    g = np.empty((len(params), len(keys)))
    for j, key in enumerate(keys):
        h = 1e-6 * max(abs(v[key]), 1e-12)
        up = spot_params(name, {**v, key: v[key] + h})
        down = spot_params(name, {**v, key: v[key] - h})
        g[:, j] = [(up[p] - down[p]) / (2 * h) for p in params]
    c = g @ cov @ g.T
    return ({p: float(x) for p, x in params.items()},
            {p: _se(c, i) for i, p in enumerate(params)})


def _unusable(res, cond, names, theta, lo, hi, params, errors) -> str:
    """Why a fit does not count (module docstring), or ""."""
    if not res.success:
        return f"least squares did not converge ({res.message})"
    if not np.isfinite(cond) or cond > ILL_CONDITIONED:
        return "its parameters are not identifiable from these stripes (JᵀJ singular)"
    # on a bound to a millionth of the interval (lsmr's active_mask is not exact); a shape
    # (β, the ratio) within a hundredth of its upper bound tends to its limit there: the
    # Gaussian, a round spot (β near 1, a flat disc, is a shape of its own)
    near = np.array([SHAPE_NEAR if n in ("beta", "ratio") else 1e-6 for n in names])
    at = np.flatnonzero((res.x - lo <= 1e-6 * (hi - lo)) | (hi - res.x <= near * (hi - lo)))
    if len(at):
        i = at[0]
        if names[i] in LIMITS and hi[i] - res.x[i] <= near[i] * (hi[i] - lo[i]):
            return f"{names[i]} → {theta[i]:.4g}, {LIMITS[names[i]]}"
        return f"{names[i]} rests on its bound ({theta[i]:.4g})"
    vague = [p for p in params if not errors[p] < UNDETERMINED * abs(params[p])]
    if vague:
        p = vague[0]
        return f"{p} = {params[p]:.4g} ± {errors[p]:.2g}: not determined by these stripes"
    return ""


__all__ = ["ModelFit", "StripeData", "fit_model", "fit_variables", "spot_params"]
