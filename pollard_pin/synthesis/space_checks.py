"""The design space's checks across its entries (docs/model.md §31.2): a key varied twice, a
length bounded below zero, an end of a bound that breaks a parameter's own rule, joint limits
that can cross or span more than a turn, a home pose no design of the box reaches. Each raises
:class:`SpaceError` (one line). ``space`` is a :class:`pollard_pin.synthesis.space.DesignSpace`
(not imported here: space.py reads the file and calls these).
"""
from __future__ import annotations

import itertools
from collections.abc import Mapping

from ..checks import shorten
from ..errors import InputError
from ..model.overrides import ParameterError, lookup
from ..model.params import params_from_dict

LENGTHS = ("chain0.", "leg1.y10", "leg1.z32", "leg1.x43", "leg1.x87", "leg1.x1211",
           "leg1.z1312", "leg2.y10", "leg2.z32", "leg2.x43", "leg2.x87", "leg2.x1211",
           "leg2.z1312", "home.tip")
CORNERS = 64  # designs tried at most for the home pose's reach (corners, then the centre)


class SpaceError(InputError):
    """A design space that breaks a rule (one line)."""


def lengths_nonnegative(key: str, lo: float, where: str) -> None:
    """SpaceError when a length's bound ``[lo, …]`` reaches below zero."""
    if key.startswith(LENGTHS) and not key.startswith("home.") and lo < 0:
        raise SpaceError(f"{where}: {key} = [{lo:g}, …]: a bound below zero (a length)")


def given_once(bounds: Mapping, scales, source: str) -> None:
    """SpaceError when a key is varied twice: in [bounds] and a [[scale]], in two
    [[scale]] tables or twice in one (its value would be a product nobody wrote)."""
    seen = {k: "[bounds]" for k in bounds}
    for i, g in enumerate(scales, start=1):
        for k in g.keys:
            if k in seen:
                was = "twice in" if seen[k] == f"[[scale]] {i}" else f"in {seen[k]} and in"
                raise SpaceError(f"{source}: {k!r} is varied {was} [[scale]] {i}; give each "
                                 "key one entry")
            seen[k] = f"[[scale]] {i}"


def check_limits(space) -> None:
    """SpaceError when a joint's limits, varied, can cross (upper ≤ lower) or span more than
    one turn somewhere in the box (model/params.py's rule at every corner of the entries that
    vary them, not only at each end with the others at their middles): one line naming the
    entries and how far off. upper − lower is linear in each entry: its extremes are corners."""
    varies = {k: ("[bounds]", k, lo, hi) for k, (lo, hi) in space.bounds.items()}
    for i, g in enumerate(space.scales, start=1):  # each key varied once (given_once)
        varies.update({k: (f"[[scale]] {i}", f"scale.{g.name}", g.low, g.high) for k in g.keys})
    for j in sorted({k.split(".")[1] for k in varies if k.startswith("limits.")}):
        keys = (f"limits.{j}.lower", f"limits.{j}.upper")
        entries = {varies[k][1:] for k in keys if k in varies}
        ends = []
        for corner in itertools.product(*[((n, lo), (n, hi)) for n, lo, hi in entries]):
            ov = space.overrides(dict(corner))
            lo_, up = (ov.get(k, float(lookup(space.reference, k))) for k in keys)
            ends.append((up - lo_, lo_, up))
        who = f"{space.source}: " + " and ".join(f"{varies[k][0]} {k!r}" for k in keys
                                                 if k in varies)
        width, lo_, up = min(ends)
        if width <= 0:
            raise SpaceError(f"{who}: the upper limit can be {up:.4g} deg with the lower "
                             f"{lo_:.4g} deg: upper must exceed lower (off by {-width:.4g} deg)")
        width, lo_, up = max(ends)
        if width > 360.0:
            raise SpaceError(f"{who}: the range can reach {width:.4g} deg ({lo_:.4g} to "
                             f"{up:.4g}): one turn (360) at most, {width - 360:.4g} over")


def check_ends(space) -> None:
    """SpaceError when an end of a bound or of a scale's range breaks a parameter's own rule
    (model/params.py's; the other bounds at their middles, the other scales at 1): one line
    naming the entry, the end and the rule."""
    entries = [(f"{space.source} [bounds]", repr(k), k, (k,), lo, hi)
               for k, (lo, hi) in space.bounds.items()]
    entries += [(f"{space.source} [[scale]] {i}", "range", f"scale.{g.name}", g.keys, g.low,
                 g.high) for i, g in enumerate(space.scales, start=1)]
    for where, name, var, keys, lo, hi in entries:
        for end, value in (("low", lo), ("high", hi)):
            try:
                params_from_dict(space.design_dict({var: value}), check_home=False)
            except ParameterError as exc:  # the key's own rule, not another's
                if exc.key in keys:
                    raise SpaceError(f"{where}: {name} = [{lo:g}, {hi:g}]: its {end} end: "
                                     f"{exc}") from None


def _corner_values(space) -> list[dict[str, float]]:
    """The centre, then corners of the continuous box (at most :data:`CORNERS`)."""
    box = [(v.name, v.low, v.high) for v in space.variables() if v.kind == "float"]
    out = [{n: (lo + hi) / 2 for n, lo, hi in box}]
    for corner in itertools.islice(itertools.product(*[(lo, hi) for _, lo, hi in box]),
                                   CORNERS - 1):
        out.append(dict(zip([n for n, _, _ in box], corner)))
    return out


def check_home(space) -> None:
    """SpaceError unless the home pose is reachable for the centre or some corner of the
    bounds (a space where no design can stand at home)."""
    why = ""
    for values in _corner_values(space):
        try:
            params_from_dict(space.design_dict(values), check_home=True)
            return
        except ParameterError as exc:
            why = why or str(exc)
    raise SpaceError(f"{space.source}: the home pose is unreachable at the centre and corners "
                     f"of the bounds (e.g. {shorten(why, 120)})")


__all__ = ["CORNERS", "LENGTHS", "SpaceError", "check_ends", "check_home", "check_limits",
           "given_once", "lengths_nonnegative"]
