"""The job's ``[gun]`` table: its spray model and that model's keys (docs/model.md §20).

``model = "gaussian"`` (the default) takes ``sigma``; ``"elliptic"`` takes ``sigma_long`` and
``sigma_short``; ``"beta"`` takes ``radius`` and ``beta``; any model takes ``apex``, the spray
cone's apex in front of the nozzle [m]. A job's ``sigma`` is the spot's width
(:attr:`.spray.spots.Spot.width`), its ``spot`` None for the round Gaussian, so a job
without ``model`` reads, plans and writes as it always did.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import fields
from typing import Any

from ..model.params import did_you_mean
from ..model.values import fail, number
from .errors import JobError
from .spray.spots import SPOTS, RoundGaussian, Spot

# Every model's keys, in the order of its class's parameters; SPOT_KEYS: model, then
# sigma, then the other models' keys, then apex.
MODEL_KEYS = {name: tuple(f.name for f in fields(cls)) for name, cls in SPOTS.items()}
SPOT_KEYS = ("model", *dict.fromkeys(k for ks in MODEL_KEYS.values() for k in ks), "apex")
MAX_BETA = 1000.0  # beyond, the β spot is a Gaussian of σ = R/√(2(β + 1)) to < 0.1 %
# sigma_long/sigma_short at most: the path steps σ_long/4 (the width), and a horizontal
# stroke crosses the short axis, whose trapezoid error 2·exp(−2π²(σ_short/step)²) is 6e-6 at
# 5:1 (1.4e-2 at 8:1; docs/model.md §20)
MAX_ELONGATION = 5.0
# The apex at most this share of the standoff in front of the nozzle: nearer the surface the
# spot's size, ∝ (h − apex), would change tenfold over a tenth of the way (a standoff error of
# a tenth of a millimetre a visible film error); the calibration fits it within the same bound.
MAX_APEX = 0.9
# The spot's width at most this share of its flight (standoff − apex): a spray spreads its 1σ
# by well under 45° (a wide fan's ~35°); beyond, a size given in mm (10 for 0.010 m).
MAX_SPREAD = 1.0


def spot_model(source: str, gun: Mapping) -> str:
    """The ``[gun]`` table's model name, checked (default ``"gaussian"``)."""
    model = gun.get("model", "gaussian")
    if not (isinstance(model, str) and model in SPOTS):
        fail(JobError, f"{source}: ", "gun.model", model,
             f"must be {', '.join(repr(k) for k in SPOTS)}"
             f"{did_you_mean(str(model), tuple(SPOTS))}")
    return model


def required_gun_keys(source: str, gun: Mapping) -> tuple[str, ...]:
    """The ``[gun]`` keys the table's model needs: standoff, the model's, flow."""
    return ("standoff",) + MODEL_KEYS[spot_model(source, gun)] + ("flow",)


def spot_values(source: str, gun: Mapping, standoff: float, limit: float) -> dict:
    """The job's ``sigma`` (the spot's width), ``spot`` (None: the round Gaussian of
    ``sigma``) and ``apex`` (None: 0) from a ``[gun]`` table whose keys are known and whose
    model's keys are present; one :class:`JobError` line per broken rule (another model's
    key, a size that is not a positive length below ``limit`` [m], β outside (1, MAX_BETA],
    sigma_short above sigma_long or below 1/MAX_ELONGATION of it, the apex beyond MAX_APEX of
    the standoff, a width beyond MAX_SPREAD of the spray's flight)."""
    model = spot_model(source, gun)
    for k in gun:
        if k in SPOT_KEYS[1:-1] and k not in MODEL_KEYS[model]:
            fail(JobError, f"{source}: ", f"gun.{k}", gun[k],
                 f"is not a key of model {model!r}, which takes "
                 f"{', '.join(MODEL_KEYS[model])} (set gun.model for another spray pattern)")
    p = {}
    for k in MODEL_KEYS[model]:
        if k == "beta":
            p[k] = number(gun[k], "gun.beta", JobError, f"{source}: ")
            if not 1.0 < p[k] <= MAX_BETA:
                fail(JobError, f"{source}: ", "gun.beta", gun[k],
                     f"must be > 1 and at most {MAX_BETA:g} (1: a flat disc whose rim steps; "
                     "below, a rim of infinite density)")
        else:
            p[k] = number(gun[k], f"gun.{k}", JobError, f"{source}: ", positive=True,
                          limit=limit, limit_rule=f"must be at most {limit:g} m in size "
                                                  "(SI units: metres, not mm)")
    if model == "elliptic" and p["sigma_short"] > p["sigma_long"]:
        fail(JobError, f"{source}: ", "gun.sigma_short", gun["sigma_short"],
             f"must not exceed gun.sigma_long ({p['sigma_long']:g} m): the long axis is the "
             "gun's z axis, across horizontal passes")
    if model == "elliptic" and p["sigma_long"] > MAX_ELONGATION * p["sigma_short"]:
        fail(JobError, f"{source}: ", "gun.sigma_short", gun["sigma_short"],
             f"must be at least 1/{MAX_ELONGATION:g} of gun.sigma_long ({p['sigma_long']:g} "
             "m): the path's steps, a quarter of the long axis, would not resolve the short")
    spot = SPOTS[model].from_params(**p)
    values: dict[str, Any] = {"sigma": spot.width,
                              "spot": None if model == "gaussian" else spot}
    if "apex" in gun:
        apex = number(gun["apex"], "gun.apex", JobError, f"{source}: ", limit=limit,
                      limit_rule=f"must be at most {limit:g} m from the nozzle")
        if not apex <= MAX_APEX * standoff:
            fail(JobError, f"{source}: ", "gun.apex", gun["apex"],
                 f"must lie before the standoff ({standoff:g} m), at most {MAX_APEX:g} of it: "
                 "the spray cone's apex, in front of the nozzle (negative: behind it)")
        values["apex"] = apex
    throw = standoff - values.get("apex", 0.0)  # the spray's flight from its apex to the spot
    if spot.width > MAX_SPREAD * throw:
        k = MODEL_KEYS[model][0]
        fail(JobError, f"{source}: ", f"gun.{k}", gun[k],
             f"makes a spot {spot.width:.4g} m wide, wider than the {throw:.4g} m it flies to "
             "the standoff (over 45° at 1σ; SI units: metres, not mm)")
    return values


