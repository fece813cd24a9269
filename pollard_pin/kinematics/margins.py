"""The singularity margins (docs/model.md §12): their defaults, the numerical floors, and the one
rule that says whether a sample is too close to a singularity, for the IK, the workspace map
and the paint planner alike. Cheap to import (no numpy at import time): the CLI shows the
defaults in ``--help`` without loading numpy or the compiled kernels."""
from __future__ import annotations

from dataclasses import dataclass

from ..checks import real, shorten
from ..errors import InputError

SINGULARITY_MARGIN = 1e-3  # default smallest singular value allowed (parallel and serial)
WRIST_MARGIN = 0.05  # default smallest |sin θ1716| allowed (≈ 2.9°)

# Numerical floors, relative to σ_max of the same matrix; they apply whatever the margins
# (even 0), so an exactly or numerically singular sample is always rejected (docs/model.md §12).
# A solve with condition κ = σ_max/σ_min loses log10 κ digits: SIGMA_FLOOR keeps its relative
# error ≲ κ ε ≈ 2e-6. A serial singularity is a fold of the IK (an arccos at ±1): there the
# positions themselves move by ≈ ε/σ, so rates err by ≈ ε/σ² (measured on a leg's reach
# boundary: 1-ulp pose changes move the joint rates by ≈ 0.6 ε/σ²); the same 2e-6 budget
# needs σ ≥ √SIGMA_FLOOR = 1e-5 there (and for |sin θ1716|, the wrist's own fold).
SIGMA_FLOOR = 1e-10  # parallel map, spherical-joint ZYZ rates, the dynamics' Jc_pᵀ split
SERIAL_FLOOR = 1e-5  # serial map and |sin θ1716|

# The checks of :meth:`Margins.violations`, in the order a tie at one sample is reported, and
# each one's floor (relative to σ_max for the two maps; |sin| for the wrist and the spherical
# joints).
CHECKS = ("wrist", "parallel", "serial", "spherical joint 1", "spherical joint 2")
FLOORS = {"wrist": SERIAL_FLOOR, "parallel": SIGMA_FLOOR, "serial": SERIAL_FLOOR,
          "spherical joint 1": SIGMA_FLOOR, "spherical joint 2": SIGMA_FLOOR}


class MarginError(InputError):
    """A margin that is not a number, not finite, negative, or (the wrist's |sin|) above 1."""


@dataclass(frozen=True)
class Margins:
    """How close to a singularity a sample may come (docs/model.md §12). Validated once,
    here; passed whole.

    Parameters
    ----------
    wrist : float, optional
        The smallest |sin θ1716| allowed, in [0, 1] (default 0.05, about 2.9°).
    singularity : float, optional
        The smallest σ_min of the parallel and of the serial map allowed, finite and ≥ 0
        (default 1e-3). The numerical floors apply whatever the margins, even 0.

    Raises
    ------
    MarginError
        A margin that is not a number, not finite, negative, or (the wrist's) above 1.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> pp.Margins(wrist=0.1)
    Margins(wrist=0.1, singularity=0.001)
    >>> pp.Margins(wrist=2.0)
    Traceback (most recent call last):
    ...
    pollard_pin.kinematics.margins.MarginError: ...
    """

    wrist: float = WRIST_MARGIN
    singularity: float = SINGULARITY_MARGIN

    def __post_init__(self):
        object.__setattr__(self, "wrist", real(
            self.wrist, "wrist margin", 0.0, 1.0, error=MarginError,
            why=" (the smallest |sin θ1716| allowed, in [0, 1])"))
        object.__setattr__(self, "singularity", real(
            self.singularity, "singularity margin", 0.0, error=MarginError,
            why=" (the smallest parallel and serial σ_min allowed)"))

    def margin(self, check: str) -> float:
        """The margin a check of ``CHECKS`` applies (the spherical joints: floor only)."""
        return {"wrist": self.wrist, "parallel": self.singularity,
                "serial": self.singularity}.get(check, 0.0)

    def limits(self, parallel_max=1.0, serial_max=1.0) -> dict:
        """{check: limit} (``CHECKS``): each margin raised to its numerical floor, the σ
        floors relative to the map's σ_max (scalars or arrays)."""
        return {c: self._limit(c, parallel_max, serial_max) for c in CHECKS}

    def _limit(self, check, parallel_max, serial_max):
        import numpy as np

        scale = {"parallel": parallel_max, "serial": serial_max}.get(check, 1.0)
        return np.maximum(self.margin(check), FLOORS[check] * np.asarray(scale, dtype=float))

    def violations(self, *, wrist=None, parallel=None, serial=None, parallel_max=1.0,
                   serial_max=1.0, spherical=None) -> dict:
        """THE margin rule (docs/model.md §12), vectorised: {check: boolean mask} for the
        values given — ``wrist`` |sin θ1716|, ``parallel`` and ``serial`` σ_min (their σ_max
        scale the floors), ``spherical`` the pair of |sin θ109_i| arrays. A value violates
        its check when it is below its limit (:meth:`limits`) or NaN; a value EQUAL to the
        limit passes (value ≥ limit is the test)."""
        import numpy as np

        given = {"wrist": wrist, "parallel": parallel, "serial": serial}
        if spherical is not None:
            given["spherical joint 1"], given["spherical joint 2"] = spherical
        return {c: ~(np.asarray(v, dtype=float) >= self._limit(c, parallel_max, serial_max))
                for c, v in given.items() if v is not None}

    def as_dict(self) -> dict:
        """The margins under their option names (run's and workspace's metadata)."""
        return {"wrist_margin": self.wrist, "singularity_margin": self.singularity}


def as_margins(value) -> Margins:
    """``value`` if it is a :class:`Margins`, the defaults for None; else :class:`MarginError`."""
    if value is None:
        return Margins()
    if not isinstance(value, Margins):
        raise MarginError(f"margins = {shorten(value)}: expected Margins(wrist=…, singularity=…)")
    return value


__all__ = ["CHECKS", "FLOORS", "MarginError", "Margins", "SERIAL_FLOOR", "SIGMA_FLOOR",
           "SINGULARITY_MARGIN", "WRIST_MARGIN", "as_margins"]
