"""Small paint cells for the planner's tests (docs/model.md §26): a 0.2 × 0.33 m panel on a
+y line painted by two stacked robots (one raised 0.17 m and set 0.6 m down the line), and
the same scene moved rigidly."""
import numpy as np

from pollard_pin.painting.job import job_from_dict

GUN = {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7}
STACKED = [{"name": "low", "base": [0.0, 0.0, 0.0]},
           {"name": "high", "base": [0.0, 0.6, 0.17]}]


def panel_cell(robots=STACKED, width: float = 0.2, speed: float = 0.025) -> dict:
    """The job's tables: the panel upstream at y = −0.3 m, its bottom 15 mm above the low
    robot's base."""
    return {"panel": {"center": [0.70, -0.3, 0.18], "normal": [-1.0, 0.0, 0.0],
                      "width": width, "height": 0.33},
            "gun": dict(GUN), "job": {"thickness": 25e-6},
            "line": {"speed": speed, "direction": [0.0, 1.0, 0.0]},
            "robot": [dict(r) for r in robots]}


def moved(tables: dict, turn_deg: float, shift) -> dict:
    """The scene turned by ``turn_deg`` about world z, then shifted by ``shift`` [m]: the
    panel's centre and normal, the line's direction, every base and its rotation."""
    c, s = np.cos(np.radians(turn_deg)), np.sin(np.radians(turn_deg))
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    t = np.asarray(shift, float)
    out = {k: dict(v) if isinstance(v, dict) else v for k, v in tables.items()}
    out["panel"]["center"] = list(R @ tables["panel"]["center"] + t)
    out["panel"]["normal"] = list(R @ tables["panel"]["normal"])
    out["line"]["direction"] = list(R @ tables["line"]["direction"])
    out["robot"] = [{"name": r["name"], "base": list(R @ r["base"] + t),
                     "rotation": [0.0, 0.0, turn_deg]} for r in tables["robot"]]
    return out


def cell_job(tables: dict, source: str = "<cell test>"):
    return job_from_dict(tables, source)


# A plate part riding the line past one robot at the origin (its mesh: plate.stl beside it)
PLATE_CELL = """
[part]
mesh = "plate.stl"
position = [0.71, -0.3, 0.10]
facing = [-1.0, 0.0, 0.0]

[gun]
standoff = 0.15
sigma = 0.01
flow = 1.5e-7

[job]
thickness = 25e-6

[line]
speed = 0.02
direction = [0.0, 1.0, 0.0]

[[robot]]
name = "near"
base = [0.0, 0.0, 0.0]
"""
