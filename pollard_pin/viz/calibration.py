"""The calibration figure (``calibrate``'s fits.png): each measured stripe against the film the
fitted spot leaves (docs/model.md §30). It draws what
:func:`pollard_pin.painting.spray.calibrate.fit_stripes` computed; nothing here computes."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np


def fits_figure(fit):
    """One panel per stripe: the measured film (dots), the chosen model's (solid line) and
    every other model's that fits (thin dashed), against the position re-centred on the
    chosen fit's centre. Artist gids: ``measured<i>``, ``<model><i>``.

    Parameters
    ----------
    fit : pollard_pin.painting.spray.calibrate.CalibrationFit
        The calibration.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    data, stripes = fit.data(), fit.stripes.stripes
    best = fit.best
    cols = min(len(data), 4)
    rows = math.ceil(len(data) / cols)
    fig = Figure(figsize=(3.2 * cols + 0.6, 2.6 * rows + 0.8), constrained_layout=True)
    axes = fig.subplots(rows, cols, squeeze=False, sharey=False)
    for i, (d, s) in enumerate(zip(data, stripes)):
        ax = axes.flat[i]
        c = best.offsets[i]
        x = np.linspace(d.x[0], d.x[-1], 600)
        (pts,) = ax.plot((d.x - c) * 1e3, d.t * 1e6, ".", ms=2.5, color="0.35",
                         label="measured")
        pts.set_gid(f"measured{i}")
        for f in fit.fits:
            if not f.usable:
                continue
            chosen = f.name == best.name
            (ln,) = ax.plot((x - c) * 1e3, f.thickness(d, x, f.offsets[i]) * 1e6,
                            "-" if chosen else "--", lw=1.6 if chosen else 0.9,
                            color="C3" if chosen else None, label=f.name, zorder=3 if chosen
                            else 2)
            ln.set_gid(f"{f.name}{i}")
        ax.set_title(f"{s.standoff * 1e3:.0f} mm, {s.speed:.3g} m/s, {s.direction}: "
                     f"RMS {best.stripe_rms[i]:.1%}", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_xlabel("position − centre [mm]", fontsize=8)
        if i % cols == 0:
            ax.set_ylabel("dry film [µm]", fontsize=8)
    for ax in axes.flat[len(data):]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=7, loc="upper right")
    fig.suptitle(f"{fit.stripes.source}: {best.name} chosen (BIC), residual RMS "
                 f"{best.rms_share:.2%} of the peak", fontsize=10)
    return fig


def write_fits_png(path, fit, dpi: int = 100) -> Path:
    """:func:`fits_figure` written to ``path`` as PNG, atomically.

    Parameters
    ----------
    path : str or Path
        The PNG file.
    fit : pollard_pin.painting.spray.calibrate.CalibrationFit
        The calibration.
    dpi : int, optional
        Resolution.

    Returns
    -------
    Path
    """
    from .plots import save_png

    return save_png(fits_figure(fit), path, dpi)


__all__ = ["fits_figure", "write_fits_png"]
