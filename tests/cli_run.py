"""Run ``pollard-pin ARGV`` in this process for the CLI tests (tests/ is on the path), and
the fuzz suites' "nothing written" snapshot."""
import argparse
import contextlib
import hashlib
import importlib
import os
import signal
import stat

import pytest

from pollard_pin.cli import main


def run_cli(argv, capsys):
    """(exit code, stdout, stderr) of ``pollard-pin argv``; argv items may be paths."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:  # argparse
        code = exc.code
    out, err = capsys.readouterr()
    check_refusal(err)
    return code, out, err


def ctrl_c_as_at_a_terminal() -> None:
    """A child process's ``preexec_fn``: SIGINT back to its default, as a terminal's Ctrl-C
    finds it. A run started in the background (a script's ``&``, as a CI may start the suite)
    hands its children SIGINT ignored, Python then leaves it ignored, and the command's Ctrl-C
    rule (an ignored SIGINT stays ignored) would let a test's Ctrl-C wait forever."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


LONGEST_REFUSAL = 250  # characters: a refusal says its first cause, where, and what to change


def check_refusal(err: str) -> None:
    """Every refusal line on standard error is at most LONGEST_REFUSAL characters and whole
    (not cut short with "…")."""
    for line in err.splitlines():
        if ": error: " in line and line.startswith("pollard-pin "):
            assert len(line) <= LONGEST_REFUSAL, f"refusal of {len(line)} characters: {line}"
            assert not line.endswith("…"), f"refusal cut short: {line}"


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


def tree_state(root, prefix: str = "") -> dict:
    """Every entry under ``root`` (os.scandir: the fuzz suites' 1,300 snapshots felt os.walk's
    joins and pathlib's rglob): a folder, a link (its target, and the digest of the regular
    file it reaches: a write through the link shows), a regular file (its digest), any other
    file (its type, never read: a FIFO would block)."""
    out = {}
    with os.scandir(root) as entries:
        for entry in entries:
            rel = prefix + entry.name
            if entry.is_symlink():
                out[rel] = "-> " + os.readlink(entry.path)
                try:
                    st = entry.stat()  # the target's
                except OSError:  # dangling, or a loop
                    continue
                if stat.S_ISREG(st.st_mode):
                    out[rel + " ->"] = _digest(entry.path, st)
            elif entry.is_dir():
                out[rel] = "folder"
                out.update(tree_state(entry.path, rel + "/"))
            else:
                st = entry.stat()
                out[rel] = (_digest(entry.path, st) if stat.S_ISREG(st.st_mode)
                            else stat.S_IFMT(st.st_mode))
    return out


_DIGESTS: dict[str, tuple[tuple, bytes]] = {}


def _digest(path: str, st: os.stat_result) -> bytes:
    """sha1 of the file at ``path``, read again only when its inode, size, mtime or ctime
    changed (any write changes them; ctime cannot be set back)."""
    key = (st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns)
    known = _DIGESTS.get(path)
    if known is None or known[0] != key:
        with open(path, "rb") as fh:
            known = _DIGESTS[path] = (key, hashlib.sha1(fh.read()).digest())
    return known[1]
