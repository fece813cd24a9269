"""Tall parts on a line for the cell's split and layout tests (docs/model.md §26.2, §26.5):
a panel, and a thin plate's mesh painted on both faces."""
import math

from pollard_pin.painting.job import job_from_dict

GUN = {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7}
LINE = {"speed": 0.012, "direction": [0.0, 1.0, 0.0]}


def tall_panel(height: float = 0.34, z: float = 0.17, width: float = 0.8, x: float = 0.70,
               lift: float = 0.0, robots=None):
    """A ``width`` × ``height`` panel facing −x at depth ``x`` [m], centred at height ``z``
    (+ ``lift``), upstream on a +y line; ``robots``: [[robot]] tables."""
    d = {"panel": {"center": [x, -0.75, z + lift], "normal": [-1.0, 0.0, 0.0],
                   "width": width, "height": height},
         "gun": dict(GUN), "job": {"thickness": 25e-6}, "line": dict(LINE)}
    if robots:
        d["robot"] = robots
    return job_from_dict(d)


def plate_part(folder, height: float = 0.34, z: float = 0.17, width: float = 0.8,
               thick: float = 0.02, x: float = 0.70):
    """A plate ``width`` (along y) × ``thick`` (x) × ``height`` (z) centred at (x, ·, z),
    upstream on a +y line, its −x face painted: (the job file's path)."""
    import trimesh

    trimesh.creation.box((thick, width, height)).export(folder / "plate.stl")
    text = f"""
[part]
mesh = "plate.stl"
position = [{x}, -0.75, {z}]
facing = [-1.0, 0.0, 0.0]

[gun]
standoff = 0.15
sigma = 0.01
flow = 1.5e-7

[job]
thickness = 25e-6

[line]
speed = 0.012
direction = [0.0, 1.0, 0.0]
"""
    (folder / "plate.toml").write_text(text)
    return folder / "plate.toml"


def check_zones(robot, robots, split, strokes):
    """Contiguous zones, free edges at the ends, each zone + its run-outs in its robot's
    band; the zones' lengths on the part."""
    from pollard_pin.painting.cell.bands import robot_band

    by = {r.name: r for r in robots}
    z = split.zones
    assert z[0].lo == -math.inf and z[-1].hi == math.inf
    assert all(a.hi == b.lo for a, b in zip(z, z[1:]))
    assert all(a.lo < a.hi for a in z)
    for zone in z:
        band = robot_band(robot, by[zone.robot], strokes)
        need = strokes.needed(zone.lo, zone.hi)
        assert band.holding(*need).holds(*need), (zone, band)
    return [min(b.hi, strokes.extent[1]) - max(b.lo, strokes.extent[0]) for b in z]


def door_part(folder, height: float = 0.33, chamfer: float = 0.04, angle: float = 40.0,
              speed: float = 0.024):
    """A door 0.8 m long (along y) and ``height`` high from z = 0.015 m, its top and bottom
    edges bevelled ``angle`` degrees away from the robots over ``chamfer`` of surface
    (:func:`pollard_pin.painting.workpiece.shapes.chamfered_plate`), written in mm, upstream
    on a +y line at ``speed`` [m/s] (docs/model.md §26.5's): (the job file's path)."""
    from pollard_pin.painting.workpiece.shapes import chamfered_plate

    mesh = chamfered_plate(height=height, chamfer=chamfer, angle_deg=angle,
                           z0=height / 2 + 0.015)
    mesh.apply_scale(1000.0)
    mesh.export(folder / "door.stl")
    text = f"""
[part]
mesh = "door.stl"
units = "mm"
position = [0.0, -0.75, 0.0]
facing = [-1.0, 0.0, 0.0]

[gun]
standoff = {GUN["standoff"]}
sigma = {GUN["sigma"]}
flow = {GUN["flow"]}

[job]
thickness = 25e-6

[line]
speed = {speed}
direction = [0.0, 1.0, 0.0]
"""
    (folder / "door.toml").write_text(text)
    return folder / "door.toml"
