"""The paint a job uses (docs/model.md §29): paint.json's ``paint`` (and a cell robot's) and
the lines ``pollard-pin paint`` prints of it.

The dry film volume on the part is ∫ film dA over the film's points (a panel's grid: the
trapezoid rule's cell areas; a part's points: their area weights, which cover every face the
gun lies in front of); the dry volume sprayed is flow × the spray-on time, the trapezoid weights
of the very samples the film integrates (a trigger's fractions at a cell's seams included).
The geometric overspray is 1 − on the part / sprayed. With a ``[paint]`` table these become
litres and kilograms of liquid paint: wet = dry / solids, and the gun sprays
flow / (solids · transfer efficiency) of liquid per second.
"""
from __future__ import annotations

import math

import numpy as np

from .errors import ReportError
from .film.grid import grid_areas
from .film.stats import ACCEPTANCE_BAND
from .report import SLACK

# The painted area: where the film reaches this share of the target (the acceptance band's
# lower edge, docs/model.md §21).
COVERED_SHARE = 1.0 - ACCEPTANCE_BAND
LITRE = 1e-3  # m³
HOUR = 3600.0  # s
# Where the figures hold (paint.json's paint.holds).
HOLDS = ("the film model's: paint on the part = the film's integral over its points (a flat "
         "panel: exact to the grid's quadrature, second order where the panel cuts the spot; "
         "a part: over its facets); electrostatic wrap and bounce are not modelled")


def point_areas(film) -> np.ndarray:
    """Each film point's area [m²] (P,): a panel's grid cells (its ``grid``), else the part's
    points' weights. ``film``: a :class:`~pollard_pin.painting.result.PaintFilm`."""
    if film.grid is not None:
        return grid_areas(*film.grid)
    return np.asarray(film.points.areas, dtype=float)


def dry_volumes(film, areas=None) -> tuple[float, float, list]:
    """(dry volume on the part [m³], dry volume sprayed [m³], each robot's (on, sprayed) of a
    cell) of a :class:`~pollard_pin.painting.result.PaintFilm`: Σ film × area over its
    points and flow × the spray-on time (the film's ``sprayed``)."""
    areas = point_areas(film) if areas is None else areas
    f = film.film
    if hasattr(f, "landed"):  # a part's MeshFilm: its own sums
        return f.landed, f.sprayed, [(r.landed, r.sprayed) for r in f.robots]
    return (float(f.thickness @ areas), float(f.sprayed),
            [(float(r.thickness @ areas), float(r.sprayed)) for r in f.robots])


def _share(on: float, sprayed: float) -> float | None:
    return 1.0 - on / sprayed if sprayed > 0 else None


def liquid(dry: float, paint, sprayed: bool) -> tuple[float, float]:
    """(litres, kg) of the liquid paint of ``dry`` [m³] of dry film: the wet film
    dry / solids on the part; what the gun sprays dry / (solids · transfer efficiency)."""
    wet = dry / paint.solids / (paint.efficiency if sprayed else 1.0)
    return wet / LITRE, wet * paint.density


def _volumes(on: float, sprayed: float, paint, per_hour: float | None) -> dict:
    out = {"dry_sprayed_l": sprayed / LITRE, "dry_on_part_l": on / LITRE,
           "overspray": _share(on, sprayed)}
    if paint is not None:
        (ls, ks), (lo, ko) = liquid(sprayed, paint, True), liquid(on, paint, False)
        out.update(sprayed_l=ls, sprayed_kg=ks, on_part_l=lo, on_part_kg=ko)
        if per_hour is not None:
            out.update(sprayed_l_per_h=ls * per_hour, sprayed_kg_per_h=ks * per_hour,
                       on_part_l_per_h=lo * per_hour, on_part_kg_per_h=ko * per_hour)
    return out


