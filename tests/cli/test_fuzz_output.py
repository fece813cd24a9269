"""Fuzzing what every command WRITES (the conventions of test_fuzz.py): a full device, dangling
and looping links, an output that fails half-way through a command's outputs, two outputs
naming one file, and the folders ``view`` reads back. Each case must give exactly one line on
standard error, exit status 2, no traceback, and write nothing (the scratch folder unchanged,
links included). Then: stale outputs of the other format, a link written through, and text
output on an ASCII terminal (in this process, and once in a fresh interpreter)."""
from __future__ import annotations

import errno
import io
import os
import subprocess
import sys
from pathlib import Path

import pytest
from cli_run import run_cli, tree_state

from pollard_pin.cli import main

# one parser per module (tests/conftest.py): building one per case was a tenth of the time
pytestmark = pytest.mark.usefixtures("one_parser_per_module")

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
ACT = str(EXAMPLES / "actuators.toml")
JOB = str(EXAMPLES / "paint.toml")
# the same job on a 5 × 3 cm panel (small.toml): 4 passes, planned in a quarter of the time
SMALL_JOB = (EXAMPLES / "paint.toml").read_text().replace("width = 0.26", "width = 0.05", 1) \
    .replace("height = 0.12", "height = 0.03", 1)
SHORT = ["--samples", "11", "--duration", "0.2"]
# size on a short path: its time-optimal grid follows the path's length, not the samples
# (the thesis curve, even at 11 samples, took 1.5 s before a write failed)
SIZE = ["size", "--trajectory", "good.csv", "--actuators", ACT]
PRECIOUS = b"precious: a failed command must leave this untouched\n"
FULL = "/dev/full: cannot write: no space left on device"
HAS_FULL = os.path.exists("/dev/full")


def _good() -> str:
    lines = (EXAMPLES / "figure8.csv").read_text().splitlines()[:13]
    return "\n".join(",".join(line.split(",")[:7]) for line in lines) + "\n"


WS_HEADER = "x,y,z,psi,theta,phi,reachable,reason,conditioning\n"
FILM = "x,y,z,u,v,thickness\n" + "".join(f"0.55,{u},{v},{u},{v},2.5e-05\n"
                                          for v in (0, 0.1) for u in (0, 0.1))
REPORT = '{"grid": {"nu": 2, "nv": 2, "resolution": 0.1}, "target": 2.5e-05}\n'


def _files() -> dict:
    def paint(name, film=FILM, extra=None):
        out = {f"{name}/path.csv": _good(), f"{name}/thickness.csv": film,
               f"{name}/paint.json": REPORT}
        if extra:
            out[f"{name}/{extra}"] = b"PAR1garbage"
        return out

    return {
        "good.csv": _good(),
        "grid.toml": "trajectory = 'good.csv'\n[grid]\n'chain0.x32' = [0.33]\n",
        "existing.md": PRECIOUS, "existing.csv": PRECIOUS,
        # outputs a command checks only once some are written (before the fix)
        "P/paint.json/": None, "P/path.csv": PRECIOUS, "P/thickness.csv": PRECIOUS,
        "pl/joint_loads.png/": None, "x.srdf/": None, "ws/workspace.png/": None,
        "ws/workspace.csv": PRECIOUS, "r.units.json/": None, "pp/torque_speed.png/": None,
        "sim.units.json/": None, "F/": None,
        # view's folders, each damaged in one way
        "W_reach2/workspace.csv": WS_HEADER + "0.55,0,0.16,0,0,0,2,0,0.3\n",
        "W_cond/workspace.csv": WS_HEADER + "0.55,0,0.16,0,0,0,1,0,1.5\n",
        "W_far/workspace.csv": WS_HEADER + "0.55,0,0.16,0,0,0,1,0,0.3\n"
                                           "1e300,0,0.16,0,0,0,1,0,0.3\n",
        "W_both/workspace.csv": WS_HEADER + "0.55,0,0.16,0,0,0,1,0,0.3\n",
        "W_both/workspace.parquet": b"PAR1garbage",
        **paint("P_neg", FILM.replace("2.5e-05", "-2.5e-05")),
        **paint("P_far", FILM.replace("0.55,0.1,0.1", "-1e300,0.1,0.1")),
        **paint("P_both", extra="thickness.parquet"),
    }


