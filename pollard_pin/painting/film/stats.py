"""One film statistics for every film: a panel's grid, a part's film points, on a line or
still (paint.json's ``thickness``, docs/model.md §21, §23)."""
from __future__ import annotations

import math

import numpy as np


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


__all__ = ["film_stats"]
