"""The spray pattern calibrated from measured stripes (docs/model.md §30): every spot model
fitted (:mod:`.stripe_fit`), the one chosen by the Bayesian information criterion among those
that fit, and the gun it makes.

Before any fit, each stripe is checked against what a fit needs: film above the noise, bare
panel at both ends, no negative film beyond the noise, enough points across the spot, and a
transfer efficiency η = ∫T dx · v / (φ q) in (0, 1] (more paint on the stripe than was sprayed
is a flow, solids or speed in other units). Each failure is one :class:`StripeError` line
saying what to measure.

Why BIC: the stripes hold hundreds of points, and BIC's penalty k ln N then picks the true
model with a probability that tends to one (it is consistent), where AIC's 2k keeps a
sizeable chance of the elliptic spot's extra σ on a round one; both are reported.
"""
from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass

import numpy as np

from ...checks import instance, real, shorten
from ...errors import InputError, SolveError
from ...io.stripes import StripeError, StripeSet
from ...model.params import did_you_mean
from .deposition import Gun
from .spots import SPOTS
from .stripe_fit import ModelFit, StripeData, fit_model

CRITERION = "bic"
MODELS = ("gaussian", "elliptic", "beta")
SPREADS = ("auto", "cone", "fit")
NOISE_SIGMAS = 5.0  # a value is beyond the noise past this many noise σ
END_SHARE = 0.05  # an end of the stripe holds at most this share of its peak (bare panel)
MIN_ACROSS = 5  # points above half the peak: fewer cannot show the spot's shape
EFFICIENCY_MAX = 1.1  # the stripes' own η beyond this: the flow, solids or speed are off
EFFICIENCY_MIN = 0.02  # below: almost no paint landed, or the flow is in other units
GIVEN_AGREES = 1.1  # a given efficiency within this factor of the stripes' own η
EXTRAPOLATE = 1.5  # the reference standoff at most this factor beyond the stripes' ones
SWAPPED = 1.05  # 'along' stripes this much wider than 'across' ones: the labels swapped
POOR_FIT = 0.05  # a chosen model's residual RMS beyond this share of the peak is noted


@dataclass(frozen=True)
class CalibrateOptions:
    """How to calibrate (checked once).

    Parameters
    ----------
    model : str, optional
        ``"auto"`` (default): every spot model the stripes identify, the one of least BIC
        chosen; or one of ``"gaussian"``, ``"elliptic"``, ``"beta"``.
    spread : str, optional
        The spread law's apex: ``"auto"`` (default) fitted when the stripes have two
        standoffs or more, else 0 (a cone from the nozzle); ``"cone"``: 0; ``"fit"``: fitted
        (two standoffs needed).
    efficiency : float or None, optional
        The transfer efficiency η in (0, 1] when known; None (default): fitted, one for all
        stripes.
    """

    model: str = "auto"
    spread: str = "auto"
    efficiency: float | None = None

    def __post_init__(self):
        for key, choices in (("model", ("auto", *MODELS)), ("spread", SPREADS)):
            value = getattr(self, key)
            if value not in choices:
                raise InputError(f"CalibrateOptions.{key} = {shorten(value)}: expected one of "
                                 f"{', '.join(choices)}{did_you_mean(str(value), choices)}")
        if self.efficiency is not None:
            object.__setattr__(self, "efficiency", real(
                self.efficiency, "CalibrateOptions.efficiency", 0.0, 1.0, above=True,
                why=" (the share of the sprayed paint that lands, in (0, 1])"))


@dataclass(frozen=True)
class CalibrationFit:
    """The stripes' calibration (:func:`fit_stripes`).

    Attributes
    ----------
    stripes : pollard_pin.io.stripes.StripeSet
        The stripes fitted.
    standoff : float
        The reference standoff [m]: the spots' sizes are there.
    flow : float
        The liquid flow of the gun written [m³/s]: the stripes' most common.
    fits : tuple of ModelFit
        Every model tried, in :data:`MODELS` order.
    skipped : dict
        The models not tried and why (not identifiable from these stripes).
    chosen : str
        The model chosen.
    spread : str
        ``"fitted"`` or ``"cone"`` (apex 0).
    notes : tuple of str
        What the user should know (a spread law not fitted, a model skipped).
    """

    stripes: StripeSet
    standoff: float
    flow: float
    fits: tuple
    skipped: dict
    chosen: str
    spread: str
    notes: tuple = ()

    @property
    def best(self) -> ModelFit:
        """The chosen model's fit."""
        return next(f for f in self.fits if f.name == self.chosen)

    def data(self) -> list[StripeData]:
        """The stripes as the fit saw them."""
        return stripe_data(self.stripes)

    def gun(self) -> Gun:
        """The calibrated gun: the chosen spot at the reference standoff, its apex, and the
        dry film flow φ η q it deposits at the stripes' most common liquid flow q."""
        best = self.best
        return Gun(self.standoff, None, self.flow * self.stripes.solids * best.efficiency,
                   spot=best.spot, apex=best.apex)


