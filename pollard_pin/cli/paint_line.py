"""pollard-pin paint of a job with a [line]: the panel or part rides a conveyor
(docs/model.md §24)."""
from __future__ import annotations

from .paint_files import motor_use_line


def line_lines(rep: dict) -> list[str]:
    """The two lines ``paint`` prints of the line (a panel's or a part's)."""
    ln = rep["line"]
    return [
        f"line speed {ln['speed']:.4g} m/s{' (the fastest)' if ln['searched'] else ''}, "
        f"upper bound {ln['upper_bound']:.4g} m/s (part length + window over area × target / "
        "flow)",
        f"start delay {ln['start_delay']:.3f} s, window {ln['window'][0]:.3f}–"
        f"{ln['window'][1]:.3f} m along the line, cycle {ln['cycle']:.3f} s, pitch "
        f"{ln['min_pitch']:.3f} m, {ln['parts_per_hour']:.1f} parts per hour",
    ]


def line_summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a panel on the line."""
    th = rep["thickness"]
    return line_lines(rep) + [
        f"passes {rep['passes']} ({rep['direction']}), spacing {rep['spacing'] * 1e3:.2f} mm, "
        f"gun speed {rep['speed']:.4g} m/s relative to the part",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {rep['target'] * 1e6:.4g} µm), {100 * th['within_5pct']:.2f} % within ±5 %, "
        f"{100 * th['within_10pct']:.2f} % within ±10 %",
        motor_use_line(rep, names),
        f"planned in {rep['timings']['plan']:.2f} s, film map in {rep['timings']['film']:.2f} s "
        f"({rep['grid']['nu']} × {rep['grid']['nv']} points, {rep['samples']} path samples)",
    ]


def cell_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a cell (docs/model.md §26): the line, the film, the
    seams, each robot's zone, start, program and motors, the clearances."""
    ln, th = rep["line"], rep["thickness"]
    lines = [
        f"line speed {ln['speed']:.4g} m/s{' (the fastest)' if ln['searched'] else ''}, "
        f"cycle {ln['cycle']:.3f} s (robot {ln['slowest_robot']!r}, the slowest), pitch "
        f"{ln['min_pitch']:.3f} m, {ln['parts_per_hour']:.1f} parts per hour; upper bound "
        f"{ln['upper_bound']:.4g} m/s",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {rep['target'] * 1e6:.4g} µm), {100 * th['within_5pct']:.2f} % of the area "
        f"within ±5 %, {100 * th['within_10pct']:.2f} % within ±10 %"]
    lines += [f"seam at {s['at']:.4f} m: film {s['min']:.4f}–{s['max']:.4f} of the target "
              f"within ±{s['band_m'] * 1e3:.0f} mm" for s in rep["seams"]]
    for r in rep["robots"]:
        z = r["zone"]
        lo = "edge" if z["lo"] is None else f"{z['lo']:.4f}"
        hi = "edge" if z["hi"] is None else f"{z['hi']:.4f}"
        use = r["motors"]
        peak = max(use[n]["peak_torque"] for n in names)
        rms = max(use[n]["rms_torque"] for n in names)
        lines.append(f"robot {r['name']!r}: zone {lo}..{hi} m, starts {r['start']:.3f} s, "
                     f"program {r['program_time']:.3f} s, cycle {r['cycle']:.3f} s, motors "
                     f"≤ {100 * peak:.0f} % of peak torque, ≤ {100 * rms:.0f} % RMS")
    c = rep["clearance"]
    if c.get("gun_to_part_m") is not None:
        lines.append(f"gun body {c['gun_to_part_m'] * 1e3:.1f} mm from the part at its "
                     f"closest (robot {c['gun_robot']!r})")
    if c.get("to_part_m") is not None:
        lines.append(f"the links of robot {c['robot']!r} {c['to_part_m'] * 1e3:.1f} mm from the "
                     f"part at their closest (t = {c['robot_at_s']:.2f} s)")
    if c.get("between_robots_m") is not None:
        lines.append(f"robots {c['pair'][0]!r} and {c['pair'][1]!r} "
                     f"{c['between_robots_m'] * 1e3:.1f} mm apart at their closest "
                     f"(t = {c['pair_at_s']:.2f} s)")
    lines.append(f"planned in {rep['timings']['plan']:.2f} s, film in "
                 f"{rep['timings']['film']:.2f} s")
    return lines
