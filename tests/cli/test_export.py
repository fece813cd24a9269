"""``pollard-pin export`` (cli/export.py): the MJCF it writes is io.mjcf's for the same model,
--set reaches it, and a bad destination is one line with nothing written. (The MJCF itself:
tests/io/test_mjcf.py.)"""
import pytest
from cli_run import run_cli

from pollard_pin.io.mjcf import export_mjcf


def test_export_writes_the_libraries_mjcf(robot, tmp_path, capsys):
    out = tmp_path / "m.xml"
    code, _, err = run_cli(["export", "--out", out], capsys)
    assert code == 0 and f"wrote {out} (MJCF: 12 joints, 2 connect equalities)" in err
    ref = export_mjcf(tmp_path / "ref.xml", urdf=robot.urdf)
    assert out.read_text() == ref.read_text()


def test_set_changes_the_model(tmp_path, capsys):
    a, b = tmp_path / "a.xml", tmp_path / "b.xml"
    assert run_cli(["export", "--out", a], capsys)[0] == 0
    assert run_cli(["export", "--set", "chain0.x32=0.34", "--out", b], capsys)[0] == 0
    assert a.read_text() != b.read_text() and "0.34" in b.read_text()


@pytest.mark.parametrize("argv, says", [(["--out", "{d}/afile/m.xml"], "not a folder"),
                                        (["--format", "stl"], "invalid choice")])
def test_bad_destination_or_format(tmp_path, capsys, argv, says):
    (tmp_path / "afile").write_text("x")
    code, _, err = run_cli(["export", *[a.format(d=tmp_path) for a in argv]], capsys)
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile"]