LINKS = {"dang.out": "nowhere/x", "loop.out": "loop.out", "dangdir": "nowhere",
         "loopdir": "loopdir", "link.md": "existing.md"}


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    root = tmp_path_factory.mktemp("fuzz_output")
    for name, content in _files().items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        if name.endswith("/"):
            (root / name).mkdir(exist_ok=True)
        elif isinstance(content, bytes):
            (root / name).write_bytes(content)
        else:
            (root / name).write_text(content, encoding="utf-8")
    for name, target in LINKS.items():
        os.symlink(target, root / name)
    return root


# --- the cases ---------------------------------------------------------------------------------
def _file_commands(out: str) -> dict:
    """Every command writing one file, writing it to ``out``."""
    return {
        "run": ["run", *SHORT, "--out", out],
        "size": [*SIZE, "--out", out],
        "size-retime": [*SIZE, "--out", "s.md", "--retime", out],
        "simulate": ["simulate", "--quiet", "--trajectory", "good.csv", "--out", out],
        "sweep": ["sweep", "--workers", "1", "--quiet", "--grid", "grid.toml", "--out", out],
        "report": ["report", *SHORT, "--no-cross-check", "--out", out],
        "urdf": ["urdf", "--out", out],
        "export": ["export", "--out", out],
        "view": ["view", *SHORT, "--html", out],
        "stiffness": ["stiffness", *SHORT, "--actuators", ACT, "--out", out],
    }


def _folder_commands(out: str) -> dict:
    return {
        "paint": ["paint", "--job", JOB, "--resolution", "0.01", "--out", out],
        "workspace": ["workspace", "--quiet", "--resolution", "0.05", "--out", out],
        "plot": ["plot", *SHORT, "--out", out],
        "size-plot": [*SIZE, "--out", "s.md", "--plot", out],
    }


CASES = []
# 1. a full device: one line naming it and why (each command did its work, then a traceback)
if HAS_FULL:
    CASES += [(argv, FULL) for argv in _file_commands("/dev/full").values()]
    # the retimed trajectory was written, then the report failed
    CASES += [([*SIZE, "--retime", "R.csv", "--out", "/dev/full"], FULL)]
    # without --quiet too: the banner rides the progress bar, on a terminal only
    CASES += [(["simulate", "--trajectory", "good.csv", "--out", "/dev/full"], FULL),
              (["sweep", "--workers", "1", "--grid", "grid.toml", "--out", "/dev/full"], FULL)]
# 2. links that lead nowhere: refused before any work, the link left alone
for out, says in (("dang.out", "dang.out: a dangling symbolic link (to nowhere/x)"),
                  ("loop.out", "loop.out: a symbolic link loop")):
    CASES += [(argv, says) for argv in _file_commands(out).values()]
for out, says in (("dangdir", "dangdir: a dangling symbolic link (to nowhere)"),
                  ("loopdir", "loopdir: a symbolic link loop")):
    CASES += [(argv, says) for argv in _folder_commands(out).values()]
