"""Fuzzing what every command reads with hostile input: integers of 400 and 5,000 digits,
arrays nested 3,000 deep, a NUL in a path, FIFOs with no writer, ``0.5_5`` and full-width
digits, a newline inside ``--set``, a 100,000-digit CSV cell.

The conventions of tests/cli/test_fuzz.py: cases ``(argv, fragment)``, run in this process;
each must give exactly one line on standard error with the fragment (at most ~200
characters, no warning), exit status 2, and write nothing.
"""
from __future__ import annotations

import importlib.util
import os
import sys
import threading
from pathlib import Path

import pytest
from cli_run import run_cli

from pollard_pin.cli import main

# one parser per module (tests/conftest.py): building one per case was a tenth of the time
pytestmark = pytest.mark.usefixtures("one_parser_per_module")

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
ACT = str(EXAMPLES / "actuators.toml")
HEADER = "t,x,y,z,psi,theta,phi"
B400, B5000 = "1" * 400, "1" * 5000
DEEP = "[" * 3000 + "]" * 3000
FIFOS = ("fifo.toml", "fifo.csv", "ws_fifo/workspace.csv")


def _files() -> dict[str, str]:
    rows = [",".join(r.split(",")[:7])
            for r in (EXAMPLES / "figure8.csv").read_text().splitlines()[1:13]]
    good = HEADER + "\n" + "\n".join(rows) + "\n"

    def cell(value: str) -> str:  # the second sample's time
        return good.replace("\n" + rows[1].split(",")[0] + ",", f"\n{value},", 1)

    job = (EXAMPLES / "paint.toml").read_text()
    act = (EXAMPLES / "actuators.toml").read_text()
    grid = "[grid]\n'chain0.x32' = [0.33]\n"
    film = "x,y,z,u,v,thickness\n" + "".join(
        f"0.55,{u},{v},{u},{v},2.5e-05\n" for v in (0, 0.1) for u in (0, 0.1))
    out = {
        "good.csv": good,
        "t_underscore.csv": cell("0.0_2"),
        "t_fullwidth.csv": cell("０.０２"),
        "t_huge_cell.csv": cell("1" * 100_000),
        # times in ms and more: the spline's squares overflowed (a RuntimeWarning line)
        "t_big_time.csv": HEADER + "\n" + "".join(
            f"{1e200 * (i + 1):g},{r.split(',', 1)[1]}\n" for i, r in enumerate(rows)),
        # subnormal steps: scipy's spline raised a ValueError (a traceback)
        "t_subnormal_dt.csv": HEADER + "\n" + "".join(
            f"{5e-324 * i!r},{r.split(',', 1)[1]}\n" for i, r in enumerate(rows)),
        "p_big.toml": f"[chain0]\nx32 = {B400}\n",
        "p_negative_big.toml": f"[bodies.gun]\ncom = [0, -{B400}, 0]\n",
        "p_digits.toml": f"[chain0]\nx32 = {B5000}\n",
        "p_deep.toml": f"[chain0]\nx32 = {DEEP}\n",
        "p_deep40.toml": "[chain0]\nx32 = " + "[" * 40 + "]" * 40 + "\n",
        "j_big.toml": job.replace("width = 0.26", f"width = {B400}"),
        "j_coats.toml": job + f"coats = {B400}\n",
        "j_digits.toml": job.replace("width = 0.26", f"width = {B5000}"),
        "j_deep.toml": job.replace("width = 0.26", f"width = {DEEP}"),
        "j_nul.toml": job + 'actuators = "a\\u0000b"\n',
        "a_big.toml": act.replace("gear_ratio = 100.0", f"gear_ratio = {B400}", 1),
        "a_digits.toml": act.replace("gear_ratio = 100.0", f"gear_ratio = {B5000}", 1),
        "a_deep.toml": act.replace("gear_ratio = 100.0", f"gear_ratio = {DEEP}", 1),
        "grid_ok.toml": f"trajectory = 'good.csv'\n{grid}",
        "g_big.toml": f"[grid]\n'chain0.x32' = [{B400}]\n",
        "g_digits.toml": f"[grid]\n'chain0.x32' = [{B5000}]\n",
        "g_deep.toml": f"[grid]\n'chain0.x32' = {DEEP}\n",
        "g_samples.toml": f"samples = {B400}\n{grid}",
        "g_duration.toml": f"duration = {B400}\n{grid}",
        "g_nul_trajectory.toml": f'trajectory = "a\\u0000b"\n{grid}',
        "g_nul_params.toml": f'params = "a\\u0000b"\n{grid}',
        "g_fifo_trajectory.toml": f"trajectory = 'fifo.csv'\n{grid}",
        "g_fifo_params.toml": f"params = 'fifo.toml'\n{grid}",
        "g_underscore_trajectory.toml": f"trajectory = 't_underscore.csv'\n{grid}",
        "j_fifo_actuators.toml": job + "actuators = 'fifo.toml'\n",
        # result tables and their units sidecars (plot/report --simulation, view --workspace)
        "sim_deep.csv": "t,theta21\n0,1\n1,2\n", "sim_deep.units.json": DEEP,
        "sim_list.csv": "t,theta21\n0,1\n1,2\n", "sim_list.units.json": "[1]",
        "sim_long_column.csv": f"t,{'x' * 100_000}\n0,1\n1,2\n",
        "ws_deep/workspace.csv": "x,y,z,reachable,conditioning\n0.55,0,0.16,1,0.3\n",
        "ws_deep/workspace.units.json": DEEP,
    }
    for name, report in (("paint_deep", '{"grid": {"nu": ' + DEEP + ', "nv": 2}, '
                                        '"target": 2.5e-05}'),
                         ("paint_big", '{"grid": {"nu": ' + B400 + ', "nv": 2}, '
                                       '"target": 2.5e-05}')):
        out.update({f"{name}/path.csv": good, f"{name}/thickness.csv": film,
                    f"{name}/paint.json": report})
    return out


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    root = tmp_path_factory.mktemp("fuzz_input")
    for name, content in _files().items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(content, encoding="utf-8")
    for name in FIFOS:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        os.mkfifo(root / name)
    stop = threading.Event()
    # A reader that blocks on a FIFO (the old code) is let go after 2 s by a writer that
    # sends nothing, so that a regression fails its case instead of hanging the suite.
    thread = threading.Thread(target=_unblock, args=([root / n for n in FIFOS], stop),
                              daemon=True)
    thread.start()
    yield root
    stop.set()
    thread.join()


