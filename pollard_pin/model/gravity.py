"""Gravity in a robot's base frame (docs/model.md §2, §26.1): a robot turned about x or y
sees g = Rᵀ(0, 0, −9.81); its dynamics use a model copy with that gravity, the shared model
is never changed in place."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import InputError

GRAVITY = np.array([0.0, 0.0, -9.81])  # world, m/s² (docs/model.md §2)
G_TOLERANCE = 0.10  # a gravity's magnitude within 10 % of 9.81 m/s² (a unit or sign slip is not)


def check_gravity(value, where: str) -> np.ndarray:
    """``value`` as a gravity vector [m/s²]: three finite numbers of magnitude 9.81 ± 10 %;
    :class:`~pollard_pin.errors.InputError` (one line naming ``where``) otherwise."""
    if isinstance(value, (bool, np.bool_)) or (
            isinstance(value, (list, tuple)) and any(isinstance(c, (bool, np.bool_))
                                                     for c in value)):
        raise InputError(f"{where}: gravity {value!r}: expected three numbers [m/s²], not "
                         "booleans")
    try:
        g = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{where}: gravity {value!r}: expected three numbers [m/s²]") from None
    if np.asarray(value).dtype == bool:
        raise InputError(f"{where}: gravity {value!r}: expected three numbers [m/s²], not "
                         "booleans")
    if g.shape != (3,) or not np.all(np.isfinite(g)):
        raise InputError(f"{where}: gravity {value!r}: expected three finite numbers [m/s²]")
    ref = float(np.linalg.norm(GRAVITY))
    if np.abs(g).max() > 10 * ref:  # before any arithmetic: |g|² of 1e308 overflows
        raise InputError(f"{where}: gravity {[float(c) for c in g]} has a component of "
                         f"{np.abs(g).max():.4g} m/s², far off {ref:g} (at most "
                         f"{G_TOLERANCE:.0%} off)")
    norm = float(np.linalg.norm(g))
    if abs(norm - ref) > G_TOLERANCE * ref:
        raise InputError(f"{where}: gravity {[float(c) for c in g]} has magnitude {norm:.4g} "
                         f"m/s², {abs(norm - ref) / ref:.0%} off {ref:g} (at most "
                         f"{G_TOLERANCE:.0%})")
    return g


def with_gravity(robot, g):
    """The robot with gravity ``g`` [m/s²] in its base frame: its own model and data (the
    given one is left as it is); itself when ``g`` is the model's own gravity."""
    g = np.asarray(g, dtype=float)
    if np.array_equal(g, np.asarray(robot.model.gravity.linear)):
        return robot
    import pinocchio as pin

    model = pin.Model(robot.model)
    model.gravity = pin.Motion(g, np.zeros(3))
    return replace(robot, model=model, data=model.createData(),
                   constraint_datas=[c.createData() for c in robot.constraint_models])


__all__ = ["GRAVITY", "G_TOLERANCE", "check_gravity", "with_gravity"]
