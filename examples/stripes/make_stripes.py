"""Make the example stripes: what a paint lab measures to calibrate a spray gun.

    .venv/bin/python examples/stripes/make_stripes.py [--out-dir examples/stripes]

A known elliptic spray pattern (TRUTH below: σ_long 30 mm and σ_short 12 mm at 200 mm, its
cone's apex 20 mm in front of the nozzle) paints eight straight stripes on flat panels: at
standoffs 150 and 250 mm, gun speeds 0.4 and 0.8 m/s, strokes along and across the pattern's
long axis. Each stripe's dried film is "measured" every millimetre across it, with a
profilometer's noise (0.2 µm, white) and its resolution (0.01 µm), the stripe a few mm off
the scan's centre. Writes ``stripes.toml`` and one CSV per stripe (``position``,
``thickness`` [m]); then ``pollard-pin calibrate --stripes examples/stripes/stripes.toml``
should give back TRUTH within its standard errors (docs/model.md §30).
"""
import argparse
from pathlib import Path

import numpy as np

from pollard_pin.painting.spray import EllipticGaussian

TRUTH = {"sigma_long": 0.030, "sigma_short": 0.012, "standoff": 0.20, "apex": 0.02,
         "efficiency": 0.60}
SOLIDS = 0.45  # volume solids of the paint
FLOW = 1.5e-6  # m³/s of liquid paint (90 ml/min)
STANDOFFS = (0.15, 0.25)  # m
SPEEDS = (0.4, 0.8)  # m/s
NOISE = 0.2e-6  # m, the profilometer's noise (1 σ)
RESOLUTION = 1e-8  # m, its reading's last digit
SEED = 20261206


def stripes(rng):
    """(file name, standoff, speed, direction, positions, thickness) of every stripe."""
    spot = EllipticGaussian(TRUTH["sigma_long"], TRUTH["sigma_short"])
    x = np.round(np.arange(-150, 151) * 1e-3, 6)  # every mm over 300 mm
    for h in STANDOFFS:
        for v in SPEEDS:
            for d in ("across", "along"):
                s = float(spot.scale(h, TRUTH["standoff"], TRUTH["apex"]))
                centre = rng.uniform(-3e-3, 3e-3)
                film = (TRUTH["efficiency"] * SOLIDS * FLOW / v
                        * spot.stripe((x - centre) / s, d) / s)
                measured = np.round((film + rng.normal(0.0, NOISE, x.shape)) / RESOLUTION)
                yield (f"h{h * 1e3:.0f}_v{v * 10:.0f}_{d}.csv", h, v, d, x,
                       measured * RESOLUTION)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", type=Path, default=Path(__file__).resolve().parent)
    args = ap.parse_args(argv)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    toml = ["# Eight measured stripes of one spray gun (examples/stripes/make_stripes.py made",
            "# them from a known elliptic pattern: sigma_long 30 mm, sigma_short 12 mm at",
            "# 200 mm, apex 20 mm, transfer efficiency 0.60). pollard-pin calibrate --stripes",
            "# examples/stripes/stripes.toml --out DIR fits the pattern back.",
            "solids = 0.45          # volume share of the liquid paint that stays (dry film)",
            "standoff = 0.20        # m: the reference standoff of the gun.toml written"]
    for name, h, v, d, x, t in stripes(np.random.default_rng(SEED)):
        rows = "".join(f"{p:.3f},{f:.4e}\n" for p, f in zip(x, t))
        (args.out_dir / name).write_text("position,thickness\n" + rows)
        toml += ["", "[[stripe]]", f'file = "{name}"',
                 f"standoff = {h}          # m, nozzle to panel",
                 f"speed = {v}             # m/s",
                 f"flow = {FLOW}          # m³/s of liquid paint",
                 f'direction = "{d}"    # the stroke against the pattern\'s long axis']
    (args.out_dir / "stripes.toml").write_text("\n".join(toml) + "\n")
    print(f"wrote {args.out_dir}/stripes.toml and 8 stripes")


if __name__ == "__main__":
    main()