def _unblock(fifos, stop: threading.Event) -> None:
    waited = {f: 0.0 for f in fifos}
    while not stop.wait(0.1):
        for f in fifos:
            try:
                fd = os.open(f, os.O_WRONLY | os.O_NONBLOCK)  # ENXIO while nobody reads
            except OSError:
                waited[f] = 0.0
                continue
            waited[f] += 0.1
            if waited[f] < 2.0:
                os.close(fd)
                continue
            os.close(fd)  # the reader now sees end of file
            waited[f] = 0.0


SHORT = ["--samples", "11", "--duration", "0.2"]
FIFO = "not a regular file (a FIFO)"
BEYOND = ": must be within the float range"
DIGITS = "an integer of more than 4300 digits"
NESTED = "nested more than 32 deep"

# parameter files and --set: every command that loads the model
MODEL = [["urdf", "--out", "out.urdf"], ["info"], ["export", "--out", "out.xml"],
         ["run", *SHORT, "--out", "out.csv"], ["view", *SHORT, "--html", "out.html"],
         ["plot", *SHORT, "--out", "plots"], ["report", *SHORT, "--out", "out.md"],
         ["size", *SHORT, "--actuators", ACT, "--out", "out.md"],
         ["simulate", "--trajectory", "good.csv", "--out", "out.csv"],
         ["paint", "--job", str(EXAMPLES / "paint.toml"), "--out", "p"],
         ["workspace", "--quiet", "--out", "ws"]]
