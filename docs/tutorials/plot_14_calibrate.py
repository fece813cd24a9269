"""
Calibrating the spray from measured stripes
===========================================

A paint engineer does not know the spray spot's σ: she paints stripes and measures them. Each
stripe is one straight stroke of the gun over a flat test panel at a fixed standoff and speed;
the dried film is measured across it. :func:`pollard_pin.calibrate` fits every spot model to
the stripes, chooses one by the Bayesian information criterion and writes the ``[gun]`` table
a paint job takes (docs/model.md §30). The command line does the same with
``pollard-pin calibrate --stripes stripes.toml --out DIR``.
"""

# %%
# The stripes
# -----------
# ``examples/stripes/`` holds eight stripes that ``make_stripes.py`` made from a known
# elliptic pattern (σ_long 30 mm and σ_short 12 mm at 200 mm, its cone's apex 20 mm in
# front of the nozzle, 60 % of the paint landing) with a profilometer's noise: two standoffs,
# two speeds, strokes along and across the pattern's long axis. ``stripes.toml`` lists them
# with the paint's volume solids (the thickness is dry film).
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp

here = Path.cwd().resolve()
stripes = next(p / "examples" / "stripes" / "stripes.toml" for p in (here, *here.parents)
               if (p / "examples" / "stripes" / "stripes.toml").is_file())
print(stripes.read_text().split("[[stripe]]")[0])

# %%
# Fit and choose
# --------------
# Every model the stripes identify is fitted by least squares: its sizes at the reference
# standoff, the spread law's apex (two standoffs), the transfer efficiency and each stripe's
# centre, with standard errors from the Jacobian. The elliptic spot fits to the noise; the
# round ones cannot be narrow one way and wide the other.
cal = pp.calibrate(stripes)
print("\n".join(cal.summary_lines()))
for f in cal.fit.fits:
    state = f"BIC {f.bic:.0f}, residual {f.rms_share:.2%}" if f.usable else f.why
    print(f"{f.name:9s} {state}")

# %%
# Each stripe against its fit
# ---------------------------
# What ``fits.png`` shows (:func:`pollard_pin.viz.calibration.fits_figure`): the measured
# film and the chosen model's, stripe by stripe, against the position from the fitted centre.
best = cal.fit.best
fig, axes = plt.subplots(2, 4, figsize=(12, 5), constrained_layout=True)
for ax, d, s, c in zip(axes.flat, cal.fit.data(), cal.fit.stripes.stripes, best.offsets):
    ax.plot((d.x - c) * 1e3, d.t * 1e6, ".", ms=2, color="0.4")
    ax.plot((d.x - c) * 1e3, best.thickness(d, d.x, c) * 1e6, color="C3")
    ax.set_title(f"{s.standoff * 1e3:.0f} mm, {s.speed} m/s, {s.direction}", fontsize=8)
fig.supxlabel("position − centre [mm]")
fig.supylabel("dry film [µm]")

# %%
# The gun
# -------
# ``cal.gun`` is a :class:`pollard_pin.painting.spray.Gun`; ``write`` puts its ``[gun]`` table
# in ``gun.toml``, beside ``calibration.json`` (every model tried) and ``fits.png``.
import tempfile  # noqa: E402

out = Path(tempfile.mkdtemp()) / "calibration"
cal.write(out)
print((out / "gun.toml").read_text())

# %%
# Any job takes it as it is
# -------------------------
# The ``[gun]`` table goes into a paint job unchanged (its ``[paint]`` table may take the
# solids and the efficiency, for the litres paint.json reports).
import tomllib  # noqa: E402

gun = tomllib.loads((out / "gun.toml").read_text())["gun"]
job = pp.job_from_dict({"panel": {"center": [0.75, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
                                  "width": 0.16, "height": 0.08},
                        "gun": gun, "job": {"thickness": 25e-6}})
print(job.spot, f"apex {job.apex * 1e3:.1f} mm")

# %%
# Against the pattern the stripes came from
# -----------------------------------------
# The stripe a stroke at 0.5 m/s leaves at 0.25 m, across the long axis: the calibrated gun
# (its spread law carries the sizes from 0.20 m) against the pattern ``make_stripes.py``
# painted with.
from pollard_pin.painting.spray import EllipticGaussian  # noqa: E402

h, v = 0.25, 0.5
x = np.linspace(-0.12, 0.12, 481)
g = cal.gun
fitted = g.flow / v * g.spot.stripe_at(x, h, g.standoff, g.apex, "across")
true = EllipticGaussian(0.030, 0.012)
made = 0.60 * 0.45 * 1.5e-6 / v * true.stripe_at(x, h, 0.20, 0.02, "across")
fig2, ax = plt.subplots(figsize=(6, 3))
ax.plot(x * 1e3, made * 1e6, label="the pattern the stripes were made from")
ax.plot(x * 1e3, fitted * 1e6, "--", label="calibrated")
ax.set_xlabel("across the stroke [mm]")
ax.set_ylabel("dry film [µm]")
ax.legend(fontsize=8)
print(f"largest difference {np.abs(fitted - made).max() / made.max():.3%} of the peak")
