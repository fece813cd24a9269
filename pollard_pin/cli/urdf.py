"""pollard-pin urdf: generate the URDF and SRDF."""
from __future__ import annotations

from pathlib import Path

from ..io.atomic import all_or_nothing, atomic_open, check_outputs, is_special
from .common import STDOUT, UsageError, command, model_args, name, params_of


def run(args) -> int:
    from ..model.build import generate

    out = Path(args.out) if args.out != STDOUT else None
    # the SRDF beside the URDF; none beside a FIFO or device (as a table's units sidecar)
    srdf_path = None if out is None or is_special(out) else out.with_suffix(".srdf")
    if out is not None:
        check_outputs(out, srdf_path)  # first: a link loop cannot resolve()
        installed = Path(__file__).resolve().parent.parent  # the pollard_pin package
        if installed in out.resolve().parents:
            raise UsageError(f"--out {out}: refusing to write inside the installed package "
                              f"({installed}); write elsewhere and load it with --params")
    params = params_of(args)
    if params is None:
        from ..model.params import load_params

        params = load_params()
    urdf, srdf = generate(params)
    if out is None:
        with atomic_open(STDOUT) as f:
            f.write(urdf)
        return 0
    with all_or_nothing():  # both files or neither; a device (written in place) last
        for path, text in ((srdf_path, srdf), (out, urdf)):
            if path is not None:
                with atomic_open(path) as f:
                    f.write(text)
    also = f" and {srdf_path}" if srdf_path else " (no SRDF beside a device or FIFO)"
    print(f"wrote {out}{also} from {params.source}")
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "urdf",
                "generate the URDF (and the SRDF beside it) from parameters", run)
    model_args(p)
    p.add_argument("--out", type=name, default="pollard.urdf", metavar="FILE.urdf",
                   help="output URDF ('-': the URDF on standard output); the shipped "
                        "model is regenerated with --out models/pollard.urdf")