BAD_PARAMS = [
    ("p_big.toml", f"'chain0.x32' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    ("p_negative_big.toml", "'bodies.gun.com[1]' = -1.111e+399"),
    ("p_digits.toml", DIGITS),
    ("p_deep.toml", NESTED),
    ("p_deep40.toml", "parameter file 'p_deep40.toml': 'chain0.x32' nests arrays or tables "
                      "more than 32 deep"),
    ("fifo.toml", f"parameter file 'fifo.toml' cannot be read: {FIFO}"),
]
CASES = [([*prefix, "--params", name], says)
         for prefix in MODEL for name, says in BAD_PARAMS]
BAD_SETS = [
    (f"chain0.x32={B400}", f"parameter 'chain0.x32' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    (f"home.tip=[0, -{B400}, 0]", f"parameter 'home.tip[1]' = -1.111e+399 (a 400-digit integer)"
                                  f"{BEYOND}"),
    (f"chain0.x32={B5000}", DIGITS),
    (f"chain0.x32={DEEP}", NESTED),
    ("chain0.x32=0.5_5", "'_' digit separators are not accepted"),
    ("chain0.x32=０.５５", "'０' is not an ASCII character"),
    ("chain0.x32=0.33\nchain0.x65=3", "a control character '\\n': one KEY=VALUE per override"),
    ("chain0.x32=0.33\rx", "a control character '\\r'"),
    ("home.tip=[0.5_5, 0, 0.16]", "digit separators"),
    (f"{'x' * 5000}=1", f"parameter '{'x' * 57}…' = 1: override names no parameter"),
    ("limits.theta21.lower=-1e300", "'limits.theta21.lower' = -1e+300: must be within ±720 deg"),
    # absurd bodies: the dynamics' squares overflowed (a RuntimeWarning line, or a pass)
    ("bodies.gun.mass=1e300", "'bodies.gun.mass' = 1e+300: must be at most 1000 kg"),
    ("bodies.gun.com=[1e300, 0, 0]", "'bodies.gun.com[0]' = 1e+300: must be within ±10 m"),
    ("bodies.gun.inertia=[[1e300, 0, 0], [0, 1e300, 0], [0, 0, 1e300]]",
     "'bodies.gun.inertia[0][0]' = 1e+300: must be within ±1e+11 kg·mm²"),
    ("limits.theta21.upper=1e300", "'limits.theta21.upper' = 1e+300: must be within ±720 deg"),
    ("limits.theta21.lower=-300", "'limits.theta21.lower' = -300, 'limits.theta21.upper' = "
                                  "-35: the range 265"),
]
del BAD_SETS[-1]  # -300..-35 is within one turn: see the range case below
BAD_SETS.append(("limits.theta1615.lower=-200", "'limits.theta1615.lower' = -200, "
                                                "'limits.theta1615.upper' = 270: the range 470"))
CASES += [([*prefix, "--set", text], says) for prefix in MODEL for text, says in BAD_SETS]

# paint jobs, and the actuator file a job names
PAINT = ["paint", "--out", "p", "--job"]
CASES += [([*PAINT, name], says) for name, says in [
    ("j_big.toml", f"'panel.width' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    ("j_coats.toml", f"'job.coats' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    ("j_digits.toml", DIGITS),
    ("j_deep.toml", NESTED),
    ("j_nul.toml", "'job.actuators' = 'a\\x00b': a path with a NUL character"),
    ("j_fifo_actuators.toml", f"fifo.toml' cannot be read: {FIFO}"),
    ("fifo.toml", f"paint job file 'fifo.toml' cannot be read: {FIFO}"),
]]

# actuator files: every command that reads one
ACTUATED = [["size", *SHORT, "--out", "out.md"],
            ["simulate", "--trajectory", "good.csv", "--out", "out.csv"],
            ["paint", "--job", str(EXAMPLES / "paint.toml"), "--out", "p"],
            ["workspace", "--quiet", "--out", "ws"]]
CASES += [([*prefix, "--actuators", name], says) for prefix in ACTUATED for name, says in [
    ("a_big.toml", f"'theta21.gear_ratio' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    ("a_digits.toml", DIGITS),
    ("a_deep.toml", NESTED),
    ("fifo.toml", f"actuator file 'fifo.toml' cannot be read: {FIFO}"),
]]

# sweep grids, and the files a grid names
SWEEP = ["sweep", "--out", "out.csv", "--workers", "1", "--grid"]
CASES += [([*SWEEP, name], says) for name, says in [
    ("g_big.toml", f"'grid.chain0.x32[0]' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    ("g_digits.toml", DIGITS),
    ("g_deep.toml", NESTED),
    ("g_samples.toml", f"'samples' = 1.111e+399 (a 400-digit integer){BEYOND}"),
    ("g_duration.toml", BEYOND),
    ("g_nul_trajectory.toml", "path = 'a\\x00b': a path with a NUL character"),
    ("g_nul_params.toml", "params: path = 'a\\x00b': a path with a NUL character"),
    ("g_fifo_trajectory.toml", FIFO),
    ("g_fifo_params.toml", FIFO),
    ("g_underscore_trajectory.toml", "'0.0_2' is not a number ('_' digit separators"),
    ("fifo.toml", f"grid file 'fifo.toml' cannot be read: {FIFO}"),
]]

# trajectory CSVs: every command that reads one
TRAJ = [["run", "--out", "out.csv"], ["view", "--html", "out.html"], ["plot", "--out", "plots"],
        ["report", "--no-cross-check", "--out", "out.md"],
        ["size", "--actuators", ACT, "--out", "out.md"], ["simulate", "--out", "out.csv"]]
CASES += [([*prefix, "--trajectory", name], says) for prefix in TRAJ for name, says in [
    ("fifo.csv", f"cannot read trajectory file 'fifo.csv': {FIFO}"),
    ("t_underscore.csv", "row 3, column 't': '0.0_2' is not a number ('_' digit separators "
                         "are not accepted)"),
    ("t_fullwidth.csv", "row 3, column 't': '０.０２' is not a number ('０' is not an ASCII"),
    ("t_huge_cell.csv", "row 3, column 't': value '1111111111"),
    ("t_big_time.csv", "row 2, column 't': 1e+200 s is beyond ±1e+06 s (seconds, not ms?)"),
    ("t_subnormal_dt.csv", "row 3, column 't': time step too small: 5e-324 after 0.0 is "
                           "4.94e-324 s, below 1e-09 s"),
]]

# a device never ends: read whole, it filled the memory
if os.path.exists("/dev/zero"):
    CASES += [(["info", "--params", "/dev/zero"], "cannot be read: not a regular file (a device)"),
              (["run", "--out", "out.csv", "--trajectory", "/dev/zero"], "(a device)"),
              ([*PAINT, "/dev/zero"], "(a device)"),
              ([*SWEEP, "/dev/zero"], "(a device)"),
              (["size", *SHORT, "--out", "out.md", "--actuators", "/dev/zero"], "(a device)")]

# result tables and folders that view, plot and report read
CASES += [
    (["plot", "--out", "plots", "--simulation", "fifo.csv"], "not a regular file"),
    (["report", *SHORT, "--out", "out.md", "--simulation", "fifo.csv"], "not a regular file"),
    (["view", *SHORT, "--html", "out.html", "--workspace", "ws_fifo"], "no workspace.csv"),
    (["view", *SHORT, "--html", "out.html", "--workspace", "ws_deep"],
     "ws_deep/workspace.units.json: not a readable units sidecar (maximum recursion depth"),
    *(([*prefix, "--simulation", name], says) for prefix in (["plot", "--out", "plots"],
                                                              ["report", *SHORT, "--out", "out.md"])
      for name, says in [
          ("sim_deep.csv", "sim_deep.units.json: not a readable units sidecar (maximum "
                           "recursion depth exceeded"),
          ("sim_list.csv", "sim_list.units.json: not a readable units sidecar (expected a JSON "
                           "object)"),
          ("sim_long_column.csv", f"column '{'x' * 57}…' is not one pollard-pin writes")]),
    (["view", "--html", "out.html", "--paint", "paint_deep"],
     "paint_deep/paint.json: not a paint report (maximum recursion depth exceeded"),
    (["view", "--html", "out.html", "--paint", "paint_big"],
     "paint_big/paint.json: not a paint report ('grid.nu' = 1.111e+399 (a 400-digit integer): "
     "must be a count of at most 1e+15)"),
]

# numbers on the command line: Python's float() and int() take more than a user means
CASES += [([*prefix, option, value], says) for prefix, option, value, says in [
    (["run", "--out", "out.csv", "--samples", "11"], "--duration", "0.5_5",
     "argument --duration: not a number: '0.5_5' ('_' digit separators are not accepted)"),
    (["run", "--out", "out.csv", "--samples", "11"], "--duration", "０.５",
     "argument --duration: not a number: '０.５' ('０' is not an ASCII digit)"),
    (["run", "--out", "out.csv", *SHORT], "--wrist-margin", "0.0_1", "digit separators"),
    (["run", "--out", "out.csv", *SHORT], "--singularity-margin", "１", "ASCII"),
    (["view", "--html", "out.html", *SHORT], "--fps", "2_5", "digit separators"),
    (["simulate", "--trajectory", "good.csv", "--out", "out.csv"], "--wn", "1_0",
     "digit separators"),
    (["run", "--out", "out.csv", "--duration", "0.2"], "--samples", "1_1",
     "argument --samples: not an integer: '1_1'"),
    (["run", "--out", "out.csv", "--duration", "0.2"], "--samples", "１１", "not an integer"),
    (["run", "--out", "out.csv", "--duration", "0.2"], "--samples", B5000,
     "must be a sane count >= 2, got a 5000-digit number"),
    (["run", "--out", "out.csv", "--samples", "11"], "--duration", B5000,
     "argument --duration: must be a finite number, got '111"),
    (["workspace", "--quiet", "--out", "ws"], "--orientation", "-10,0,1e300",
     "--orientation '-10,0,1e300': orientation phi = 1e+300 deg is absurd"),
    (["workspace", "--quiet", "--out", "ws"], "--orientation", "-10,abc,0",
     "expected three finite numbers"),
    (["workspace", "--quiet", "--out", "ws"], "--orientation", "-1_0,0,0",
     "expected three finite numbers"),
    (["simulate", "--trajectory", "good.csv", "--out", "out.csv"], "--mass-error", "-1_0",
     "digit separators"),
]]
# a plant that runs away: named once, no numpy warning, no banner
CASES += [(["simulate", "--trajectory", "good.csv", "--out", "out.csv", option, "1e300"],
           "simulation diverged at t = 0.001 s") for option in ("--viscous", "--coulomb")]
# an empty or malformed scheduler address
CASES += [([*SWEEP, "grid_ok.toml", "--dask", address], "argument --dask: an empty scheduler "
           "address")
          for address in ("", "  ")]
if importlib.util.find_spec("distributed") is not None:
    CASES += [([*SWEEP, "grid_ok.toml", "--dask", "tcp://"],
               "argument --dask: not a scheduler address: 'tcp://' (missing port number")]
IDS = [" ".join(a if len(a) <= 40 else f"{a[:30]}…({len(a)})" for a in argv)
       for argv, _ in CASES]


def _listing(root: Path) -> dict:
    out = {}
    for folder, dirs, files in os.walk(root):
        for f in files:
            p = Path(folder, f)
            out[str(p)] = p.stat().st_mtime_ns if p.is_file() else None
        out.update((str(Path(folder, d)), True) for d in dirs)
    return out


@pytest.mark.parametrize("argv, says", CASES, ids=IDS)
def test_hostile_input_gives_one_short_line_exit_2_and_writes_nothing(scratch, monkeypatch,
                                                                       capsys, argv, says):
    monkeypatch.chdir(scratch)
    before = _listing(scratch)
    code, out, err = run_cli(argv, capsys)
    lines = err.strip().splitlines()
    assert code == 2, (code, out[-300:], err[-2000:])
    assert out == "", out[:300]
    assert len(lines) == 1 and lines[0].startswith("pollard-pin"), err[-2000:]
    assert says in lines[0], lines[0]
    assert len(lines[0]) <= 250 and "Warning" not in err, lines[0]
    assert _listing(scratch) == before


def test_the_cases_are_many_and_distinct():
    assert len(CASES) >= 200 and len(set(IDS)) == len(IDS)


# --- messages -------------------------------------------------------------------------------
def test_a_missing_dask_extra_is_the_only_line(tmp_path, monkeypatch, capsys):
    # the banner "N variants on Dask cluster ..." came before the missing-extra error
    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed → ImportError
    code, out, err = run_cli(["sweep", "--grid", EXAMPLES / "sweep.toml", "--out", "s.csv",
                              "--dask", "tcp://127.0.0.1:1"], capsys)
    assert code == 2 and err.strip().splitlines() == [
        "pollard-pin sweep: error: a Dask scheduler needs dask.distributed: pip install "
        "'pollard-pin[cluster]' (nothing written to s.csv)"], err
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("argv, hint", [(["info", "--set", "chain0.x32=0.33"], False),
                                        (["run", "--samples", "11", "--out", "-"], True)])
def test_the_fewer_samples_hint_only_where_there_is_a_samples_option(monkeypatch, capsys, argv,
                                                                      hint):
    import pollard_pin.model.build as build

    def no_memory(*args, **kwargs):
        raise MemoryError

    monkeypatch.setattr(build, "load", no_memory)
    code, _, err = run_cli(argv, capsys)
    assert code == 2 and ("fewer samples?" in err) == hint, err
    assert err.strip().splitlines() == [f"pollard-pin {argv[0]}: error: not enough memory "
                                        f"(MemoryError){': fewer samples?' if hint else ''}"]


@pytest.mark.parametrize("argv", [["--orientation", "-10,0,0"], ["--orientation", "-10,-5,3"]])
def test_negative_comma_lists_are_values_not_options(tmp_path, monkeypatch, argv):
    # "expected one argument": only --orientation=-10,0,0 worked
    from pollard_pin.cli.main import build_parser

    monkeypatch.chdir(tmp_path)
    args = build_parser().parse_args(["workspace", *argv])
    assert args.orientation == argv[1]


def test_a_good_run_still_reads_its_files(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    Path("good.csv").write_text(_files()["good.csv"])
    Path("p.toml").write_text("[chain0]\nx32 = 0.33\n[limits.theta21]\nlower = -105\n")
    assert main(["run", "--trajectory", "good.csv", "--params", "p.toml", "--set",
                 "home.tip=[0.55, 0, 0.16]", "--out", "out.csv"]) == 0
    assert "wrote out.csv (12 rows)" in capsys.readouterr().err
