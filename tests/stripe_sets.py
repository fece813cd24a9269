"""Measured stripes made from a known spray pattern, for the calibration's tests: the exact
stripe of the spot at each standoff (its cone from ``apex``), plus white measurement noise,
each stripe a few mm off its scan's centre (docs/model.md §30)."""
import numpy as np

from pollard_pin.io.stripes import Stripe, StripeSet

STANDOFF, APEX, EFFICIENCY, SOLIDS, FLOW = 0.20, 0.02, 0.60, 0.45, 1.5e-6
NOISE = 0.2e-6  # m


def make_stripes(spot, seed=0, standoffs=(0.15, 0.25), speeds=(0.4, 0.8),
                 directions=("across", "along"), noise=NOISE, apex=APEX, step=1e-3,
                 half=0.15, reference=STANDOFF) -> StripeSet:
    """The stripes ``spot`` (at ``reference``) paints at each standoff, speed and direction,
    measured every ``step`` over ±``half`` with ``noise`` (1 σ)."""
    rng = np.random.default_rng(seed)
    x = np.arange(-half, half + step / 2, step)
    out = []
    for h in standoffs:
        for v in speeds:
            for d in directions:
                s = float(spot.scale(h, reference, apex))
                c = rng.uniform(-3e-3, 3e-3)
                t = EFFICIENCY * SOLIDS * FLOW / v * spot.stripe((x - c) / s, d) / s
                out.append(Stripe(x, t + rng.normal(0.0, noise, x.shape), h, v, FLOW, d,
                                  source=f"h{h} v{v} {d}"))
    return StripeSet(tuple(out), SOLIDS, reference)
