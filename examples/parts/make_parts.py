"""Write the example parts to paint, as meshes in world coordinates [m].

    .venv/bin/python examples/parts/make_parts.py [--out-dir examples/parts]

Each stands where ``examples/paint.toml``'s panel does: its painted front near x = 0.70 m,
centred at y = 0, z = 0.16 m, facing the robot (−x), 0.24 × 0.10 m, a 2 mm sheet:

* ``curved_panel.stl`` (binary STL): a cylinder section of radius 0.4 m (axis vertical),
  convex towards the robot, its apex at x = 0.70 m; the gun turns by up to ±17° of yaw to
  stay normal to it;
* ``bent_plate.ply`` (binary PLY): a plate whose right half is bent 30° towards the robot
  over a concave fillet of radius 30 mm (tighter than the 0.15 m standoff: a gun normal to
  the surface would fold back over the fillet);
* ``ribbed_plate.obj`` (OBJ): a flat plate with a vertical rib 15 mm high and 6 mm wide
  down its middle, whose walls shade the plate beside them.

and for a conveyor (``examples/line_part.toml``, docs/model.md §24):

* ``long_strip.stl`` (binary STL): a strip 0.90 m long (along y, longer than the reach) and
  0.10 m high, a cylinder section of radius 3 m convex towards the robot: the gun yaws by up
  to ±8.6° from one end to the other;
* ``tall_plate.stl`` (binary STL, **in mm**): a flat plate 0.80 m long (along y) and 0.33 m
  high, taller than one robot's band and longer than its reach, centred at z = 0.18 m: a cell
  of two robots paints it riding the line (``examples/cell_part.toml``, docs/model.md §26);
* ``curved_tall.stl`` (binary STL, **in mm**): a cylinder section of radius 1.5 m (axis
  vertical), 0.80 m of arc along y and 0.33 m high, convex towards the robots, centred at
  z = 0.18 m: the curved part of ``examples/cell_curved.toml``, its strokes yawing by up to
  ±15° and 53 mm deeper at its ends than at its apex.

Read one with ``pollard_pin.painting.workpiece.mesh.load_part("examples/parts/curved_panel.stl")``.
"""
import argparse
from pathlib import Path

import numpy as np

from pollard_pin.painting.workpiece import shapes


def tall_plate():
    """The flat plate of examples/cell_part.toml, in mm."""
    front = np.column_stack([np.full(41, shapes.FRONT_X), np.linspace(-0.40, 0.40, 41)])
    mesh = shapes.extrude(front, front + [shapes.THICKNESS, 0.0], 0.33, 11, z0=0.18)
    mesh.apply_scale(1000.0)
    return mesh


def curved_tall():
    """The curved part of examples/cell_curved.toml, in mm."""
    mesh = shapes.curved_panel(radius=1.5, width=0.80, height=0.33, step=0.02, z0=0.18)
    mesh.apply_scale(1000.0)
    return mesh


PARTS = {"curved_panel.stl": lambda: shapes.curved_panel(radius=0.4, width=0.24, height=0.10),
         "bent_plate.ply": lambda: shapes.bent_plate(flat=0.12, wing=0.11, angle_deg=30.0,
                                                      fillet=0.030, height=0.10),
         "ribbed_plate.obj": lambda: shapes.ribbed_plate(width=0.24, height=0.10,
                                                         rib_height=0.015, rib_width=0.006,
                                                         step=0.01),
         "long_strip.stl": lambda: shapes.curved_panel(radius=3.0, width=0.90, height=0.10,
                                                     step=0.01),
         "tall_plate.stl": tall_plate,
         "curved_tall.stl": curved_tall}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", type=Path, default=Path(__file__).resolve().parent)
    args = ap.parse_args(argv)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    for name, make in PARTS.items():
        mesh = make()
        path = args.out_dir / name
        mesh.export(path)
        lo, hi = mesh.bounds
        print(f"wrote {path}: {len(mesh.faces)} faces, x {lo[0]:.3f}..{hi[0]:.3f}, "
              f"y {lo[1]:.3f}..{hi[1]:.3f}, z {lo[2]:.3f}..{hi[2]:.3f} m, "
              f"closed {mesh.is_watertight}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
