"""Absurd sizes (the conventions of test_fuzz.py): each request over a stated budget, or a
number that would overflow one, is one line on standard error, exit status 2, nothing
written, and it says so before anything is allocated (well within a few seconds)."""
from __future__ import annotations

import os
import time
from pathlib import Path

import pytest
from cli_run import run_cli, tree_state

# one parser per module (tests/conftest.py): building one per case was a tenth of the time
pytestmark = pytest.mark.usefixtures("one_parser_per_module")

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ACT = str(EXAMPLES / "actuators.toml")
HEADER = "t,x,y,z,psi,theta,phi"


def _rows(n: int = 12) -> list[str]:
    """The first ``n`` samples of examples/figure8.csv, poses only (as test_fuzz.py)."""
    lines = (EXAMPLES / "figure8.csv").read_text().splitlines()
    return [",".join(line.split(",")[:7]) for line in lines[1:n + 1]]


def _job(old: str, new: str) -> str:
    job = (EXAMPLES / "paint.toml").read_text()
    assert old in job, old
    return job.replace(old, new, 1)


def _files() -> dict[str, str]:
    rows = _rows()
    tiny = HEADER + "\n" + "".join(",".join([repr(5e-324 * i), *r.split(",")[1:]]) + "\n"
                                   for i, r in enumerate(rows))
    values = ", ".join(f"{0.30 + 1e-5 * i:.5f}" for i in range(1000))
    masses = ", ".join(f"{0.04 + 1e-5 * i:.5f}" for i in range(1000))
    return {
        "subnormal_dt.csv": tiny,
        "size_thick.toml": _job("thickness = 25e-6", "thickness = 0.1"),
        "size_flow.toml": _job("flow = 1.5e-7", "flow = 1e-300"),
        "size_flow_zero.toml": _job("flow = 1.5e-7", "flow = 5e-324"),
        "size_narrow.toml": _job("width = 0.26", "width = 1e-30"),
        "size_low.toml": _job("height = 0.12", "height = 0.005"),
        "size_spacing.toml": _job("thickness = 25e-6", "thickness = 25e-6\nspacing = 1e-6"),
        "size_coats.toml": _job("thickness = 25e-6", "thickness = 25e-6\ncoats = 1000000000"),
        "size_grid.toml": f"[grid]\n'chain0.x32' = [{values}]\n'gun.mass' = [{masses}]\n",
    }


@pytest.fixture(scope="module")
def sized(tmp_path_factory):
    root = tmp_path_factory.mktemp("sizes")
    files = {**_files(), "job_good.toml": (EXAMPLES / "paint.toml").read_text(),
             "existing.csv": "precious: a failed command must leave this untouched\n"}
    for name, content in files.items():
        (root / name).write_text(content)
    return root


WS = ["workspace", "--quiet", "--out", "ws"]
PAINT = ["paint", "--out", "p", "--job"]
CASES = [
    (["run", "--samples", "100000000000000000000", "--out", "existing.csv"],
     "1e+20 samples are over the streamed budget of 1e+08"),
    (["run", "--samples", "1" + "0" * 400, "--out", "out.csv"],
     "must be a sane count >= 2, got a 401-digit number"),
    (["view", "--samples", "100000000000000000000", "--html", "out.html"],
     "1e+20 samples are over the budget of 1e+06"),
    (["plot", "--samples", "2000000", "--out", "plots"], "2e+06 samples are over the budget"),
    (["simulate", "--samples", "10000000000", "--out", "out.csv"], "over the budget"),
    *(([*prefix, "--trajectory", "subnormal_dt.csv"], "row 3, column 't': time step too small")
      for prefix in (["run", "--out", "out.csv"], ["size", "--actuators", ACT, "--out", "out.md"],
                     ["simulate", "--out", "out.csv"])),
    ([*WS, "--plane", "x=0.55", "--resolution", "1e-300"],
     "resolution = 1e-300 m gives a grid of 1e+308 points (budget 1.074e+07)"),
    ([*WS, "--volume", "--resolution", "5e-324"], "use a resolution of at least 0.00287 m"),
    ([*WS, "--plane", "x=0.55", "--resolution", "1e-4"], "2.562e+08 points (budget 1.074e+07)"),
    ([*PAINT, "job_good.toml", "--resolution", "1e-300"],
     "--resolution: film grid spacing 1e-300 m makes inf film points on the 0.26 × 0.12 m "
     "panel, budget 2e+06"),
    # a part's film points: the subdivisions overflowed an int and the part got no points
    *(([*PAINT, str(EXAMPLES / job), "--resolution", r], "film points at resolution")
      for job in ("parts/curved_panel.toml", "line_part.toml") for r in ("1e-9", "1e-300")),
    ([*PAINT, "size_thick.toml"], "the path needs 1.57e+07 samples (3.131e+04 s at a gun speed "
                                  "of 8.264e-05 m/s), budget 2.5e+05: a thinner film"),
    ([*PAINT, "size_flow.toml"], "the path needs 5.87e+296 samples"),
    ([*PAINT, "size_flow_zero.toml"], "the path needs inf samples"),
    ([*PAINT, "size_narrow.toml"], "'panel.width' = 1e-30: is smaller than the spray spot "
                                   "(σ = 0.01 m)"),
    ([*PAINT, "size_low.toml"], "'panel.height' = 0.005: is smaller than the spray spot"),
    ([*PAINT, "size_spacing.toml"], "passes (1 coat(s) at spacing 0.001 mm over 0.12 m), "
                                    "budget 1000"),
    ([*PAINT, "size_coats.toml"], "budget 1000: a wider spacing, fewer coats"),
    (["sweep", "--grid", "size_grid.toml", "--out", "out.csv"],
     "the grid makes 1e+06 variants (1000 × 1000), budget 1e+04"),
]
IDS = [" ".join(argv)[:80] for argv, _ in CASES]


@pytest.mark.parametrize("argv, says", CASES, ids=IDS)
def test_an_absurd_size_is_one_line_at_once_and_writes_nothing(sized, monkeypatch, capsys,
                                                               argv, says):
    monkeypatch.chdir(sized)
    before, beside = tree_state(sized), sorted(os.listdir(sized.parent))
    t0 = time.perf_counter()
    code, out, err = run_cli(argv, capsys)
    wall = time.perf_counter() - t0
    lines = err.strip().splitlines()
    assert code == 2, (code, out[-300:], err[-2000:])
    assert out == "", out[:300]
    assert len(lines) == 1 and lines[0].startswith("pollard-pin"), err[-2000:]
    assert says in lines[0] and "Traceback" not in err, lines[0]
    assert len(lines[0]) < 330, lines[0]  # no 700-digit integers
    assert tree_state(sized) == before
    assert sorted(os.listdir(sized.parent)) == beside
    assert wall < 10.0, wall  # refused up front (the sweep: 10^6 names, seen 0.3 s)
