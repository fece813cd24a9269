"""`pollard-pin place`: the placement printed and written as a job that `paint` runs as
is; bad inputs one line, exit 2, nothing written."""
import re
from pathlib import Path

from cli_run import run_cli

from pollard_pin.painting.job import load_job

ROOT = Path(__file__).resolve().parents[2]
PART = ROOT / "examples" / "parts" / "ribbed_plate.toml"


def test_place_writes_a_job_paint_runs(tmp_path, capsys):
    out = tmp_path / "placed.toml"
    code, text, err = run_cli(["place", "--job", PART, "--out", out, "--max-turn", "0"],
                              capsys)
    assert code == 0, err
    m = re.search(r"position \[(\S+), (\S+), (\S+)\] m, .*margin (\d+) mm", text)
    assert m, text
    job = load_job(out)
    assert all(abs(a - float(m.group(i + 1))) <= 5e-5 for i, a in enumerate(job.position))
    assert int(m.group(4)) >= 30  # ribbed_plate: 83 mm
    assert Path(job.mesh).samefile(load_job(PART).mesh)
    # compliance not asserted here (tests/painting/checks/test_compliance.py checks it)
    code, text, err = run_cli(["paint", "--job", out, "--out", tmp_path / "paint",
                               "--resolution", "0.01", "--no-compliance"], capsys)
    assert code == 0, err
    mean = float(re.search(r"mean (\S+) µm", text).group(1))
    assert abs(mean / 25 - 1) < 0.05, text  # the target 25 µm


def _refused(argv, capsys, tmp_path, fragment):
    before = sorted(p.name for p in tmp_path.iterdir())
    code, text, err = run_cli(argv, capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and fragment in lines[0], err
    assert len(lines[0]) <= 250 + len("pollard-pin place: error: ") + 60
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_bad_inputs(tmp_path, capsys):
    job = tmp_path / "job.toml"
    job.write_text(PART.read_text().replace('"ribbed_plate.obj"',
                                            f'"{(PART.parent / "ribbed_plate.obj").as_posix()}"'))
    _refused(["place", "--job", ROOT / "examples" / "paint.toml", "--out", tmp_path / "o.toml"],
             capsys, tmp_path, "a [panel] job; place moves a [part]'s mesh")
    _refused(["place", "--job", job, "--out", job], capsys, tmp_path, "is one of the inputs")
    _refused(["place", "--job", tmp_path / "none.toml"], capsys, tmp_path, "none.toml")
    _refused(["place", "--job", job, "--step", "0.5"], capsys, tmp_path,
             "--step: 0.5: expected a number in [0.001, 0.2]")


def test_a_cell_job_is_placed_keeping_its_robots(tmp_path, capsys, monkeypatch):
    """A part job with [[robot]] tables (a cell, on a line): placed as any part job (for the
    robot at the world origin), written with the same robots, to a file or to stdout ('-')."""
    curved = ROOT / "examples" / "parts" / "curved_panel.toml"
    job = tmp_path / "cell.toml"
    job.write_text(curved.read_text().replace('"curved_panel.stl"', '"{}"'.format(
        (curved.parent / "curved_panel.stl").as_posix()))
        + '\n[line]\nspeed = 0.03\ndirection = [0.0, 1.0, 0.0]\n\n[[robot]]\nname = "low"\n'
        'base = [0.0, 0.0, 0.0]\n\n[[robot]]\nname = "high"\nbase = [0.0, 0.75, 0.17]\n')
    monkeypatch.chdir(tmp_path)
    for out in (tmp_path / "p.toml", "-"):
        code, text, err = run_cli(["place", "--job", job, "--out", out, "--max-turn", "0"],
                                  capsys)
        assert code == 0 and "Traceback" not in err, err
        if out == "-":  # the job, then the summary line
            (tmp_path / "stdout.toml").write_text(text.split("\nposition [")[0])
        placed = load_job(tmp_path / ("stdout.toml" if out == "-" else out))
        given = load_job(job)
        assert placed.robots == given.robots and len(placed.robots) == 2
        assert placed.line == given.line and placed.position != given.position
