"""Run ``pollard-pin ARGV`` in this process for the CLI tests (tests/ is on the path)."""
from pollard_pin.cli import main


def run_cli(argv, capsys):
    """(exit code, stdout, stderr) of ``pollard-pin argv``; argv items may be paths."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:  # argparse
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err