def stripe_data(stripes: StripeSet) -> list[StripeData]:
    return [StripeData(s.position, s.thickness, s.standoff, stripes.solids * s.flow / s.speed,
                       s.direction) for s in stripes.stripes]


def noise(t: np.ndarray) -> float:
    """The measurement noise σ [m] of a profile, from its second differences (robust: the
    median absolute deviation; white noise of σ gives second differences of σ√6)."""
    d2 = np.diff(t, 2)
    return float(1.4826 * np.median(np.abs(d2 - np.median(d2))) / math.sqrt(6.0))


def check_stripe(s, solids: float) -> tuple[float, float]:
    """One stripe against what a fit needs (module docstring): its centre and variance
    (first and second moments) [m, m²], else one :class:`StripeError` line."""
    x, t, where = s.position, s.thickness, s.source
    sigma = noise(t)
    peak = float(t.max())
    if peak <= 0:
        raise StripeError(f"{where}: no film: every reading is ≤ 0 (the thickness column "
                          "negated, or the bare panel's?): measure a stripe that holds paint")
    if peak <= NOISE_SIGMAS * sigma:
        raise StripeError(f"{where}: no film above the noise (peak {peak * 1e6:.3g} µm, noise "
                          f"±{sigma * 1e6:.2g} µm): measure a stripe that holds paint")
    floor = NOISE_SIGMAS * sigma + 0.01 * peak
    i = int(np.argmin(t))
    if t[i] < -floor:
        raise StripeError(f"{where}: thickness {t[i] * 1e6:.3g} µm at {x[i]:.4g} m, below "
                          f"zero beyond the noise (±{sigma * 1e6:.2g} µm): subtract the bare "
                          "panel's reading and measure again")
    ends = max(NOISE_SIGMAS * sigma, END_SHARE * peak)
    for side, value, at in (("left", t[:3].mean(), x[0]), ("right", t[-3:].mean(), x[-1])):
        if value > ends:
            raise StripeError(f"{where}: the film is still {value / peak:.0%} of its peak at "
                              f"the {side} end ({at:.4g} m): the scan is narrower than the "
                              "pattern; measure wider, from bare panel to bare panel")
    above = int(np.count_nonzero(t > 0.5 * peak))
    if above < MIN_ACROSS:
        raise StripeError(f"{where}: only {above} points above half the peak: measure at a "
                          f"finer step (at least {MIN_ACROSS} across the spot's middle)")
    w = np.clip(t, 0.0, None)
    area = float(np.trapezoid(w, x))
    eta = float(np.trapezoid(t, x)) * s.speed / (solids * s.flow)
    if not EFFICIENCY_MIN <= eta <= EFFICIENCY_MAX:
        said = ("more paint than was sprayed" if eta > 1 else "almost none of the paint")
        raise StripeError(f"{where}: the stripe holds {said} (transfer efficiency "
                          f"∫T dx·v/(solids·flow) = {eta:.3g}): check flow [m³/s of liquid "
                          "paint], speed [m/s] and solids")
    c = float(np.trapezoid(w * x, x)) / area
    return c, float(np.trapezoid(w * (x - c) ** 2, x)) / area


def reference_standoff(stripes: StripeSet) -> float:
    """The file's ``standoff``, else the most common stripe standoff (a tie: the nearest)."""
    if stripes.standoff is not None:
        return stripes.standoff
    counts = Counter(s.standoff for s in stripes.stripes)
    return min(counts, key=lambda h: (-counts[h], h))


