"""The paint itself: a job's ``[paint]`` table (docs/model.md §29), read and checked once.

The film target is a dry film; ``solids`` (volume solids) is the share of the wet film that
stays, so the wet film is dry / solids. ``density`` is the liquid paint's [kg/m³]. The gun's
``flow`` is the dry film volume a large plane in front of it receives per second (§20), so the
liquid paint the gun sprays per second is flow / (solids · transfer_efficiency); without a
transfer efficiency only the geometric overspray (the spray that misses the part) is counted.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..model.params import did_you_mean
from ..model.values import fail, number
from .errors import JobError

REQUIRED = ("solids", "density")
OPTIONAL = ("transfer_efficiency",)
# Liquid paints weigh ~800 (solvent-borne clear) to ~2000 kg/m³ (zinc-rich primer): outside
# these bounds a value is a unit slip (1.2 meant as g/cm³, 1.2e6 as g/m³).
MIN_DENSITY = 300.0
MAX_DENSITY = 5000.0
# The least share (solids, transfer efficiency): a thinned clear coat has ~15 % solids, an air
# gun ~20 % efficiency; below 5 %, a slip (0.0045 for 0.45) that would print litres by the
# thousand.
MIN_SHARE = 0.05


@dataclass(frozen=True)
class Paint:
    """A job's paint (``[paint]``, SI units; docs/model.md §29).

    Attributes
    ----------
    solids : float
        Volume solids: the share of the wet film that stays dry, in (0, 1].
    density : float
        The liquid paint's density [kg/m³].
    transfer_efficiency : float or None
        The share of the liquid sprayed that reaches a surface large enough to catch the whole
        spot (bounce, wrap and mist lost), in (0, 1]; None: 1, only the geometric overspray
        counted.
    """

    solids: float
    density: float
    transfer_efficiency: float | None = None

    @property
    def efficiency(self) -> float:
        """The transfer efficiency used (1 when the table gives none)."""
        return 1.0 if self.transfer_efficiency is None else self.transfer_efficiency

    def to_dict(self) -> dict:
        """The table as the job file says it (``transfer_efficiency`` left out when None)."""
        out = {"solids": self.solids, "density": self.density}
        if self.transfer_efficiency is not None:
            out["transfer_efficiency"] = self.transfer_efficiency
        return out


def _share(source: str, key: str, value: Any) -> float:
    """A share in [MIN_SHARE, 1]; a value from 100·MIN_SHARE up is said not to be a per cent."""
    v = number(value, key, JobError, f"{source}: ", positive=True)
    if v > 1:
        hint = ("" if v < 100 * MIN_SHARE else ", not a per cent" if v > 100 else
                f", not a per cent ({v:g} % is {v / 100:g})")
        fail(JobError, f"{source}: ", key, value, f"must be a share in (0, 1]{hint}")
    if v < MIN_SHARE:
        fail(JobError, f"{source}: ", key, value, f"must be at least {MIN_SHARE:g} (no paint "
                                                  f"or gun has less than {100 * MIN_SHARE:g} %)")
    return v


def paint_from_table(source: str, table: Any) -> Paint:
    """The job's ``[paint]`` table checked: one :class:`JobError` line naming ``source``, the
    key and the rule for a missing or unknown key, a share outside [MIN_SHARE, 1] (a per cent)
    or a density outside MIN_DENSITY..MAX_DENSITY kg/m³ (g/cm³).

    Parameters
    ----------
    source : str
        What the messages call the job (its file).
    table : Mapping
        ``solids``, ``density`` [kg/m³] and optionally ``transfer_efficiency``.

    Returns
    -------
    Paint
        The checked paint.

    Examples
    --------
    >>> from pollard_pin.painting.material import paint_from_table
    >>> paint_from_table("job.toml", {"solids": 0.45, "density": 1300.0})
    Paint(solids=0.45, density=1300.0, transfer_efficiency=None)
    """
    if not isinstance(table, Mapping):
        fail(JobError, f"{source}: ", "paint", table, "must be a table [paint] (solids, "
                                                      "density)")
    allowed = REQUIRED + OPTIONAL
    for k in table:
        if k not in allowed:
            fail(JobError, f"{source}: ", f"paint.{k}", table[k],
                 f"unknown key{did_you_mean(k, allowed)}; [paint] takes {', '.join(allowed)}")
    for k in REQUIRED:
        if k not in table:
            raise JobError(f"{source}: 'paint.{k}' is missing ([paint] needs "
                           f"{', '.join(REQUIRED)}; optional {', '.join(OPTIONAL)})")
    solids = _share(source, "paint.solids", table["solids"])
    density = number(table["density"], "paint.density", JobError, f"{source}: ",
                     positive=True)
    if not MIN_DENSITY <= density <= MAX_DENSITY:
        fail(JobError, f"{source}: ", "paint.density", table["density"],
             f"must be within {MIN_DENSITY:g}..{MAX_DENSITY:g} kg/m³ (a liquid paint's; "
             "1.2 g/cm³ is 1200 kg/m³)")
    te = table.get("transfer_efficiency")
    if te is not None:
        te = _share(source, "paint.transfer_efficiency", te)
    return Paint(solids, density, te)


def check_paint(job) -> None:
    """A job's ``paint`` held to the ``[paint]`` table's rules (a job built in Python; a file's
    passes by :func:`paint_from_table` already): None or a :class:`Paint` whose values the
    table would take; one :class:`JobError` line naming the job's source."""
    paint = job.paint
    if paint is None:
        return
    if not isinstance(paint, Paint):
        fail(JobError, f"{job.source}: ", "paint", paint, "must be a Paint (solids, density, "
             "transfer_efficiency; pollard_pin.painting.material) or None")
    paint_from_table(job.source, paint.to_dict())


__all__ = ["MAX_DENSITY", "MIN_DENSITY", "MIN_SHARE", "Paint", "check_paint", "paint_from_table"]
