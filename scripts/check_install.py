"""What a plain ``pip install .`` gives: build the wheel, install it without extras into a
fresh venv, and run every command from a folder outside the repository (so the checkout's
own ``pollard_pin`` cannot be imported). Paint runs every example job (panel, parts, a panel
and a part on a line);
the MuJoCo export, an extra, must refuse in one line. Run by ``.ci/run`` (``make
install-check``); standard library only, so it runs with the bare interpreter.

    python3 scripts/check_install.py [--keep DIR]
"""
from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def sh(argv, cwd=None, ok=(0,)) -> subprocess.CompletedProcess:
    t0 = time.perf_counter()
    out = subprocess.run([str(a) for a in argv], cwd=cwd, capture_output=True, text=True)
    took = time.perf_counter() - t0
    shown = " ".join(str(a) for a in argv[1:] if not str(a).startswith("/"))
    print(f"{took:7.1f} s  exit {out.returncode}  {shown}", flush=True)
    if out.returncode not in ok:
        sys.exit(f"check_install: `{' '.join(map(str, argv))}` exited {out.returncode}:\n"
                 f"{out.stdout[-2000:]}\n{out.stderr[-2000:]}")
    return out


def need(path: Path, what: str) -> None:
    if not path.is_file() or path.stat().st_size == 0:
        sys.exit(f"check_install: {what}: {path.name} was not written")


def commands(cli: Path, work: Path) -> None:
    """One call of every command; paint on a still mesh part and a part on a line."""
    ex = work / "examples"
    jobs = {"part": "parts/curved_panel.toml", "line": "line_part.toml", "panel": "paint.toml",
            "line_panel": "line.toml", "bent": "parts/bent_plate.toml",
            "ribbed": "parts/ribbed_plate.toml"}  # every example job
    for folder, job in jobs.items():
        sh([cli, "paint", "--job", ex / job, "--out", folder], work)
    for folder in jobs:
        need(work / folder / "path.csv", f"paint --out {folder}")
        report = json.loads((work / folder / "paint.json").read_text())
        if not report:
            sys.exit(f"check_install: paint --out {folder}: empty paint.json")
        if report.get("compliance", {}).get("stiffness") is not True:  # docs/model.md §27.7
            sys.exit(f"check_install: paint --out {folder}: no compliance in paint.json")
    # a cell (docs/model.md §26): a folder per robot, one film
    sh([cli, "paint", "--job", ex / "cell.toml", "--out", "cell2"], work)
    for name in ("low", "high"):
        need(work / "cell2" / name / "path.csv", f"paint --out cell2 ({name})")
    need(work / "cell2" / "paint.json", "paint --out cell2")
    sh([cli, "view", "--paint", "cell2", "--html", "cell2.html"], work)
    need(work / "cell2.html", "view --paint cell2")
    # the painted program goes through run and size like any trajectory
    sh([cli, "run", "--trajectory", work / "part/path.csv", "--out", "part_run.csv"], work)
    sh([cli, "size", "--actuators", ex / "actuators.toml", "--trajectory",
        work / "part/path.csv"], work)
    sh([cli, "run", "--samples", "401", "--out", "run.csv"], work)
    need(work / "run.csv", "run")
    # stiffness on the thesis path and on a paint program's path (docs/model.md §27)
    sh([cli, "stiffness", "--actuators", ex / "actuators.toml", "--samples", "401", "--out",
        "stiff.csv"], work)
    sh([cli, "stiffness", "--actuators", ex / "actuators.toml", "--trajectory",
        work / "part/path.csv", "--wrench=0,0,-5,0,0,0", "--out", "part_stiff.parquet"], work)
    for f in ("stiff.csv", "part_stiff.parquet"):
        need(work / f, "stiffness")
    sh([cli, "urdf", "--out", "p.urdf"], work)
    info = sh([cli, "info"], work)
    if "total mass 0.9200 kg" not in info.stdout:
        sys.exit(f"check_install: info does not say the model's mass: {info.stdout[:200]!r}")
    sh([cli, "report", "--no-cross-check"], work)
    sh([cli, "simulate", "--duration", "2", "--out", "sim.csv"], work)
    sh([cli, "simulate", "--trajectory", ex / "figure8.csv", "--actuators",
        ex / "actuators.toml", "--flexible", "--out", "flex.csv"], work)
    sh([cli, "workspace", "--plane", "x=0.55", "--resolution", "0.02", "--out", "ws"], work)
    sh([cli, "sweep", "--grid", ex / "sweep.toml", "--out", "sweep.csv"], work)
    sh([cli, "plot", "--out", "plots"], work)
    sh([cli, "view", "--html", "v.html"], work)
    sh([cli, "view", "--paint", "part", "--html", "paint.html"], work)
    # the figures from the installed package (tests/model/test_build.py leaves plot to here)
    for f in ("sim.csv", "flex.csv", "sweep.csv", "v.html", "paint.html", "p.urdf",
              "plots/actuators.png"):
        need(work / f, f)
    # paint --robots auto: a proposed cell planned, its [[robot]] tables written (§26.5)
    sh([cli, "paint", "--job", ex / "line.toml", "--robots", "auto", "--out", "cell"], work)
    need(work / "cell" / "robots.toml", "paint --robots auto")
    # calibrate the spray from the example stripes; its gun.toml is a [gun] table (§30)
    sh([cli, "calibrate", "--stripes", ex / "stripes" / "stripes.toml", "--out", "cal"], work)
    gun = (work / "cal" / "gun.toml").read_text() if (work / "cal" / "gun.toml").exists() else ""
    if "[gun]" not in gun or "model" not in gun:
        sys.exit(f"check_install: calibrate wrote no gun.toml with a [gun] model: {gun[:200]!r}")
    # an extra that is not installed: one line and exit 2
    out = sh([cli, "export", "--format", "mjcf", "--out", "p.xml"], work, ok=(2,))
    if len(out.stderr.strip().splitlines()) != 1 or "mujoco" not in out.stderr:
        sys.exit(f"check_install: export without the mujoco extra: {out.stderr!r}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--keep", type=Path, help="work in this folder and keep it")
    args = ap.parse_args()
    work = args.keep or Path(tempfile.mkdtemp(prefix="pollard-install-"))
    work.mkdir(parents=True, exist_ok=True)
    try:
        t0 = time.perf_counter()
        wheels = work / "wheel"
        sh([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", wheels, ROOT])
        wheel = next(wheels.glob("pollard_pin-*.whl"))
        sh([sys.executable, "-m", "venv", work / "venv"])
        pip = work / "venv/bin/python"
        sh([pip, "-m", "pip", "install", "--quiet", wheel])
        shutil.copytree(ROOT / "examples", work / "examples")
        commands(work / "venv/bin/pollard-pin", work)
        print(f"check_install: a plain install ran every command "
              f"({time.perf_counter() - t0:.0f} s)")
    finally:
        if args.keep is None:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
