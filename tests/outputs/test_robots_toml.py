"""A cell's [[robot]] tables written (outputs/robots_toml.py) read back by the job reader as the
same robots, bit for bit."""
import tomllib

from pollard_pin.outputs.robots_toml import robots_toml, write_robots
from pollard_pin.painting.cell.robots import CellRobot, robots_from_tables


def test_robots_round_trip(tmp_path):
    robots = (CellRobot("robot1", (0.0, 0.0, -0.025)),
              CellRobot("far_2", (1.4, 0.77, 0.1 + 0.2), (180.0, -0.0, 12.345678901234567)))
    path = write_robots(robots, tmp_path / "robots.toml", "proposed\nfor a test")
    text = path.read_text()
    assert text.startswith("# proposed\n# for a test\n") and "-0.0," not in text
    back = robots_from_tables(str(path), tomllib.loads(text)["robot"])
    assert back == robots


def test_names_are_toml_strings():
    """The name is written by the one TOML string writer (the job reader allows only letters,
    digits, '_' and '-', but what is written is TOML whatever it holds)."""
    text = robots_toml((CellRobot('a"b\nc\\', (0.0, 0.0, 0.0)),))
    assert tomllib.loads(text)["robot"][0]["name"] == 'a"b\nc\\'
