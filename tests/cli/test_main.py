"""The command line as users meet it: bad values give one line and exit 2 with nothing written,
outputs never harm what is there (FIFOs, devices, existing files), and the usual habits
(--help with defaults, --version, -v, --set, partial --params, '-' for standard output)."""
import argparse
import os
import re
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli

import pollard_pin as pp

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
PACKAGE = ROOT / "pollard_pin"




@pytest.fixture
def files(tmp_path, monkeypatch):
    """A scratch folder as the working directory, with a few bad input files."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("not a folder\n")
    (tmp_path / "afolder").mkdir()
    (tmp_path / "latin1.toml").write_bytes("# m\xfcde\n[chain0]\nx32 = 0.34\n".encode("latin-1"))
    (tmp_path / "latin1.csv").write_bytes("t,x,y,z,psi,theta,phi\n# \xe9\n".encode("latin-1"))
    (tmp_path / "huge.toml").write_text("[chain0]\nx32 = 1e300\n")
    (tmp_path / "broken.toml").write_text("[chain0\n")
    return tmp_path


SHORT = ["--samples", "401", "--quiet"]
BAD = [  # (argv, what the one error line must say)
    (["urdf", "--params", "missing.toml"], "does not exist"),
    (["urdf", "--params", "latin1.toml"], "is not UTF-8 text"),
    (["urdf", "--params", "huge.toml"], "must be at most 10 m"),
    (["urdf", "--params", "broken.toml"], "is not valid TOML"),
    (["urdf", "--out", "afile/x.urdf"], "afile is a file, not a folder"),
    (["urdf", "--out", "afolder"], "is a folder"),
    (["urdf", "--set", "chain0.x32=abc"], "not a number"),
    (["urdf", "--set", "chain0.nope=1"], "names no parameter"),
    (["urdf", "--set", "chain0.x32"], "expected KEY=VALUE"),
    (["urdf", "--out", str(PACKAGE / "models" / "x.urdf")], "inside the installed package"),
    (["info", "--params", "broken.toml"], "is not valid TOML"),
    (["info", "--set", "bodies.gun.mass=-1"], "must be > 0"),
    (["run", "--samples", "0"], "must be >= 2"),
    (["run", "--samples", "1"], "must be >= 2"),
    (["run", "--samples", "many"], "not an integer"),
    (["run", "--duration", "0"], "must be > 0"),
    (["run", "--duration", "nan"], "must be a finite number"),
    (["run", "--wrist-margin", "nan"], "must be a finite number"),
    (["run", "--wrist-margin", "-1"], "must be >= 0"),
    (["run", "--singularity-margin", "nan"], "must be a finite number"),
    (["run", "--singularity-margin", "-0.1"], "must be >= 0"),
    (["run", *SHORT, "--out", "afile/run.csv"], "afile is a file, not a folder"),
    (["run", *SHORT, "--out", "afolder"], "is a folder"),
    (["run", "--trajectory", "latin1.csv", "--out", "r.csv"], "not UTF-8 text"),
    (["run", "--trajectory", "missing.csv", "--out", "r.csv"], "No such file"),
    (["run", *SHORT, "--params", "huge.toml", "--out", "r.csv"], "must be at most 10 m"),
    (["sweep", "--grid", "missing.toml", "--out", "s.csv"], "missing.toml"),
    (["sweep", "--grid", "latin1.toml", "--out", "s.csv"], "is not UTF-8 text"),
    (["sweep", "--grid", "afolder", "--out", "s.csv"], "cannot be read"),
    (["sweep", "--grid", "g.toml", "--workers", "0"], "must be >= 1"),
    (["sweep", "--grid", str(EXAMPLES / "sweep.toml"), "--out", "afile/s.csv"], "not a folder"),
    (["view", *SHORT, "--html", "afile/p.html"], "not a folder"),
    (["view", *SHORT, "--fps", "0", "--html", "p.html"], "must be > 0"),
    (["plot", *SHORT, "--dpi", "0"], "must be between 10 and 1200"),
    (["plot", *SHORT, "--dpi", "-1"], "must be between 10 and 1200"),
    (["plot", *SHORT, "--out", "afile"], "names a file, but a folder is expected"),
    (["report", *SHORT, "--format", "xml"], "invalid choice"),
    (["report", *SHORT, "--out", "afile/r.md"], "not a folder"),
    (["report", *SHORT, "--simulation", "latin1.csv", "--out", "r.md"], "not UTF-8 text"),
    (["plot", *SHORT, "--simulation", "afolder", "--out", "p"], "is a folder, not a result"),
    (["export", "--format", "stl"], "invalid choice"),
    (["export", "--out", "afile/m.xml"], "not a folder"),
    (["frobnicate"], "invalid choice"),
    ([], "required"),
]


@pytest.mark.parametrize("argv, says", BAD, ids=[" ".join(a) or "<none>" for a, _ in BAD])
def test_bad_values_give_one_line_exit_2_and_write_nothing(files, capsys, argv, says):
    before = sorted(p.relative_to(files) for p in files.rglob("*"))
    shipped = {p: p.stat().st_mtime_ns for p in (ROOT / "models").iterdir()}
    code, out, err = run_cli(argv, capsys)
    assert code == 2, (code, out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin"), err
    assert says in lines[0] and "Traceback" not in err, lines[0]
    assert "np.float64" not in lines[0]
    assert sorted(p.relative_to(files) for p in files.rglob("*")) == before  # nothing written
    assert shipped == {p: p.stat().st_mtime_ns for p in (ROOT / "models").iterdir()}


def test_failed_run_leaves_an_existing_output_untouched(files, capsys):
    out = files / "run.csv"
    out.write_text("precious\n")
    code, _, err = run_cli(["run", *SHORT, "--params", "huge.toml", "--out", str(out)], capsys)
    assert code == 2 and "nothing written to" in err
    assert out.read_text() == "precious\n"


def test_run_writes_into_a_fifo_and_leaves_it_a_fifo(files, capsys):
    fifo = files / "pipe"
    os.mkfifo(fifo)
    got = {}

    def reader():
        with open(fifo) as f:
            got["text"] = f.read()

    th = threading.Thread(target=reader)
    th.start()
    code, out, err = run_cli(["run", *SHORT, "--out", str(fifo)], capsys)
    if code != 0:  # unblock the reader
        with open(fifo, "w"):
            pass
    th.join(30)
    assert code == 0, err
    assert fifo.is_fifo(), "the FIFO was replaced"
    assert not [p for p in files.iterdir() if p.name.startswith(".pipe")], "temporary left"
    rows = got["text"].strip().splitlines()
    assert rows[0].startswith("t,x,y,z,psi,theta,phi,") and len(rows) == 402


def test_run_out_dash_writes_the_csv_to_stdout(files, capsys):
    code, out, err = run_cli(["run", *SHORT, "--out", "-"], capsys)
    assert code == 0, err
    rows = out.strip().splitlines()
    assert rows[0].startswith("t,x,y,z,") and len(rows) == 402  # the summary is on stderr
    assert "peak closure force" in err
    assert sorted(p.name for p in files.iterdir()) == ["afile", "afolder", "broken.toml",
                                                       "huge.toml", "latin1.csv", "latin1.toml"]


def test_run_out_dash_into_a_closed_pipe_stops_quietly(tmp_path):
    # `pollard-pin run --out - | head -1`: the reader leaves; no traceback, status 128 + SIGPIPE
    proc = subprocess.Popen([sys.executable, "-m", "pollard_pin.cli", "run", "--out", "-",
                             "--samples", "20001", "--quiet"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout.readline().startswith(b"t,x,y,z,")
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(60) == 141, err
    assert err == "" and not list(tmp_path.iterdir())


def test_terminated_run_removes_its_temporary_file(tmp_path):
    # SIGTERM (kill, a job's time limit) ended Python on the spot: a 100 MB temporary stayed
    out = tmp_path / "big.parquet"
    out.write_text("precious\n")
    proc = subprocess.Popen([sys.executable, "-m", "pollard_pin.cli", "run", "--out", str(out),
                             "--samples", "3000001", "--quiet"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    temporaries = []
    while proc.poll() is None and not temporaries:  # writing has begun
        threading.Event().wait(0.02)
        temporaries = list(tmp_path.glob(".big.parquet.*.tmp"))
    proc.terminate()
    _, err = proc.communicate(60)
    assert temporaries, "the run ended before writing"
    assert proc.returncode == 143, err
    assert err.decode().strip() == "pollard-pin run: terminated, nothing written"
    assert sorted(tmp_path.iterdir()) == [out] and out.read_text() == "precious\n"


def test_set_and_partial_params_file_give_the_same_model(files, capsys):
    (files / "mine.toml").write_text("[bodies.gun]\nmass = 0.05\n")
    code, a, _ = run_cli(["info", "--params", "mine.toml"], capsys)
    code2, b, _ = run_cli(["info", "--set", "bodies.gun.mass=0.05"], capsys)
    assert code == code2 == 0
    assert a == b and "total mass 0.9350 kg" in a and "gun       0.050 kg" in a


def test_help_shows_every_default_and_no_markup(capsys):
    from pollard_pin.cli import build_parser

    code, out, _ = run_cli(["--help"], capsys)
    assert code == 0 and "``" not in out and ":func:" not in out and ":class:" not in out
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    assert set(sub.choices) >= {"run", "plot", "report", "view", "sweep", "urdf", "info",
                                "export"}
    for cmd, parser in sub.choices.items():
        text = " ".join(parser.format_help().split())
        for action in parser._actions:
            if action.nargs == 0 or action.required or not action.option_strings:
                continue  # flags, required values
            help_text = " ".join(parser._get_formatter()._expand_help(action).split())
            shown = ("(default: " in help_text or "; default: " in help_text)
            assert shown and help_text in text, f"{cmd} {action.option_strings}: {help_text}"
    code, out, _ = run_cli(["run", "--help"], capsys)
    assert "(default: run.csv)" in " ".join(out.split())


def test_version_and_verbose(capsys):
    code, out, _ = run_cli(["--version"], capsys)
    assert code == 0 and out.strip() == f"pollard-pin {pp.__version__}"
    r = subprocess.run([sys.executable, "-m", "pollard_pin.cli", "info", "-v"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and re.search(r"INFO pollard_pin: model .* loaded", r.stderr)


def test_robot_repr_is_short(robot):
    text = repr(robot)
    assert len(text) < 200 and "nq=12" in text and "closure1" in text and "<robot" not in text


# --- the shipped example trajectories ---------------------------------------------------------
def test_example_trajectories_are_what_the_script_makes(tmp_path):
    r = subprocess.run([sys.executable, str(EXAMPLES / "make_trajectory.py"), "--out-dir",
                        str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    for name in ("figure8.csv", "figure8_poses.csv"):
        assert (tmp_path / name).read_bytes() == (EXAMPLES / name).read_bytes(), name


def test_example_trajectories_run_and_agree(robot, capsys, tmp_path):
    """The exact-derivative file against the analytic path, and the poses-only file (spline
    derivatives) against the exact one."""
    sys.path.insert(0, str(EXAMPLES))
    try:
        from make_trajectory import figure_eight
    finally:
        sys.path.remove(str(EXAMPLES))
    exact = pp.from_csv(EXAMPLES / "figure8.csv")
    pose, rate, acc = figure_eight(exact.t)
    assert np.array_equal(exact.poses, pose) and np.array_equal(exact.dd_poses, acc)
    results = {}
    for name in ("figure8", "figure8_poses"):
        out = tmp_path / f"{name}_run.csv"
        code, _, err = run_cli(["run", "--trajectory", str(EXAMPLES / f"{name}.csv"), "--out",
                             str(out), "--quiet"], capsys)
        assert code == 0, err
        results[name] = np.genfromtxt(out, delimiter=",", names=True)
    a, b = results["figure8"], results["figure8_poses"]
    for col, tol in (("theta21_1", 1e-8), ("d_theta21_1", 1e-6), ("tau_theta21", 1e-5),
                     ("tau_theta21_2", 1e-5)):
        assert np.abs(a[col] - b[col]).max() <= tol * max(1.0, np.abs(a[col]).max()), col


def test_a_full_standard_output_is_one_line_not_a_traceback():
    """`info > /dev/full`: the text cannot be printed; one line on stderr, exit 2, and no
    'Exception ignored' from Python's flush at exit (it gave an ENOSPC traceback)."""
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "pollard_pin.cli", "info"], stdout=full,
                              stderr=subprocess.PIPE, text=True, timeout=120)
    err = done.stderr.strip()
    assert done.returncode == 2, err
    # worded as io.atomic's own write errors (`urdf --out - > /dev/full`)
    assert err == ("pollard-pin info: error: standard output: cannot write: no space left "
                   "on device")