def material_entry(job, film, cycle: float) -> tuple[dict, list]:
    """(paint.json's ``paint``, each cell robot's ``paint``) of a job's film
    (docs/model.md §29).

    Parameters
    ----------
    job : PaintJob or pollard_pin.painting.job.PartJob
        The job (its ``thickness`` target and ``paint``).
    film : pollard_pin.painting.result.PaintFilm
        Its film.
    cycle : float
        The job's cycle [s]: a part every ``cycle``.

    Returns
    -------
    dict
        The painted area (film ≥ COVERED_SHARE × target on the target faces) and the target
        area [m²], the dry volumes sprayed and on the part [L], the geometric overspray, the
        parts per hour; with a ``[paint]`` table its solids, density, the transfer efficiency
        used and the liquid paint sprayed and on the part per part and per hour [L, kg].
    list of dict
        A cell's robots' volumes and overspray, in its robots' order (else empty).
    """
    areas = point_areas(film)
    th = np.asarray(film.thickness, dtype=float).ravel()
    target = areas if film.painted is None else np.where(film.painted, areas, 0.0)
    on, sprayed, robots = dry_volumes(film, areas)
    per_hour = HOUR / cycle if cycle > 0 and math.isfinite(cycle) else None
    paint = job.paint
    entry = {"covered_share": COVERED_SHARE,
             "painted_area_m2": float(target[th >= COVERED_SHARE * job.thickness].sum()),
             "target_area_m2": float(target.sum()),
             **_volumes(on, sprayed, None, None), "parts_per_hour": per_hour}
    if paint is not None:
        entry.update(solids=paint.solids, density=paint.density,
                     transfer_efficiency=paint.efficiency,
                     **{k: v for k, v in _volumes(on, sprayed, paint, per_hour).items()
                        if k not in entry})
    entry["holds"] = HOLDS + ("" if paint is None or paint.transfer_efficiency is not None
                              else "; no transfer efficiency given: 1, only the geometric "
                                   "overspray counted")
    return _known(entry), [_known(_volumes(o, s, paint, per_hour)) for o, s in robots]


def _known(entry: dict) -> dict:
    """The entries that are not None (paint.json leaves those out)."""
    return {k: v for k, v in entry.items() if v is not None}


def with_material(rep: dict, job, film) -> dict:
    """``rep`` with its ``paint`` (after ``film_check``, else at the end) and each cell
    robot's ``paint``; a :class:`ReportError` if more lands than is sprayed (beyond SLACK,
    the film's integration error: a bug)."""
    entry, robots = material_entry(job, film, rep["cycle_time"])
    if entry.get("overspray", 0.0) < -SLACK:
        raise ReportError(f"{job.source}: internal error: {entry['dry_on_part_l']:.6g} L of "
                          f"dry film on the part, more than the {entry['dry_sprayed_l']:.6g} L "
                          "sprayed (a bug)")
    for r, e in zip(rep.get("robots", ()), robots):
        r["paint"] = e
    out = {}
    for k, v in rep.items():
        out[k] = v
        if k == "film_check":
            out["paint"] = entry
    out.setdefault("paint", entry)
    return out


def _litres(v: float) -> str:
    return f"{v:.3g} L"


def _pct(share: float | None) -> str:
    return "—" if share is None else f"{100 * share:.1f} %"


def material_lines(rep: dict) -> list[str]:
    """The lines ``paint`` prints of paint.json's ``paint``: the area and the dry film's
    overspray (every job; a cell's by robot), and with a ``[paint]`` table the litres and
    kilograms per part and per hour."""
    p = rep.get("paint")
    if p is None:
        return []
    robots = [(r["name"], r["paint"]) for r in rep.get("robots", ()) if "paint" in r]
    by = "; by robot " + ", ".join(f"{n} {_pct(e.get('overspray'))}" for n, e in robots) \
        if robots else ""
    lines = [f"paint: {p['painted_area_m2']:.4g} of {p['target_area_m2']:.4g} m² at ≥ "
             f"{100 * p['covered_share']:.0f} % of the target; dry film "
             f"{_litres(p['dry_sprayed_l'])} sprayed, {_litres(p['dry_on_part_l'])} on the "
             f"part: geometric overspray {_pct(p.get('overspray'))}{by}"]
    if "solids" not in p:
        return lines
    given = "transfer_efficiency" in rep.get("job", {}).get("paint", {})
    te = (f"transfer efficiency {100 * p['transfer_efficiency']:.3g} %" if given else
          "no transfer efficiency: the geometric overspray only")
    hour = "" if "sprayed_l_per_h" not in p else (
        f"; per hour ({p['parts_per_hour']:.1f} parts) {_litres(p['sprayed_l_per_h'])} = "
        f"{p['sprayed_kg_per_h']:.3g} kg sprayed, {_litres(p['on_part_l_per_h'])} on the part")
    lines.append(f"liquid paint (solids {100 * p['solids']:.3g} %, {p['density']:.4g} kg/m³, "
                 f"{te}): per part {_litres(p['sprayed_l'])} = "
                 f"{p['sprayed_kg']:.3g} kg sprayed, {_litres(p['on_part_l'])} = "
                 f"{p['on_part_kg']:.3g} kg on the part{hour}")
    return lines


__all__ = ["COVERED_SHARE", "HOLDS", "dry_volumes", "liquid", "material_entry",
           "material_lines", "point_areas", "with_material"]
