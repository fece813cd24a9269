"""The lines ``pollard-pin paint`` prints that several kinds share (each kind's own lines:
its module in :mod:`pollard_pin.painting.kinds`): the motor use, a part's lines, a line's,
the gun body's clearance and the compliance (docs/model.md §21, §23–§25, §27.7)."""
from __future__ import annotations

from .accounting import material_lines


def motor_use_line(rep: dict, names) -> str:
    """Each motor's use of its ratings, one order for panels, parts and lines: peak torque,
    RMS (continuous) torque, speed."""
    use = rep["motors"]
    return "motor peak torque/RMS torque/speed use [%]: " + ", ".join(
        f"{n} {100 * use[n]['peak_torque']:.0f}/{100 * use[n]['rms_torque']:.0f}/"
        f"{100 * use[n]['speed']:.0f}" for n in names)


def part_summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a part."""
    th, target = rep["thickness"], rep["target"]
    return [
        f"passes {rep['passes']} ({rep['direction']}), spacing on the surface "
        f"{rep['spacing'] * 1e3:.2f} mm, spot speed {rep['speed']:.4g} m/s (tip "
        f"{rep['tip_speed_range'][0]:.3g}–{rep['tip_speed_range'][1]:.3g}), coats "
        f"{rep['coats']}, normal averaged over {rep['normal_smoothing'] * 1e3:.3g} mm",
        f"cycle {rep['cycle_time']:.3f} s; painting-only lower bound {rep['lower_bound']:.3f} s "
        "(painted area × target / flow)",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {target * 1e6:.4g} µm), {100 * th['within_5pct']:.2f} % of the area within "
        f"±5 %, {100 * th['within_10pct']:.2f} % within ±10 %",
        f"largest incidence {rep['largest_incidence_deg']:.3g}°, geometric transfer efficiency "
        f"{100 * rep['transfer_efficiency']:.1f} % (on the part / sprayed)",
        motor_use_line(rep, names),
        f"planned in {rep['timings']['plan']:.2f} s, film in {rep['timings']['film']:.2f} s "
        f"({rep['film_points']['painted']} painted film points, {rep['samples']} path "
        "samples)",
    ]


def line_lines(rep: dict) -> list[str]:
    """The lines ``paint`` prints of the line (a panel's or a part's): speed, cycle, the
    speeds that paint it when stated, and the strokes."""
    ln = rep["line"]
    return [
        f"line speed {ln['speed']:.4g} m/s{' (the fastest)' if ln['searched'] else ''}, "
        f"upper bound {ln['upper_bound']:.4g} m/s (part length + window over area × target / "
        "flow)",
        f"start delay {ln['start_delay']:.3f} s, window {ln['window'][0]:.3f}–"
        f"{ln['window'][1]:.3f} m along the line, cycle {ln['cycle']:.3f} s, pitch "
        f"{ln['min_pitch']:.3f} m, {ln['parts_per_hour']:.1f} parts per hour",
        *speeds_lines(rep),
    ] + ([strokes_line(rep["strokes"])] if "strokes" in rep else [])


def strokes_line(strokes: dict, dwell: str | None = None) -> str:
    """paint.json's ``strokes`` in one line (docs/model.md §24.2); ``dwell``: the waits
    said otherwise (a cell's, per robot)."""
    start = strokes.get("step_from")
    where = f", stepping from the {start} end" if start else ""
    waits = dwell if dwell is not None else (
        f"{strokes['dwell_s']:.3f} s" if strokes["dwell_s"] else "none")
    return f"strokes {strokes['direction']} the travel{where}; waits at the turnarounds {waits}"


def speeds_lines(rep: dict) -> list[str]:
    """paint.json's ``line.speeds`` in one line, when stated (``paint --speeds``,
    docs/model.md §24.3), else none."""
    sp = rep["line"].get("speeds")
    if sp is None:
        return []
    found = rep["timings"].get("speeds")
    took = "" if found is None else f", found in {found:.1f} s"
    below, above = (sp[k].removeprefix(side) for k, side in (("min_bound", "too slow: "),
                                                             ("max_bound", "too fast: ")))
    return [f"line speeds that paint it: {sp['min']:.4g}–{sp['max']:.4g} m/s (each end to "
            f"{100 * sp['resolution']:.3g} %{took}); below: {below}; above: {above}"]


def clearance_line(rep: dict) -> str:
    """paint.json's ``min_clearance_m`` in one line (docs/model.md §25)."""
    c = rep["clearance"]
    return (f"gun body {rep['min_clearance_m'] * 1e3:.1f} mm from the part at its "
            f"closest (± {c['between_samples_m'] * 1e3:.1f} mm between samples; "
            f"clearance {c['required_m'] * 1e3:.3g} mm)")


def compliance_line(c: dict) -> str:
    """paint.json's ``compliance`` in one line (docs/model.md §27.7)."""
    if not c["stiffness"] or "note" in c:  # not computed, or nothing to report
        return f"compliance {c['note']}"
    who = f" (robot '{c['standoff_error_robot']}')" if "standoff_error_robot" in c else ""
    return (f"compliance (weight, recoil {c['recoil_n']:.3g} N): standoff error "
            f"{c['standoff_error_m'] * 1e6:.3g} µm{who}, lateral "
            f"{c['lateral_error_m'] * 1e6:.3g} µm, "
            f"tilt {c['tilt_rad'] * 1e3:.3g} mrad; film changes by at most "
            f"{100 * c['film_error']:.2g} % of the target{_edges(c)}")


def _edges(c: dict) -> str:
    """The points beside a shadow's edge, said apart (docs/model.md §27.7)."""
    e = c.get("shadow_edges")
    if not e or not e["points"]:
        return ""
    return (f"; {e['points']} points beside a shadow's edge (its move there counts) by at "
            f"most {100 * e['film_error']:.2g} %")


def film_miss_line(c: dict) -> str:
    """paint.json's ``film_check`` in one warning line, for a film that misses its
    acceptance."""
    a = c["acceptance"]
    return (f"warning: the film misses its acceptance: {100 * (1 - c['outside_10pct']):.2f} % "
            f"of the area within ±{100 * a['band']:g} % of the target (needs "
            f"{100 * a['min_share']:g} %), film {c['min_relative']:.3g}–"
            f"{c['max_relative']:.3g} × the target")


def closing_lines(rep: dict) -> list[str]:
    """The lines after a kind's own: the gun body's clearance where the report has one, the
    compliance where it was computed, the paint used (docs/model.md §29), a warning where the
    film misses its acceptance."""
    lines = [clearance_line(rep)] if "min_clearance_m" in rep else []
    if "compliance" in rep:
        lines.append(compliance_line(rep["compliance"]))
    lines += material_lines(rep)
    if "film_check" in rep and not rep["film_check"]["meets"]:
        lines.append(film_miss_line(rep["film_check"]))
    return lines


__all__ = ["clearance_line", "closing_lines", "compliance_line", "film_miss_line", "line_lines",
           "motor_use_line", "part_summary_lines", "speeds_lines", "strokes_line"]
