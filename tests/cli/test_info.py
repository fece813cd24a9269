"""``pollard-pin info`` (cli/info.py): the masses and home configuration it prints are the
model's, the closure residual at home is round-off, --set reaches it."""
import re

import numpy as np
from cli_run import run_cli


def test_info_prints_the_models_numbers(robot, capsys):
    code, out, err = run_cli(["info"], capsys)
    assert code == 0 and err == ""
    assert f"total mass {robot.params.total_mass:.4f} kg" in out
    for name, b in robot.params.bodies:
        assert re.search(rf"^  {name}\s+{b.mass:.3f} kg$", out, re.M), name
    home = robot.as_dict(robot.home())
    for name, val in home.items():
        m = re.search(rf"^  {name}\s+(-?[\d.]+)$", out, re.M)
        assert m and float(m.group(1)) == round(np.degrees(val), 4), name
    residual = float(re.search(r"closure residual at home: (\S+) m", out).group(1))
    assert residual < 1e-12


def test_set_reaches_the_model(capsys):
    _, out, _ = run_cli(["info", "--set", "bodies.gun.mass=0.05"], capsys)
    assert re.search(r"^  gun\s+0\.050 kg$", out, re.M)