CASES += [(["run", *SHORT, "--out", "dangdir/run.csv"], "dangdir is a dangling symbolic link")]
# 4. one output that cannot be written among several: refused before any is written
CASES += [
    (["paint", "--job", JOB, "--resolution", "0.01", "--out", "P"], "P/paint.json: is a folder"),
    (["plot", *SHORT, "--out", "pl"], "pl/joint_loads.png: is a folder"),
    (["urdf", "--out", "x.urdf"], "x.srdf: is a folder"),
    (["workspace", "--quiet", "--resolution", "0.05", "--out", "ws"],
     "ws/workspace.png: is a folder"),
    (["run", *SHORT, "--out", "r.csv"], "r.units.json: is a folder"),
    (["simulate", "--trajectory", "good.csv", "--out", "sim.csv"], "sim.units.json: is a folder"),
    ([*SIZE, "--out", "s.md", "--plot", "pp"], "pp/torque_speed.png: is a folder"),
    ([*SIZE, "--out", "s.md", "--retime", "r.csv"], "r.units.json: is a folder"),
]
# 5. two outputs naming one file: one would overwrite the other
CASES += [(argv, "named by two outputs") for argv in [
    [*SIZE, "--out", "X.csv", "--retime", "X.csv"],
    [*SIZE, "--out", "./X.csv", "--retime", "X.csv"],
    [*SIZE, "--out", "F/../X.csv", "--retime", "X.csv"],
    [*SIZE, "--out", "link.md", "--retime", "existing.md"],
    [*SIZE, "--out", "a.units.json", "--retime", "a.csv"],  # the retimed table's sidecar
    [*SIZE, "--out", "F/torque_speed.png", "--plot", "F"],
    ["urdf", "--out", "u.srdf"],
]]
# 7. view's folders: values no command writes
VIEW = ["view", *SHORT, "--html", "v.html"]
CASES += [
    ([*VIEW, "--workspace", "W_reach2"], "W_reach2/workspace.csv: row 1: reachable = 2, "
                                          "expected 0 or 1"),
    ([*VIEW, "--workspace", "W_cond"], "W_cond/workspace.csv: row 1: conditioning = 1.5"),
    ([*VIEW, "--workspace", "W_far"], "W_far/workspace.csv: row 2: point (1e+300, 0, 0.16) m "
                                      "is beyond ±1000 m"),
    ([*VIEW, "--workspace", "W_both"], "holds both workspace.csv and workspace.parquet"),
    (["view", "--html", "v.html", "--paint", "P_neg"], "P_neg/thickness.csv: row 1: "
                                                       "thickness = -2.5e-05 m, below 0"),
    (["view", "--html", "v.html", "--paint", "P_far"], "P_far/thickness.csv: row 4: point "
                                                       "(-1e+300, 0.1, 0.1) m is beyond ±1000"),
    (["view", "--html", "v.html", "--paint", "P_both"], "holds both thickness.csv and "
                                                        "thickness.parquet"),
    ([*VIEW, "--fps", "1e-300"], "--fps 1e-300: 1e-300 key frames/s is below the least of 1"),
    ([*VIEW, "--fps", "0.5"], "0.5 key frames/s is below the least of 1"),
]
IDS = [" ".join(argv) for argv, _ in CASES]


@pytest.mark.parametrize("argv, says", CASES, ids=IDS)
def test_a_bad_output_gives_one_line_exit_2_and_writes_nothing(scratch, monkeypatch, capsys,
                                                               argv, says):
    monkeypatch.chdir(scratch)
    before = tree_state(scratch)
    code, out, err = run_cli(argv, capsys)
    lines = err.strip().splitlines()
    assert code == 2, (code, out[-300:], err[-2000:])
    assert out == "", out[:300]
    assert len(lines) == 1 and lines[0].startswith("pollard-pin"), err[-2000:]
    assert says in lines[0] and "Traceback" not in err, lines[0]
    assert tree_state(scratch) == before


def test_every_writing_command_has_cases():
    assert len(set(IDS)) == len(IDS)
    commands = {argv[0] for argv, _ in CASES}
    assert commands >= {"run", "size", "simulate", "sweep", "report", "urdf", "export", "view",
                        "paint", "workspace", "plot"}, commands