def job_spot(job) -> Spot:
    """The job's spot: its ``spot``, or the round Gaussian of its ``sigma``."""
    return job.spot if job.spot is not None else RoundGaussian(job.sigma)


def spot_keys(spot: Spot | None, sigma: float | None = None,
              apex: float | None = None) -> dict:
    """The ``[gun]`` keys that say a spot: ``sigma`` alone for the round Gaussian (``spot``
    None or a :class:`.spray.spots.RoundGaussian`), else ``model`` and the model's keys; then
    ``apex`` unless None. What a job writes back and a calibration's ``gun.toml`` holds.

    Parameters
    ----------
    spot : pollard_pin.painting.spray.Spot or None
        The spot (None: the round Gaussian of ``sigma``).
    sigma : float or None, optional
        The round Gaussian's σ [m] when ``spot`` is None.
    apex : float or None, optional
        The spray cone's apex in front of the nozzle [m] (None: left out, 0).

    Returns
    -------
    dict
        {key: value} in the file's order.
    """
    if spot is None or type(spot) is RoundGaussian:
        out = {"sigma": sigma if spot is None else spot.sigma}
    else:
        out = {"model": spot.name, **spot.params()}
    return out if apex is None else {**out, "apex": apex}


def check_spot(job, limit: float) -> None:
    """A job's ``spot``, ``sigma`` and ``apex`` held to the ``[gun]`` table's rules (a job
    built in Python; a file's job passes by :func:`spot_values` already): its spot None or a
    :class:`.spray.spots.Spot` within the model's bounds, its sigma None or the spot's width
    (None: set to it), its apex before the standoff; one :class:`JobError` line. A round
    Gaussian spot becomes None (the job the file of its ``sigma`` reads)."""
    spot, source = job.spot, job.source
    if spot is None and job.apex is None:
        return
    if spot is not None and not isinstance(spot, Spot):
        fail(JobError, f"{source}: ", "spot", spot, "must be a spray spot (RoundGaussian, "
             "EllipticGaussian, BetaSpot of pollard_pin.painting.spray) or None")
    sigma = job.sigma if spot is None or job.sigma is not None else spot.width
    standoff = job.standoff if isinstance(job.standoff, int | float) else math.inf
    values = spot_values(source, spot_keys(spot, sigma, job.apex), standoff, limit)
    if spot is not None and sigma != values["sigma"]:
        fail(JobError, f"{source}: ", "sigma", sigma,
             f"is not the {spot.name} spot's width {values['sigma']!r} m (a job's sigma is "
             "its spot's width, Spot.width: give sigma=None with a spot)")
    object.__setattr__(job, "sigma", sigma)
    object.__setattr__(job, "spot", values["spot"])


def gun_table(job, d: Mapping, keys: tuple[str, ...]) -> dict:
    """The job's ``[gun]`` table as the file says it, from ``d`` (the job's entries, None
    left out): standoff, the model and its keys (only ``sigma`` for the round Gaussian),
    apex, flow, then the table's other ``keys`` present in ``d``."""
    out = {"standoff": d["standoff"], **spot_keys(job.spot, d["sigma"], job.apex)}
    out["flow"] = d["flow"]
    out.update({k: d[k] for k in keys if k in d and k not in out
                and k not in SPOT_KEYS + ("sigma",)})
    return out


__all__ = ["MAX_APEX", "MAX_BETA", "MAX_ELONGATION", "MAX_SPREAD", "MODEL_KEYS", "SPOT_KEYS",
           "check_spot", "gun_table", "job_spot", "required_gun_keys", "spot_keys", "spot_model",
           "spot_values"]
