"""``pollard-pin plot`` (cli/plot.py): it writes every figure, PNGs that are not blank, and
checks every destination before it solves. (The figures' contents: tests/viz/test_plots.py;
a simulation's: tests/cli/test_simulate.py.)"""
import numpy as np
from cli_run import run_cli

from pollard_pin.cli import main
from pollard_pin.viz.plots import FIGURES, LOAD_FIGURES

ARGS = ["--samples", "401", "--quiet"]


def test_plot_command_writes_every_figure(tmp_path, capsys):
    from PIL import Image

    out = tmp_path / "figs"
    assert main(["plot", *ARGS, "--out", str(out), "--dpi", "50"]) == 0
    written = sorted(p.name for p in out.iterdir())
    assert written == sorted(f"{n}.png" for n in FIGURES + LOAD_FIGURES)
    for name in FIGURES:
        path = out / f"{name}.png"
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        with Image.open(path) as im:
            assert im.width >= 300 and im.height >= 250
            px = np.asarray(im.convert("L"))
        assert px.std() > 5, f"{name}.png looks blank"
    assert str(out / "actuators.png") in capsys.readouterr().out


def test_a_figure_path_that_is_a_folder_is_one_line_and_nothing_is_written(tmp_path, capsys):
    out = tmp_path / "figs"
    (out / f"{LOAD_FIGURES[0]}.png").mkdir(parents=True)
    code, _, err = run_cli(["plot", *ARGS, "--out", out], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert f"{LOAD_FIGURES[0]}.png" in err and "is a folder" in err
    assert [p.name for p in out.iterdir()] == [f"{LOAD_FIGURES[0]}.png"]