def _family_errors():
    """One error of each family, and each of the named pairs the family rule settles
    (pollard_pin/errors.py)."""
    from pollard_pin.analytic.closed_form import UnreachableError
    from pollard_pin.errors import DestinationError, InputError, SolveError
    from pollard_pin.kinematics.errors import KinematicsInputError, UnreachablePoseError

    return [InputError("bad value"), SolveError("no solution"),
            DestinationError("cannot write x.csv: not a folder"),
            UnreachableError("leg 1", 3, 0.002, 1.1),
            UnreachablePoseError("leg 1 cannot reach", sample=3, time=0.5),
            KinematicsInputError("poses must be finite", sample=2, chain="x")]


@pytest.mark.parametrize("exc", _family_errors(), ids=lambda e: type(e).__name__)
def test_every_family_is_one_line_and_exit_2(monkeypatch, capsys, exc):
    def fails(args):
        raise exc

    monkeypatch.setattr("pollard_pin.cli.info.load_robot", fails)
    code, out, err = run_cli(["info"], capsys)
    assert code == 2 and out == "", (code, out, err)
    assert err.splitlines() == [f"pollard-pin info: error: {exc}"], err


def test_a_long_refusal_gives_way_its_suffix_then_its_folders_never_its_cause(
        monkeypatch, capsys, tmp_path, caplog):
    from pollard_pin.errors import LONGEST_LINE, SolveError

    folder = "/tmp/" + "deep/" * 20
    cause = "the cause, where it happened, and what to change " * 3

    def fails(args):
        raise SolveError(f"{folder}job.toml: {cause}")

    monkeypatch.setattr("pollard_pin.painting.job.load_job", fails)
    out = tmp_path / ("o" * 40)
    code, _, err = run_cli(["paint", "--job", "j.toml", "--out", out], capsys)
    assert code == 2
    line, = err.splitlines()
    assert len(line) <= LONGEST_LINE, line  # the folders and the output's name give way
    assert line == f"pollard-pin paint: error: job.toml: {cause.strip()} (nothing written)"
    cause *= 2  # then the suffix; the cause itself is never cut (too long: whole, a bug,
    # which run_cli's check of every refusal catches)
    with pytest.raises(AssertionError, match="refusal of 329 characters"):
        run_cli(["paint", "--job", "j.toml", "--out", out], capsys)
    cause = cause[:len(cause) // 2]
    with caplog.at_level("INFO", logger="pollard_pin"):  # -v: the whole story
        run_cli(["-v", "paint", "--job", "j.toml", "--out", out], capsys)
    assert f"{folder}job.toml" in caplog.text and f"nothing written to {out}" in caplog.text


@pytest.mark.parametrize("argv", [
    ["plot", "--samples", "11", "--out", "p", "--simulation", "a" * 300 + ".csv"],
    ["view", "--samples", "11", "--html", "v.html", "--paint", "a" * 300],
    ["view", "--samples", "11", "--html", "v.html", "--workspace", "a" * 300],
])
def test_an_input_name_too_long_for_the_file_system_is_one_line(tmp_path, monkeypatch, capsys,
                                                                argv):
    # Path.is_dir() and exists() raise ENAMETOOLONG (a traceback) where they answer False for
    # a missing file
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(argv, capsys)
    lines = err.strip().splitlines()
    assert code == 2 and out == "" and len(lines) == 1, err[-2000:]
    assert lines[0].startswith(f"pollard-pin {argv[0]}: error: 'aaaaaaaaaaa…"), lines[0]
    assert "holds a name of 30" in lines[0] and lines[0].endswith(
        "bytes, over the 255 a file system takes: give a shorter one"), lines[0]
    assert list(tmp_path.iterdir()) == []
