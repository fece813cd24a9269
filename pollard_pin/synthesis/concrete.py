"""One design made concrete (docs/model.md §31.1–§31.2): its parameters under the mass model,
its actuators from the chosen motors, and the TOML texts every command reads back
(``--params``, ``--actuators``)."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..dynamics.motors import Actuators
from ..io.job_file import toml_value
from ..model.masses import design_bodies
from ..model.params import Params, params_from_dict
from ..names import ACTUATED
from .space import DesignSpace


@dataclass(frozen=True)
class Design:
    """A design's robot, from :func:`build`.

    Attributes
    ----------
    params : Params
        Its parameters, the masses from the mass model (docs/model.md §31.1).
    actuators : Actuators
        The chosen motors behind their gear ratios.
    robots : int
        The robots in the cell.
    motors : dict
        Actuator joint → (motor name, gear ratio).
    toml : dict
        Its thesis-unit dictionary (the parameter file's layout).
    price : float or None
        One robot's motors' catalogue price (None: the catalogue has none).
    """

    params: Params
    actuators: Actuators
    robots: int
    motors: dict
    toml: dict
    price: float | None

    @property
    def moving_mass(self) -> float:
        """One robot's moving mass [kg]: its links and the motors they carry."""
        return self.params.total_mass


def build(values: Mapping[str, Any], space: DesignSpace, check_home: bool = True) -> Design:
    """The :class:`Design` of ``values`` (a value per :meth:`DesignSpace.variables`).

    Parameters
    ----------
    values : Mapping
        The design's values (keys left out: the middle of their bounds, motor 0, ratio 0,
        the fewest robots).
    space : DesignSpace
        The space they belong to.
    check_home : bool, optional
        Refuse a design whose home pose is out of reach (default True).

    Returns
    -------
    Design
        The design.

    Raises
    ------
    pollard_pin.model.overrides.ParameterError
        A parameter out of its rule, or the home pose out of reach (one line).
    pollard_pin.synthesis.space.SpaceError
        An index or a robot count out of its range.
    """
    d = space.design_dict(values)
    chosen = space.motors(values)
    d["bodies"] = design_bodies(space.reference, d, {j: m.mass for j, (m, _) in chosen.items()})
    for j, (m, n) in chosen.items():  # the URDF's limits say what the motor gives
        d["limits"][j]["effort"] = round(m.peak_torque * n, 6)
        d["limits"][j]["velocity"] = round(m.speed / n, 6)
    params = params_from_dict(d, source="design", check_home=check_home)
    act = Actuators(ACTUATED, tuple(chosen[j][0].actuator(chosen[j][1]) for j in ACTUATED),
                    "design")
    price = (sum(chosen[j][0].price for j in ACTUATED) if space.catalogue.priced else None)
    return Design(params, act, space.robot_count(values),
                  {j: (m.name, n) for j, (m, n) in chosen.items()}, d, price)


def _table(lines: list[str], name: str, t: Mapping) -> None:
    lines += ["", f"[{name}]"]
    for k, v in t.items():
        if isinstance(v, Mapping):
            inner = ", ".join(f"{kk} = {toml_value(_plain(vv))}" for kk, vv in v.items())
            lines.append(f"{k} = {{ {inner} }}")
        else:
            lines.append(f"{k} = {toml_value(_plain(v))}")


def _plain(v):
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return float(v) if isinstance(v, float) else v


def params_toml(design: Design, header: str = "") -> str:
    """The design's parameter file (the layout of models/pollard.toml, thesis units)."""
    lines = [f"# {h}" for h in header.splitlines()]
    d = design.toml
    for sec in ("chain0", "leg1", "leg2"):
        _table(lines, sec, d[sec])
    for name, b in d["bodies"].items():
        _table(lines, f"bodies.{name}", b)
    for sec in ("home", "branches", "limits"):
        _table(lines, sec, d[sec])
    return "\n".join(lines).lstrip("\n") + "\n"


def actuators_toml(design: Design, header: str = "") -> str:
    """The design's actuator file (the layout of examples/actuators.toml)."""
    lines = [f"# {h}" for h in header.splitlines()]
    for j, u in zip(design.actuators.names, design.actuators.units):
        motor, _ = design.motors[j]
        t = {"gear_ratio": u.gear_ratio, "rotor_inertia": u.rotor_inertia,
             "viscous": u.viscous, "coulomb": u.coulomb, "peak_torque": u.peak_torque,
             "continuous_torque": u.continuous_torque, "max_speed": u.max_speed}
        if u.stiffness is not None:
            t["stiffness"] = u.stiffness
        lines += ["", f"[{j}]  # {motor}"] + [f"{k} = {toml_value(float(v))}"
                                               for k, v in t.items()]
    return "\n".join(lines).lstrip("\n") + "\n"


__all__ = ["Design", "actuators_toml", "build", "params_toml"]
