"""What ``paint`` says for a panel or a part, still or on a line: the --resolution refusal,
the 'wrote' line and the lines it prints for a part, written once for both (cli/paint.py,
cli/paint_line.py; the files themselves: pollard_pin.io.paint_files)."""
from __future__ import annotations

import sys
from pathlib import Path

from .common import UsageError


def spacing(rule, job, resolution) -> float:
    """The film point spacing [m] by ``rule(job, --resolution)`` (a panel's grid or a part's
    points), its refusal as a usage error naming the flag."""
    from ..painting.errors import ResolutionError

    try:
        return rule(job, resolution)
    except ResolutionError as exc:
        raise UsageError(f"--resolution: {exc}") from None


def say_written(out: Path, table: Path, robots=()) -> None:
    """The line on standard error naming what paint wrote in ``out`` (a cell: a path.csv in
    each robot's folder)."""
    paths = (", ".join(f"{out}/{r}/path.csv" for r in robots) if robots else
             f"{out}/path.csv")
    print(f"wrote {paths}, {table.name}, film.ply, paint.json, thickness.png",
          file=sys.stderr)


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
        f"largest incidence {rep['largest_incidence_deg']:.3g}°, transfer efficiency "
        f"{100 * rep['transfer_efficiency']:.1f} %",
        motor_use_line(rep, names),
        f"planned in {rep['timings']['plan']:.2f} s, film in {rep['timings']['film']:.2f} s "
        f"({rep['film_points']['painted']} painted film points, {rep['samples']} path "
        "samples)",
    ]
