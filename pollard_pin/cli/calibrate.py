"""pollard-pin calibrate: the spray pattern fitted to measured stripes (docs/model.md §30)."""
from __future__ import annotations

import sys
from pathlib import Path

from .common import command, fraction, name


def run(args) -> int:
    from ..io.atomic import check_outputs
    from ..io.stripes import read_stripes
    from ..outputs.calibration import FILES, calibrate
    from ..painting.spray.calibrate import CalibrateOptions
    from .common import UsageError, refuse_inputs

    out = Path(args.out)
    files = [out / f for f in FILES]
    check_outputs(*files, folders=(out,))
    if args.efficiency is not None and args.efficiency == 0:
        raise UsageError("--efficiency: must be > 0 (the share of the sprayed paint that "
                         "lands)")
    options = CalibrateOptions(model=args.model, spread=args.spread,
                               efficiency=args.efficiency)
    stripes = read_stripes(args.stripes)
    refuse_inputs(args, *files, also=[("the stripes", args.stripes),
                                      *(("a stripe", f) for f in stripes.files)])
    result = calibrate(stripes, options)
    result.write(out)
    print("\n".join(result.summary_lines()))
    args.notes.extend(result.fit.notes)
    print(f"wrote {out}/gun.toml, calibration.json, fits.png", file=sys.stderr)
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "calibrate", "fit the spray pattern to measured stripes: the "
                "spot model, its sizes and spread law, the transfer efficiency "
                "(docs/model.md §30)", run)
    p.add_argument("--stripes", type=name, required=True, metavar="STRIPES.toml",
                   help="the measured stripes: solids, [[stripe]] tables naming each CSV "
                        "(position, thickness [m]) with its standoff, speed, flow and "
                        "direction (see examples/stripes/stripes.toml)")
    p.add_argument("--out", type=name, default="calibration", metavar="DIR",
                   help="output folder: gun.toml (a [gun] table any job takes), "
                        "calibration.json (every model tried), fits.png")
    p.add_argument("--model", choices=("auto", "gaussian", "elliptic", "beta"),
                   default="auto",
                   help="the spot model: auto chooses by BIC among those the stripes "
                        "identify")
    p.add_argument("--spread", choices=("auto", "cone", "fit"), default="auto",
                   help="the spread law's apex: auto fits it when the stripes have two "
                        "standoffs or more, else 0 (a cone from the nozzle); cone: 0; fit: "
                        "fitted (two standoffs needed)")
    p.add_argument("--efficiency", type=fraction, default=None, metavar="SHARE",
                   help="the transfer efficiency in (0, 1] when known (default: fitted, one "
                        "for all stripes)")
