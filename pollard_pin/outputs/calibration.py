"""The spray calibration that writes itself (``pollard-pin calibrate``, docs/model.md §30):
:func:`calibrate` is ``pollard_pin.calibrate``, :class:`Calibration` its result with
:meth:`Calibration.write`: ``gun.toml`` (a ``[gun]`` table any job takes as it is),
``calibration.json`` (every model tried) and ``fits.png`` (each stripe against its fit)."""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

from ..checks import file_path, shorten
from ..errors import InputError
from ..io.atomic import all_or_nothing, atomic_open, check_outputs, make_folder
from ..io.job_file import toml_value
from ..io.json_text import finite_json
from ..io.stripes import StripeSet, read_stripes
from ..painting.gun_table import spot_keys
from ..painting.spray.calibrate import CRITERION, CalibrateOptions, CalibrationFit, fit_stripes
from ..painting.spray.deposition import Gun
from ..viz.calibration import write_fits_png

FILES = ("gun.toml", "calibration.json", "fits.png")


@dataclass(frozen=True)
class Calibration:
    """What :func:`calibrate` returns: the fit of every spot model, the one chosen, the gun
    it makes and :meth:`write`.

    Attributes
    ----------
    fit : pollard_pin.painting.spray.calibrate.CalibrationFit
        The stripes, every model's fit, the chosen one.
    """

    fit: CalibrationFit

    @property
    def gun(self) -> Gun:
        """The calibrated gun (:meth:`CalibrationFit.gun`): the chosen spot at the reference
        standoff, its apex and the dry film flow it deposits."""
        return self.fit.gun()

    def gun_table(self) -> dict:
        """The ``[gun]`` table of gun.toml: standoff, model, the model's sizes, apex, flow
        (the keys of a job's ``[gun]``, docs/formats.md)."""
        best = self.fit.best
        return {"standoff": self.fit.standoff, **spot_keys(best.spot, apex=best.apex + 0.0),
                "flow": self.gun.flow}

    def gun_toml(self) -> str:
        """gun.toml's text: the ``[gun]`` table, with comment lines saying where it comes
        from."""
        fit, best = self.fit, self.fit.best
        eta = (f"{best.efficiency:.4g} ± {best.errors['efficiency']:.2g} (fitted)"
               if "efficiency" in best.errors else f"{best.efficiency:.4g} (given)")
        lines = [f"# pollard-pin calibrate: the {best.name} spot fitted to "
                 f"{len(fit.stripes.stripes)} stripes of {fit.stripes.source} (calibration.json)",
                 f"# flow: the dry film deposited = solids {fit.stripes.solids:.4g} × transfer "
                 f"efficiency {eta} × liquid flow {fit.flow:.4g} m³/s",
                 f"# a job's [paint] table may say: solids = {fit.stripes.solids!r}, "
                 f"transfer_efficiency = {round(best.efficiency, 4)!r}",
                 "", "[gun]"]
        units = {"standoff": "m", "apex": "m (the spray cone's apex in front of the nozzle)",
                 "flow": "m³/s of dry film", "beta": "1"}
        for k, v in self.gun_table().items():
            text = f"{k} = {toml_value(v)}"
            unit = units.get(k, "m" if k != "model" else "")
            lines.append(f"{text:<40} # {unit}" if unit else text)
        return "\n".join(lines) + "\n"

    def to_dict(self) -> dict:
        """calibration.json's content: every model tried (parameters, standard errors, AIC,
        BIC, the residual RMS as a share of the peak, chosen or why not usable)."""
        fit = self.fit
        models = []
        for f in fit.fits:
            models.append({
                "model": f.name, "chosen": f.name == fit.chosen, "usable": f.usable,
                **({"why": f.why} if f.why else {}),
                "params": f.params, "errors": {k: _finite(v) for k, v in f.errors.items()
                                               if k in f.params},
                "apex": f.apex, "apex_error": _finite(f.errors.get("apex")),
                "efficiency": f.efficiency,
                "efficiency_error": _finite(f.errors.get("efficiency")),
                "aic": f.aic, "bic": f.bic, "rms_share": f.rms_share, "points": f.points,
                "parameters": f.k,
                "stripes": [{"offset": o, "offset_error": _finite(e), "rms_share": r}
                            for o, e, r in zip(f.offsets, f.offset_errors, f.stripe_rms)]})
        return {
            "stripes": [{"source": s.source, "standoff": s.standoff, "speed": s.speed,
                         "flow": s.flow, "direction": s.direction, "points": len(s.position)}
                        for s in fit.stripes.stripes],
            "solids": fit.stripes.solids, "reference_standoff": fit.standoff,
            "liquid_flow": fit.flow, "criterion": CRITERION, "spread": fit.spread,
            "chosen": fit.chosen, "models": models, "skipped": dict(fit.skipped),
            "notes": list(fit.notes), "gun": self.gun_table()}

    def summary_lines(self) -> list[str]:
        """What ``calibrate`` prints: the chosen model with its parameters ± standard errors,
        the others' BIC and residual, the gun."""
        fit, best = self.fit, self.fit.best
        sizes = ", ".join(_pm(k, v, best.errors[k], k != "beta")
                          for k, v in best.params.items())
        how = (f"chosen by BIC among {', '.join(f.name for f in fit.fits if f.usable)}"
               if len(fit.fits) > 1 else "(the model asked)")
        lines = [f"{best.name} spot {how}: {sizes} at {fit.standoff * 1e3:.4g} mm"]
        spread = (_pm("apex", best.apex, best.errors["apex"], True) if "apex" in best.errors
                  else "apex 0 mm (not fitted)")
        eta = (f"transfer efficiency {best.efficiency:.4f} ± {best.errors['efficiency']:.2g}"
               if "efficiency" in best.errors else f"transfer efficiency {best.efficiency:.4g}"
               " (given)")
        lines.append(f"{spread}, {eta}; residual RMS {best.rms_share:.2%} of the peak")
        for f in fit.fits:
            if f.name != best.name:
                state = (f"BIC {f.bic - best.bic:+.1f}, residual {f.rms_share:.2%}"
                         if f.usable else f"not usable: {f.why}")
                lines.append(f"  {f.name}: {state}")
        g = self.gun
        lines.append(f"gun: standoff {g.standoff * 1e3:.4g} mm, dry film flow {g.flow:.4g} m³/s")
        return lines

    def write(self, folder: str | Path) -> Path:
        """Write gun.toml, calibration.json and fits.png in ``folder``, every one or none.

        Parameters
        ----------
        folder : str or Path
            The output folder (created).

        Returns
        -------
        Path
            The folder.
        """
        folder = file_path(folder, "folder")
        check_outputs(*(folder / f for f in FILES), folders=(folder,))
        text = self.gun_toml()
        data = finite_json(self.to_dict(), "calibration.json", indent=2, ensure_ascii=False)
        with all_or_nothing():
            make_folder(folder)
            with atomic_open(folder / "gun.toml") as f:
                f.write(text)
            with atomic_open(folder / "calibration.json") as f:
                f.write(data + "\n")
            write_fits_png(folder / "fits.png", self.fit)
        return folder


