"""``pollard-pin workspace``: where the tool reaches at a fixed orientation, how well-conditioned
and how strong it is there (docs/model.md §22). Writes DIR/workspace.csv (or .parquet),
DIR/workspace.json and, for a plane, DIR/workspace.png; nothing when anything fails."""
from __future__ import annotations

import math
from pathlib import Path

from ..io.json_text import finite_json
from ..model.values import parse_float
from .common import (
    UsageError,
    command,
    count,
    load_robot,
    margin_args,
    margins_of,
    model_args,
    name,
    positive,
    progress,
    wrote,
)

HELP = "map where the tool reaches at a fixed orientation (plane or volume)"
DEFAULT_PLANE = "x=0.55"


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "workspace", HELP, run)
    where = p.add_mutually_exclusive_group()
    where.add_argument("--plane", metavar="AXIS=VALUE", default=None,
                       help=f"map a plane grid, e.g. x=0.55 [m] (default: {DEFAULT_PLANE})")
    where.add_argument("--volume", action="store_true",
                       help="map a box instead (streamed: bounded memory; no figure)")
    p.add_argument("--orientation", metavar="PSI,THETA,PHI", default="0,0,0",
                   help="fixed tool orientation (ψ, θ, φ) [deg] (docs/model.md §2); 0,0,0 "
                        "sprays along +x at a vertical wall")
    p.add_argument("--resolution", type=positive, default=0.005, metavar="M",
                   help="grid spacing [m]")
    p.add_argument("--bounds", metavar="AXIS=LO:HI[,AXIS=LO:HI]", default=None,
                   help="grid bounds [m] of some axes, e.g. y=-0.3:0.3,z=-0.1:0.3 (default: "
                        "the whole reach with a margin)")
    p.add_argument("--actuators", type=name, metavar="FILE.toml", default=None,
                   help="actuator file: adds each point's payload capacity and, when it "
                        "gives stiffnesses, kmin, f1 and the sag under the weight "
                        "(workspace_stiffness.png for a plane; default: none)")
    model_args(p)
    margin_args(p)
    p.add_argument("--out", type=name, default="workspace", metavar="DIR",
                   help="output folder")
    p.add_argument("--format", choices=("csv", "parquet"), default="csv",
                   help="table format")
    p.add_argument("--dpi", type=count(10, 1200), default=100, help="PNG resolution")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def parse_orientation(text: str) -> tuple[float, float, float]:
    """"PSI,THETA,PHI" in degrees → radians, checked as the library checks them."""
    from ..workspace.options import WorkspaceError, check_orientation

    parts = text.split(",")
    try:
        vals = [parse_float(x) for x in parts]
    except ValueError:
        vals = []
    if len(vals) != 3 or not all(math.isfinite(v) for v in vals):
        raise UsageError(f"--orientation {text!r}: expected three finite numbers "
                         "PSI,THETA,PHI in degrees, e.g. 0,0,0")
    try:
        return check_orientation(vals, deg=True)
    except WorkspaceError as exc:
        raise UsageError(f"--orientation {text!r}: {exc}") from None


def parse_bounds(text: str | None) -> dict | None:
    """"y=-0.3:0.3,z=-0.1:0.3" → {"y": (-0.3, 0.3), "z": (-0.1, 0.3)}, checked as the library
    checks them."""
    from ..workspace.lattice import check_bounds
    from ..workspace.options import WorkspaceError

    if text is None:
        return None
    out = {}
    for item in text.split(","):
        axis, sep, rng = item.partition("=")
        lo, colon, hi = rng.partition(":")
        try:
            pair = (parse_float(lo), parse_float(hi))
        except ValueError:
            pair = None
        axis = axis.strip().lower()
        if not (sep and colon and pair) or axis not in ("x", "y", "z"):
            raise UsageError(f"--bounds {text!r}: expected AXIS=LOW:HIGH items "
                             "separated by commas, e.g. y=-0.3:0.3,z=-0.1:0.3 [m]")
        if axis in out:
            raise UsageError(f"--bounds {text!r}: {axis} is given twice")
        out[axis] = pair
    try:
        return check_bounds(out)
    except WorkspaceError as exc:
        raise UsageError(f"--bounds {text!r}: {exc}") from None