def fit_stripes(stripes: StripeSet, options: CalibrateOptions | None = None) -> CalibrationFit:
    """Fit every spot model the stripes identify and choose one (module docstring).

    Parameters
    ----------
    stripes : pollard_pin.io.stripes.StripeSet
        The measured stripes (:func:`pollard_pin.io.stripes.read_stripes`).
    options : CalibrateOptions or None, optional
        The model, the spread law, the transfer efficiency (default: all fitted).

    Returns
    -------
    CalibrationFit

    Raises
    ------
    StripeError
        A stripe a fit cannot use, or a model or spread law asked for that the stripes do
        not identify (one line: what to measure).
    SolveError
        No model fits.
    """
    instance(stripes, "stripes", StripeSet, "a StripeSet (pollard_pin.io.stripes)")
    options = CalibrateOptions() if options is None else instance(
        options, "options", CalibrateOptions, "CalibrateOptions")
    moments = [check_stripe(s, stripes.solids) for s in stripes.stripes]
    data = stripe_data(stripes)
    h0 = reference_standoff(stripes)
    standoffs = sorted({s.standoff for s in stripes.stripes})
    if not standoffs[0] / EXTRAPOLATE <= h0 <= standoffs[-1] * EXTRAPOLATE:
        # the spread law extrapolated that far (below the apex: a spot of negative size)
        raise StripeError(f"{stripes.source}: standoff = {h0:g} m, beyond the stripes' "
                          f"{standoffs[0]:g}-{standoffs[-1]:g} m by over ×{EXTRAPOLATE:g}: "
                          "measure stripes near it, or give one between")
    notes = []
    if options.spread == "fit" and len(standoffs) < 2:
        raise StripeError(f"{stripes.source}: a spread law needs stripes at two standoffs "
                          f"or more (all are at {standoffs[0]:g} m): measure one farther or "
                          "nearer")
    fit_apex = options.spread == "fit" or (options.spread == "auto" and len(standoffs) > 1)
    if not fit_apex:
        notes.append(f"spread law not fitted ({'one standoff' if len(standoffs) < 2 else 'cone'}"
                     "): apex 0, the spot grows in proportion to the standoff")
    directions = {s.direction for s in stripes.stripes}
    skipped = {}
    if len(directions) < 2:
        why = (f"an elliptic spot needs stripes in both directions (all are "
               f"'{next(iter(directions))}'): measure one along and one across the pattern's "
               "long axis")
        if options.model == "elliptic":
            raise StripeError(f"{stripes.source}: {why}")
        skipped["elliptic"] = why
    models = MODELS if options.model == "auto" else (options.model,)
    var: dict = {}
    for s, (_, v) in zip(stripes.stripes, moments):
        scale = s.standoff / h0  # the start: a cone from the nozzle
        var.setdefault(s.direction, []).append(v / scale ** 2)
    spread = {k: math.sqrt(float(np.mean(v))) for k, v in var.items()}
    if len(spread) == 2 and spread["along"] > SWAPPED * spread["across"]:
        raise StripeError(f"{stripes.source}: the 'along' stripes are wider than the 'across' "
                          f"ones ({spread['along'] * 1e3:.3g} against "
                          f"{spread['across'] * 1e3:.3g} mm σ at {h0:g} m): a stroke along "
                          "the long axis shows the short size; directions swapped?")
    eta0 = float(np.mean([np.trapezoid(d.t, d.x) / d.amount for d in data]))
    given = options.efficiency
    if given is not None and not 1 / GIVEN_AGREES <= given / eta0 <= GIVEN_AGREES:
        # the spot integrates to 1: a stripe's film holds η φ q / v whatever its shape
        raise StripeError(f"{stripes.source}: efficiency {given:.4g} given, but the stripes "
                          f"hold {eta0:.3g} of the paint sprayed: check flows, speeds and "
                          "solids, or let the fit find it")
    fits = tuple(fit_model(m, data, h0, [c for c, _ in moments], spread, fit_apex=fit_apex,
                           efficiency=options.efficiency, efficiency0=eta0)
                 for m in models if m not in skipped and m in SPOTS)
    usable = [f for f in fits if f.usable]
    if not usable:
        whys = "; ".join(f"{f.name}: {f.why}" for f in fits)
        if len(whys) > 150:  # one line: the first model's reason (calibration.json: none)
            whys = f"{fits[0].name}: {fits[0].why}; nor {' or '.join(f.name for f in fits[1:])}"
        raise SolveError(f"no spot model fits the stripes: {whys}")
    chosen = min(usable, key=lambda f: getattr(f, CRITERION))
    notes += [f"{name} not tried: {why}" for name, why in skipped.items()]
    if chosen.efficiency > 1.0:
        notes.append(f"transfer efficiency fitted at {chosen.efficiency:.3f}, over 1: more paint "
                     "on the panels than sprayed; check the flows, speeds and solids")
    if chosen.rms_share > POOR_FIT:
        notes.append(f"the {chosen.name} spot leaves a residual of {chosen.rms_share:.1%} of "
                     "the peak: no model describes these stripes well (a pattern with two "
                     "peaks, a fan with horns?); look at fits.png")
    counts = Counter(s.flow for s in stripes.stripes)
    flow = max(counts, key=lambda q: (counts[q], -q))
    return CalibrationFit(stripes=stripes, standoff=h0, flow=flow, fits=fits, skipped=skipped,
                          chosen=chosen.name, spread="fitted" if fit_apex else "cone",
                          notes=tuple(notes))


__all__ = ["CRITERION", "MODELS", "CalibrateOptions", "CalibrationFit", "check_stripe",
           "fit_stripes", "noise", "reference_standoff", "stripe_data"]