def _finite(x):
    """A standard error for JSON: null where JᵀJ gave none (an unusable fit's NaN)."""
    return x if x is None or math.isfinite(x) else None


def _pm(key: str, value: float, error: float, length: bool) -> str:
    if length:
        return f"{key} {value * 1e3:.4g} ± {error * 1e3:.2g} mm"
    return f"{key} {value:.4g} ± {error:.2g}"


def calibrate(stripes, options: CalibrateOptions | None = None) -> Calibration:
    """Calibrate the spray pattern from measured stripes (``pollard-pin calibrate``,
    docs/model.md §30): fit every spot model the stripes identify (sizes, the spread law's
    apex, the transfer efficiency, each stripe's centre) by least squares, choose one by BIC.

    Parameters
    ----------
    stripes : str, pathlib.Path or pollard_pin.io.stripes.StripeSet
        A STRIPES.toml (docs/formats.md) or the stripes read.
    options : pollard_pin.painting.spray.calibrate.CalibrateOptions or None, optional
        The model (default: chosen), the spread law, the transfer efficiency.

    Returns
    -------
    Calibration
        ``.gun`` (a :class:`~pollard_pin.painting.spray.Gun`), ``.write(folder)``.

    Raises
    ------
    pollard_pin.io.stripes.StripeError
        A stripe file or value that cannot be used, a model the stripes do not identify
        (one line: what to measure).
    pollard_pin.errors.SolveError
        No model fits the stripes.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> cal = pp.calibrate("examples/stripes/stripes.toml")   # doctest: +SKIP
    >>> cal.fit.chosen, cal.gun.standoff                      # doctest: +SKIP
    ('elliptic', 0.2)
    """
    if not isinstance(stripes, (StripeSet, str, os.PathLike)):
        raise InputError(f"stripes = {shorten(stripes, 40)}: expected a STRIPES.toml's path "
                         "or a StripeSet (pollard_pin.io.stripes)")
    if not isinstance(stripes, StripeSet):
        stripes = read_stripes(stripes)
    return Calibration(fit_stripes(stripes, options))


__all__ = ["FILES", "Calibration", "calibrate"]
