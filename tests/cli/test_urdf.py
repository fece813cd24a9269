"""``pollard-pin urdf`` (cli/urdf.py): it writes the shipped files' text (installed entry point
too), here by default and never over the shipped files, to standard output with ``--out -``;
a broken parameter file is one line and nothing written."""
import subprocess
import sys
from pathlib import Path

from cli_run import run_cli

import pollard_pin as pp

ROOT = Path(__file__).resolve().parents[2]
URDF_PATH = ROOT / "models" / "pollard.urdf"
SRDF_PATH = ROOT / "models" / "pollard.srdf"


def test_cli_urdf_writes_the_same_text(tmp_path, monkeypatch, capsys):
    exe = Path(sys.executable).with_name("pollard-pin")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "pollard_pin.cli"]
    out = subprocess.run(cmd + ["urdf", "--out", "tmp/x.urdf"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "tmp/x.urdf").read_text() == URDF_PATH.read_text()
    assert (tmp_path / "tmp/x.srdf").read_text() == SRDF_PATH.read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text("[chain0\n")
    monkeypatch.chdir(tmp_path)  # the refusal in this process: the one run above is the end-to-end
    code, _, err = run_cli(["urdf", "--params", bad, "--out", "y.urdf"], capsys)
    assert code == 2
    assert err.startswith("pollard-pin urdf: error: parameter file") and \
        "is not valid TOML" in err, err
    assert not (tmp_path / "y.urdf").exists()


def test_urdf_default_writes_here_and_never_the_shipped_files(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    files = tmp_path
    shipped = {p: p.stat().st_mtime_ns for p in (ROOT / "models").iterdir()}
    code, out, err = run_cli(["urdf", "--set", "chain0.x32=0.34"], capsys)
    assert code == 0, err
    assert shipped == {p: p.stat().st_mtime_ns for p in (ROOT / "models").iterdir()}
    urdf = (files / "pollard.urdf").read_text()
    assert (files / "pollard.srdf").exists()
    assert urdf == pp.load(pp.load_params(overrides={"chain0.x32": 0.34})).urdf
    code, out, _ = run_cli(["urdf", "--out", "-"], capsys)
    assert code == 0 and out == (ROOT / "models" / "pollard.urdf").read_text()
