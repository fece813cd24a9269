"""One film statistics for every film: a panel's grid, a part's film points, on a line or
still (paint.json's ``thickness``, docs/model.md §21, §23), and the check of that film against
the acceptance (paint.json's ``film_check``)."""
from __future__ import annotations

import math

import numpy as np

# The acceptance of a film: at least this share of the (painted) area within ±ACCEPTANCE_BAND
# of the target. A paint shop's usual tolerance; every example meets it (the ribbed plate,
# whose rib feet the gun half paints, with 99.19 %).
ACCEPTANCE_SHARE = 0.99
ACCEPTANCE_BAND = 0.10


def film_stats(thickness, target: float, areas=None) -> dict:
    """``mean, min, max, std`` [m], ``uniformity`` (min/max), the shares within ±5 % and
    ±10 % of ``target`` and the deviations of min and max from it. ``areas``: each point's
    share of the surface (a part's film points), the weights of mean, std and shares; None:
    the points weigh alike (a panel's regular grid)."""
    th = np.asarray(thickness, dtype=float).ravel()
    dev = np.abs(th / target - 1)
    if areas is None:
        mean, std = float(th.mean()), float(th.std())

        def share(band: float) -> float:
            return float(np.mean(dev <= band))
    else:
        w = np.asarray(areas, dtype=float).ravel()
        w = w / w.sum()
        mean = float(w @ th)
        std = float(math.sqrt(max(w @ (th - mean) ** 2, 0.0)))

        def share(band: float) -> float:
            return min(1.0, float(w[dev <= band].sum()))  # round-off may pass 1
    return {"mean": mean, "min": float(th.min()), "max": float(th.max()), "std": std,
            "uniformity": float(th.min() / th.max()), "within_5pct": share(0.05),
            "within_10pct": share(0.10), "deviation_min": float(th.min() / target - 1),
            "deviation_max": float(th.max() / target - 1)}


def film_check(stats: dict, target: float, share: float = ACCEPTANCE_SHARE) -> dict:
    """paint.json's ``film_check`` of ``stats`` (:func:`film_stats` of a film for ``target``):
    the shares of the area outside ±5 % and ±10 % of the target, the least and largest film
    over the target, and whether at least ``share`` of the area lies within
    ±ACCEPTANCE_BAND (``meets``)."""
    return {"outside_5pct": 1.0 - stats["within_5pct"],
            "outside_10pct": 1.0 - stats["within_10pct"],
            "min_relative": stats["min"] / target, "max_relative": stats["max"] / target,
            "acceptance": {"band": ACCEPTANCE_BAND, "min_share": share},
            "meets": bool(stats["within_10pct"] >= share)}


def misses(check: dict, share: float | None = None) -> bool:
    """Whether the film of ``check`` (:func:`film_check`) has less than ``share`` of its
    area within ±10 % of the target (None: the check's own acceptance, its ``meets``)."""
    if share is None:
        return not check["meets"]
    return 1.0 - check["outside_10pct"] < share


__all__ = ["ACCEPTANCE_BAND", "ACCEPTANCE_SHARE", "film_check", "film_stats", "misses"]
