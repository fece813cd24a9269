"""Run ``pollard-pin ARGV`` in this process for the CLI tests (tests/ is on the path)."""
import argparse
import contextlib
import importlib

import pytest

from pollard_pin.cli import main


def run_cli(argv, capsys):
    """(exit code, stdout, stderr) of ``pollard-pin argv``; argv items may be paths."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:  # argparse
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def run_and_size(path, actuators, capsys, tmp_path) -> dict:
    """`run` then `size --format json` of the trajectory ``path`` (a paint job's path.csv),
    each exit 0; `size`'s report."""
    import json

    code, _, err = run_cli(["run", "--trajectory", path, "--out", tmp_path / "run.csv",
                            "--quiet"], capsys)
    assert code == 0, err
    code, out, err = run_cli(["size", "--trajectory", path, "--actuators", actuators,
                              "--format", "json", "--quiet"], capsys)
    assert code == 0, err
    return json.loads(out)


@contextlib.contextmanager
def one_parser():
    """``main`` parses with one parser, built here, instead of one per call: building it (12
    commands' options, 2-3 ms) was a tenth of the fuzz suites' 1,300 calls. argparse keeps no
    state between ``parse_args`` calls; a command that changed a default in place (a
    ``--set`` list) would leak into the next case, and is caught here at the end."""
    module = importlib.import_module("pollard_pin.cli.main")
    parser = module.build_parser()
    before = _defaults(parser)
    with pytest.MonkeyPatch.context() as m:
        m.setattr(module, "build_parser", lambda: parser)
        yield parser
    assert _defaults(parser) == before, "a command changed its parser's defaults in place"


def _defaults(parser: argparse.ArgumentParser) -> dict:
    out = {}
    for action in parser._actions:
        out[parser.prog, action.dest] = repr(action.default)
        if isinstance(action.choices, dict):  # the commands' subparsers
            for sub in action.choices.values():
                out.update(_defaults(sub))
    return out