# --- a write that fails half-way: every output stays as it was -------------------------------
def _no_space(*args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


@pytest.mark.parametrize("argv, module, writer, says", [
    (["paint", "--job", "small.toml", "--resolution", "0.01", "--out", "out"],
     "pollard_pin.viz.paint",
     "thickness_figure", "thickness.png: cannot write: no space left on device"),
    (["workspace", "--quiet", "--resolution", "0.05", "--out", "out"],
     "pollard_pin.viz.workspace", "workspace_figure", "workspace.png: cannot write"),
    (["plot", *SHORT, "--out", "out"], "pollard_pin.viz.plots", "_loads_figure",
     "joint_loads.png: cannot write"),
    (["urdf", "--out", "out/m.urdf"], None, None, "m.urdf: cannot write"),
])
def test_a_failure_in_the_last_output_leaves_every_output_as_it_was(tmp_path, monkeypatch,
                                                                    capsys, argv, module,
                                                                    writer, says):
    # the figure (urdf: the URDF, after its SRDF) is written last; the files before it were left new
    monkeypatch.chdir(tmp_path)
    (tmp_path / "small.toml").write_text(SMALL_JOB)
    (tmp_path / "out").mkdir()
    for name in ("path.csv", "thickness.csv", "paint.json", "workspace.csv", "workspace.json",
                 "chain0_joints.png", "m.urdf", "m.srdf"):
        (tmp_path / "out" / name).write_bytes(PRECIOUS)
    before = tree_state(tmp_path)

    def failing_savefig(fig, f, **kwargs):
        f.write(b"half a figure")
        _no_space()

    import pollard_pin.io.atomic as atomic

    if module is not None:
        import importlib

        mod = importlib.import_module(module)
        make = getattr(mod, writer)

        def broken(*args, **kwargs):
            fig = make(*args, **kwargs)
            fig.savefig = lambda f, **kw: failing_savefig(fig, f, **kw)
            return fig

        monkeypatch.setattr(mod, writer, broken)
        # the figures before it are written as a few bytes, not drawn (plot drew nine for 3 s):
        # what is tested is that they are put back, not what they show
        from matplotlib.figure import Figure

        monkeypatch.setattr(Figure, "savefig", lambda fig, f, **kw: f.write(b"a figure\n"))
    else:
        real = atomic.atomic_open

        def urdf_fails(path, *args, **kwargs):  # the URDF is written after the SRDF
            if str(path).endswith(".urdf"):
                return real("/dev/full", *args, **kwargs) if HAS_FULL else _no_space()
            return real(path, *args, **kwargs)

        if not HAS_FULL:
            pytest.skip("no /dev/full")
        monkeypatch.setattr("pollard_pin.cli.urdf.atomic_open", urdf_fails)
    code, out, err = run_cli(argv, capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and "Traceback" not in err, err[-2000:]
    assert (says if module else "/dev/full: cannot write") in lines[0], lines[0]
    assert tree_state(tmp_path) == before


# --- stale outputs of the other format ----------------------------------------------------------
@pytest.mark.parametrize("argv, stem", [
    (["workspace", "--quiet", "--resolution", "0.05"], "workspace"),
    (["paint", "--job", "small.toml", "--resolution", "0.01"], "thickness"),
])
def test_a_second_run_in_the_other_format_replaces_the_first(tmp_path, monkeypatch, capsys,
                                                             argv, stem):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "small.toml").write_text(SMALL_JOB)
    for fmt, gone in (("parquet", ("csv", "units.json")), ("csv", ("parquet",))):
        code, _, err = run_cli([*argv, "--out", "D", "--format", fmt], capsys)
        assert code == 0, err
        assert (tmp_path / "D" / f"{stem}.{fmt}").is_file()
        for ext in gone:  # the old code left both tables: view drew the older one
            assert not (tmp_path / "D" / f"{stem}.{ext}").exists(), ext
    what = "--workspace" if stem == "workspace" else "--paint"
    code, _, err = run_cli(["view", *(SHORT if stem == "workspace" else []), "--html",
                            "v.html", what, "D"], capsys)
    assert code == 0, err


def test_a_volume_map_replaces_a_plane_map_figure(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert run_cli(["workspace", "--quiet", "--resolution", "0.05", "--out", "D"], capsys)[0] == 0
    code, _, err = run_cli(["workspace", "--quiet", "--volume", "--resolution", "0.1", "--out",
                            "D"], capsys)
    assert code == 0, err
    assert sorted(os.listdir("D")) == ["workspace.csv", "workspace.json", "workspace.units.json"]


# --- links written through ----------------------------------------------------------------------
def test_a_link_to_a_file_is_written_through(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    Path("data").mkdir()
    Path("data/real.urdf").write_bytes(PRECIOUS)
    os.symlink("data/real.urdf", "link.urdf")
    code, _, err = run_cli(["urdf", "--out", "link.urdf"], capsys)
    assert code == 0, err
    assert os.path.islink("link.urdf")  # the old code replaced the link by a file
    assert Path("data/real.urdf").read_text().startswith("<?xml")
    assert Path("link.srdf").is_file()


def test_a_urdf_to_a_device_writes_no_srdf_beside_it(tmp_path, monkeypatch, capsys):
    # the old code created /dev/null.srdf (a regular file among the devices, as root)
    monkeypatch.chdir(tmp_path)
    os.mkfifo("pipe.urdf")
    reader = os.open("pipe.urdf", os.O_RDONLY | os.O_NONBLOCK)
    try:
        code, out, err = run_cli(["urdf", "--out", "pipe.urdf"], capsys)
        assert code == 0, err
        assert os.read(reader, 5) == b"<?xml"
    finally:
        os.close(reader)
    assert sorted(os.listdir(tmp_path)) == ["pipe.urdf"]
    assert "no SRDF beside a device or FIFO" in out


# --- a FIFO that no one reads: one line, not a hang -------------------------------------------
def test_a_fifo_that_no_one_reads_is_one_line(tmp_path, monkeypatch, capsys):
    import pollard_pin.io.atomic as atomic

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(atomic, "FIFO_WAIT", 0.05)
    os.mkfifo("fifo.csv")
    code, out, err = run_cli(["run", *SHORT, "--out", "fifo.csv"], capsys)
    assert code == 2 and out == "" and err.strip().splitlines() == [
        "pollard-pin run: error: fifo.csv: a FIFO that no one reads (none opened it in 0.05 s): "
        "start its reader first (nothing written to fifo.csv)"], err
    assert sorted(os.listdir(tmp_path)) == ["fifo.csv"]


def test_a_fifo_whose_reader_comes_late_is_written(tmp_path, monkeypatch, capsys):
    import threading

    monkeypatch.chdir(tmp_path)
    os.mkfifo("fifo.csv")
    got = []

    def reader():
        import time

        time.sleep(0.2)  # after the writer's first try
        with open("fifo.csv", "rb") as f:
            got.append(f.read())

    thread = threading.Thread(target=reader, daemon=True)  # never holds pytest at exit
    thread.start()
    code, _, err = run_cli(["run", *SHORT, "--out", "fifo.csv", "--quiet"], capsys)
    thread.join(timeout=60)
    assert code == 0, err
    assert got and got[0].startswith(b"t,x,y,z,") and got[0].count(b"\n") == 12  # header + 11


# --- text on a terminal that cannot show θ, µ, σ --------------------------------------------
def _cli(args, cwd, **env):
    return subprocess.run([sys.executable, "-m", "pollard_pin.cli", *args], cwd=cwd,
                          env={**os.environ, "PYTHONPATH": str(ROOT), **env},
                          capture_output=True, timeout=300)


def _on_an_ascii_terminal(argv, monkeypatch) -> tuple[int, bytes, bytes]:
    """(exit code, standard output, standard error) of ``pollard-pin argv`` run in this
    process with both streams strict ASCII text, as Python makes them under
    PYTHONIOENCODING=ascii (a fresh interpreter costs a second of imports per case)."""
    out, err = (io.TextIOWrapper(io.BytesIO(), encoding="ascii", errors="strict")
                for _ in range(2))
    with monkeypatch.context() as m:
        m.setattr(sys, "stdout", out)
        m.setattr(sys, "stderr", err)
        try:
            code = main([str(a) for a in argv])
        except SystemExit as exc:  # --help
            code = exc.code
        out.flush()
        err.flush()
    return code, out.buffer.getvalue(), err.buffer.getvalue()


@pytest.mark.parametrize("argv, says", [
    (["paint", "--job", "small.toml", "--resolution", "0.01", "--out", "p"],
     rb" \xb5m (target 25 \xb5m"),
    (["run", *SHORT, "--out", "r.csv"], rb"\u03c3_min parallel"),
    # the report is UTF-8 like any file the commands write (io.atomic): no escapes
    ([*SIZE], "τm = τ/N".encode()),
    (["sweep", "--help"], rb"trajectory \u2192 CSV"),
])
def test_an_ascii_terminal_gets_escapes_not_a_crash(tmp_path, monkeypatch, argv, says):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "small.toml").write_text(SMALL_JOB)
    (tmp_path / "good.csv").write_text(_good())
    code, out, err = _on_an_ascii_terminal(argv, monkeypatch)
    assert code == 0 and b"Traceback" not in err, err[-2000:]
    assert says in out + err, (out + err)[-2000:]  # θ, µ, … as backslash escapes
    if argv[0] == "paint":  # the files are written whatever the terminal
        assert (tmp_path / "p" / "thickness.png").is_file()


class _StrictAscii(io.StringIO):
    """A text stream that cannot be reconfigured and refuses what ASCII cannot encode."""

    encoding = "ascii"

    def write(self, text):
        text.encode("ascii")  # UnicodeEncodeError, as a strict stream's
        return super().write(text)

    def reconfigure(self, **kwargs):
        raise AttributeError("reconfigure")


def test_a_stream_that_cannot_show_the_text_is_one_line_and_exit_2(tmp_path, monkeypatch):
    # the work is done, the file written; the summary cannot be shown: the status says so
    monkeypatch.chdir(tmp_path)
    err = io.StringIO()
    monkeypatch.setattr(sys, "stdout", _StrictAscii())
    monkeypatch.setattr(sys, "stderr", err)
    code = main(["run", *SHORT, "--out", "r.csv"])
    assert code == 2 and err.getvalue().splitlines() == [
        "pollard-pin run: error: standard output cannot show '\\u03b8' in ascii: set "
        "PYTHONIOENCODING=utf-8"], err.getvalue()


def test_an_ascii_terminal_gets_escapes_in_a_fresh_interpreter(tmp_path):
    # end to end: the streams Python itself opens for PYTHONIOENCODING=ascii, and their
    # flush at exit
    done = _cli(["run", *SHORT, "--out", "r.csv"], tmp_path, PYTHONIOENCODING="ascii")
    assert done.returncode == 0 and b"Traceback" not in done.stderr, done.stderr[-2000:]
    assert rb"\u03c3_min parallel" in done.stdout, done.stdout[-2000:]
    assert (tmp_path / "r.csv").is_file()


@pytest.mark.parametrize("redirect", [">&-", ">&- 2>&-"])
def test_a_closed_standard_output_is_one_line_before_any_work(tmp_path, redirect):
    # nowhere to say the summary: refused before the work
    done = subprocess.run(f"{sys.executable} -m pollard_pin.cli run --samples 11 --duration "
                          f"0.2 --out r.csv {redirect}", shell=True, cwd=tmp_path,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, stderr=subprocess.PIPE,
                          timeout=300)
    said = [] if "2>&-" in redirect else ["pollard-pin run: error: standard output is closed: "
                                          "give it a file or /dev/null"]
    assert done.returncode == 2 and done.stderr.decode().splitlines() == said, done.stderr
    assert not list(tmp_path.iterdir())


@pytest.mark.skipif(not HAS_FULL, reason="no /dev/full")
def test_standard_output_on_a_full_device_is_one_line(tmp_path):
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "pollard_pin.cli", "urdf", "--out", "-"],
                              cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(ROOT)},
                              stdout=full, stderr=subprocess.PIPE, timeout=300)
    lines = done.stderr.decode().strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr[-2000:]
    assert lines[0] == ("pollard-pin urdf: error: standard output: cannot write: no space "
                        "left on device")