def run(args) -> int:
    from ..io.atomic import (
        OutputError,
        all_or_nothing,
        atomic_open,
        check_name,
        check_outputs,
        make_folder,
        remove_stale,
    )
    from ..io.table import FORMATS, TableWriter, table_files, write_table
    from ..workspace.grid import WorkspaceError, map_workspace
    from ..workspace.lattice import parse_plane
    from ..workspace.options import WorkspaceOptions

    orientation = parse_orientation(args.orientation)
    margins = margins_of(args)
    bounds = parse_bounds(args.bounds)
    plane = None if args.volume else DEFAULT_PLANE if args.plane is None else args.plane
    if plane is not None:
        try:
            parse_plane(plane)
        except WorkspaceError as exc:
            raise UsageError(f"--plane: {exc}") from None
    out = Path(args.out)
    check_name(out)  # a name too long for the file system: exists() raised
    if out.exists() and not out.is_dir():
        raise OutputError(f"--out {out}: exists and is not a folder")
    paths = {"table": out / f"workspace.{args.format}", "json": out / "workspace.json",
             "png": out / "workspace.png"}
    # an earlier map's outputs that this one does not replace: removed with the writing, so
    # that view --workspace never finds two tables
    stale = [f for fmt in FORMATS if fmt != args.format
             for f in table_files(out / f"workspace.{fmt}", fmt)]
    if plane is None:
        stale.append(paths.pop("png"))
    act = None
    if args.actuators is not None:
        from ..dynamics.motors import load_actuators
        from ..workspace.reach import has_stiffness

        act = load_actuators(args.actuators)
        if plane is not None and has_stiffness(act):  # docs/model.md §27.6
            paths["stiffness"] = out / "workspace_stiffness.png"
    stale.extend(f for f in (out / "workspace_stiffness.png",) if "stiffness" not in paths)
    check_outputs(*table_files(paths["table"], args.format), *list(paths.values())[1:],
                  folders=(out,))
    robot = load_robot(args)
    options = WorkspaceOptions(volume=plane is None, orientation=orientation,
                               resolution=args.resolution, bounds=bounds, actuators=act,
                               margins=margins)
    bar = progress("mapping", not args.quiet)
    metadata = {"command": "workspace", "parameters_source": str(robot.params.source),
                "parameters": robot.params.to_toml_dict(),
                "options": {"plane": plane, "volume": args.volume,
                            "orientation_deg": args.orientation, "bounds": args.bounds,
                            "resolution": args.resolution, "actuators": args.actuators}}
    if plane is not None:  # everything computed before anything written
        ws = map_workspace(robot, plane, options, progress=bar)
    with all_or_nothing():  # every output or none; a folder made for a failed map goes
        make_folder(out)
        if plane is not None:
            write_table(paths["table"], ws.columns, metadata, args.format)
        else:  # streamed: the table is written while the map is computed
            with TableWriter(paths["table"], metadata, args.format) as writer:
                ws = map_workspace(robot, None, options, sink=writer.write, progress=bar)
        ws.summary["metadata"].update(metadata)
        text = finite_json(ws.summary, "workspace.json", indent=1, ensure_ascii=False)
        with atomic_open(paths["json"]) as f:
            f.write(text + "\n")
        if plane is not None:
            from ..viz.workspace import write_workspace_png

            write_workspace_png(ws, paths["png"], args.dpi)
        if "stiffness" in paths:
            from ..viz.workspace import write_stiffness_png

            write_stiffness_png(ws, paths["stiffness"], args.dpi)
        remove_stale(*stale)
    print(summary_text(ws))
    for path in paths.values():
        wrote(path)
    return 0


def summary_text(ws) -> str:
    s = ws.summary
    deg = ", ".join(f"{math.degrees(a):g}" for a in ws.orientation)
    g = s["grid"]
    lines = [f"grid {' × '.join(map(str, g['shape']))} ({g['points']:,} points, step "
             f"{g['step']:g} m) at (ψ, θ, φ) = ({deg})°, "
             f"{s['metadata']['us_per_point']:.2f} µs/point"]
    if "area" in s:
        bound = (f" ± {s['area_bound']:.2g}" if "area_bound" in s else "")
        lines.append(f"area {s['area']:.5g}{bound} m² ({s['reachable_points']:,} reachable "
                     f"points{', ± their boundary cells' if bound else ''})")
    else:
        lines.append(f"volume {s['volume']:.5g} m³ ({s['reachable_points']:,} reachable "
                     "points)")
    lo, hi = s["bounding_box"]["low"], s["bounding_box"]["high"]
    lines.append("reachable box " + ", ".join(f"{a} ∈ [{lo[i]:.4g}, {hi[i]:.4g}]"
                                              for i, a in enumerate("xyz")) + " m")
    rect = s.get("largest_rectangle")
    if rect:
        c = rect["centre"]
        lines.append(f"largest rectangle {rect['size'][0]:.4g} × {rect['size'][1]:.4g} m "
                     f"({'–'.join(rect['axes'])}), centre ({c[0]:.4g}, {c[1]:.4g}, "
                     f"{c[2]:.4g}) m")
    lines.append(f"global conditioning index {s['global_conditioning_index']:.4g}")
    if "payload_capacity" in s:
        p = s["payload_capacity"]
        lines.append(f"payload capacity {p['min']:.4g} to {p['max']:.4g} kg over the "
                     "reachable points")
    if "stiffness" in s:
        st = s["stiffness"]
        sag = (f", sag {1e6 * st['sag']['min']:.4g} to {1e6 * st['sag']['max']:.4g} µm"
               if "sag" in st else "")
        beyond = st.get("sag_beyond_linear_points")
        lines.append(f"stiffness over the reachable points: kmin {st['kmin']['min']:.4g} to "
                     f"{st['kmin']['max']:.4g} N/m, f1 {st['f1']['min']:.4g} to "
                     f"{st['f1']['max']:.4g} Hz{sag}"
                     + (f"; sag blank at {beyond:,} points where a drive turns beyond the "
                        "linear model's bound (docs/model.md §27.2)" if beyond else ""))
    lines.append("points by reason: " + ", ".join(f"{r} {c:,}"
                                                  for r, c in s["reason_counts"].items()))
    return "\n".join(lines)
