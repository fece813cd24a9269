"""Fuzzing every command with bad input: malformed numbers, NaN/inf, zero and
negative values, huge values, wrong units, missing/unreadable/binary/empty/non-UTF-8 files,
folders given as files, unwritable outputs, bad --set keys and values, truncated CSVs, rows of
NaN, time that does not increase, duplicate columns, and more.

Every case must give exactly one line on standard error starting ``pollard-pin``, saying the
expected fragment, exit status 2, no traceback, and write nothing: no new file, and the
existing output files unchanged. The commands run in this process (``main(argv)``).

To add a command's cases, append ``(argv, fragment)`` pairs to ``CASES`` (or a family of your
own concatenated to it); the files named in them live in the ``scratch`` folder below.
"""
from __future__ import annotations

import contextlib
import io
import os
import re
import socket
from pathlib import Path

import pytest
from cli_run import run_cli, tree_state

from pollard_pin.cli import main

# one parser per module (tests/conftest.py): building one per case was a tenth of the time
pytestmark = pytest.mark.usefixtures("one_parser_per_module")

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
ACT = str(EXAMPLES / "actuators.toml")
HEADER = "t,x,y,z,psi,theta,phi"
PRECIOUS = b"precious: a failed command must leave this untouched\n"


# --- the scratch folder: one small trajectory and every bad file derived from it -------------
def _good_rows(n: int = 12) -> list[str]:
    """The first ``n`` samples of examples/figure8.csv, poses only (12 samples, 0.22 s)."""
    lines = (EXAMPLES / "figure8.csv").read_text().splitlines()
    return [",".join(line.split(",")[:7]) for line in lines[1:n + 1]]


def _files() -> dict[str, bytes | str | None]:
    rows = _good_rows()
    body = "\n".join(rows) + "\n"
    good = f"{HEADER}\n{body}"
    first = rows[0].split(",")

    def with_row(i: int, cells: dict[int, str]) -> str:
        out = [r.split(",") for r in rows]
        for c, v in cells.items():
            out[i][c] = v
        return HEADER + "\n" + "\n".join(",".join(r) for r in out) + "\n"

    act = (EXAMPLES / "actuators.toml").read_text()
    sweep = "trajectory = 'good.csv'\n[grid]\n'chain0.x32' = [0.33]\n"
    return {
        # trajectories
        "good.csv": good,
        "empty.csv": "",
        "blank.csv": "\n\n\n",
        "comments.csv": "# nothing but a comment\n",
        "header_only.csv": HEADER + "\n",
        "one_row.csv": f"{HEADER}\n{rows[0]}\n",
        "three_rows.csv": HEADER + "\n" + "\n".join(rows[:3]) + "\n",
        "truncated.csv": good[:-25],  # the last row cut short: fewer fields
        "cut_number.csv": good.rstrip("\n")[:-3] + "e\n",  # cut inside a number
        "nan_row.csv": with_row(5, {1: "nan", 2: "nan"}),
        "inf_row.csv": with_row(5, {3: "inf"}),
        "empty_cell.csv": with_row(4, {2: ""}),
        "text_cell.csv": with_row(4, {2: "abc"}),
        "comma_decimal.csv": with_row(4, {2: "0,55"}),
        "decreasing_t.csv": with_row(6, {0: "0.01"}),
        "duplicate_t.csv": with_row(6, {0: rows[5].split(",")[0]}),
        "duplicate_column.csv": "t,x,y,z,psi,theta,phi,x\n" + "".join(
            f"{r},{r.split(',')[1]}\n" for r in rows),
        "unknown_column.csv": "t,x,y,z,psi,theta,phi,speed\n" + "".join(f"{r},1\n" for r in rows),
        "missing_column.csv": "t,x,y,z,psi,theta\n" + "".join(
            ",".join(r.split(",")[:6]) + "\n" for r in rows),
        "mm.csv": HEADER + "\n" + "".join(
            ",".join([c[0], str(1e3 * float(c[1])), *c[2:]]) + "\n"
            for c in (r.split(",") for r in rows)),
        "deg.csv": with_row(3, {4: "30"}),
        "no_t.csv": "x,y,z,psi,theta,phi\n" + "".join(r.split(",", 1)[1] + "\n" for r in rows),
        "trailing_comma.csv": HEADER + "\n" + "".join(r + ",\n" for r in rows),
        "partial_derivatives.csv": "t,x,y,z,psi,theta,phi,d_x\n" + "".join(
            f"{r},0\n" for r in rows),
        "semicolon.csv": good.replace(",", ";"),
        "tabs.csv": good.replace(",", "\t"),
        "nul.csv": good.encode()[:40] + b"\x00\x00\x00" + good.encode()[40:],
        "latin1.csv": f"# Pollard m\xfcde\n{good}".encode("latin-1"),
        "utf16.csv": good.encode("utf-16"),
        "png.csv": b"\x89PNG\r\n\x1a\n" + bytes(range(256)),
        "gzip.csv": b"\x1f\x8b\x08\x00" + bytes(64),
        "long_field.csv": f"{HEADER}\n{'1' * 200_000},0,0,0,0,0,0\n",
        "fast.csv": "t,x,y,z,psi,theta,phi,d_x,d_y,d_z,d_psi,d_theta,d_phi\n" + "".join(
            f"{r},1e200,0,0,0,0,0\n" for r in rows),
        "tiny_dt.csv": HEADER + "\n" + "".join(
            ",".join([f"{1e-12 * i:g}", *r.split(",")[1:]]) + "\n" for i, r in enumerate(rows)),
        "garbage.parquet": b"PAR1garbage",
        "parquet.csv": b"PAR1" + bytes(32) + b"PAR1",  # Parquet bytes, a .csv name
        "unreachable.csv": HEADER + "\n" + "".join(
            ",".join([c[0], "2.9", *c[2:]]) + "\n" for c in (r.split(",") for r in rows)),
        "still.csv": HEADER + "\n" + "".join(
            f"{0.02 * i:.2f},{','.join(first[1:])}\n" for i in range(50)),
        # simulation tables (plot/report --simulation)
        "ab.csv": "a,b\n",
        "ab_rows.csv": "a,b\n1,2\n3,4\n",
        "t_only.csv": "t\n",
        "sim_text.csv": "t,theta21\n0,abc\n",
        # parameter files
        "broken.toml": "[chain0\n",
        "latin1.toml": "# m\xfcde\n[chain0]\nx32 = 0.34\n".encode("latin-1"),
        "nul.toml": b"[chain0]\nx32 = \x00\n",
        "huge.toml": "[chain0]\nx32 = 1e300\n",
        "mm.toml": "[chain0]\nx32 = 330\n",
        "nan.toml": "[chain0]\nx32 = nan\n",
        "inf.toml": "[chain0]\nx65 = inf\n",
        "negative_mass.toml": "[bodies.gun]\nmass = -0.05\n",
        "zero_mass.toml": "[bodies.gun]\nmass = 0\n",
        "string.toml": "[chain0]\nx32 = '0.33'\n",
        "bool.toml": "[chain0]\nx32 = true\n",
        "array.toml": "[chain0]\nx32 = [0.33]\n",
        "unknown_section.toml": "[chain9]\nx32 = 0.33\n",
        "unknown_key.toml": "[chain0]\nx33 = 0.33\n",
        "short_com.toml": "[bodies.gun]\ncom = [0.0, 0.0]\n",
        # actuator files
        "act_missing_table.toml": act.split("[theta1817]")[0],
        "act_unknown_table.toml": act + "\n[theta99]\ngear_ratio = 1.0\n",
        "act_missing_key.toml": act.replace("max_speed = 500.0\n", "", 1),
        "act_unknown_key.toml": act.replace("viscous = 1e-6", "viscous = 1e-6\nviscus = 1", 1),
        "act_negative.toml": act.replace("gear_ratio = 100.0", "gear_ratio = -100.0", 1),
        "act_zero.toml": act.replace("peak_torque = 0.05", "peak_torque = 0.0", 1),
        "act_nan.toml": act.replace("rotor_inertia = 5e-6", "rotor_inertia = nan", 1),
        "act_inf.toml": act.replace("max_speed = 500.0", "max_speed = inf", 1),
        "act_string.toml": act.replace("coulomb = 1e-3", "coulomb = '1e-3'", 1),
        "act_huge.toml": act.replace("gear_ratio = 100.0", "gear_ratio = 1e300", 1),
        "act_continuous.toml": act.replace("continuous_torque = 0.02", "continuous_torque = 1",
                                           1),
        # a weak motor with a rotor it can spin up (Jm·ω/τ = 0.5 s, docs/model.md §19)
        "act_weak.toml": act.replace("peak_torque = 0.05", "peak_torque = 1e-6", 1)
                            .replace("rotor_inertia = 5e-6", "rotor_inertia = 1e-9", 1)
                            .replace("continuous_torque = 0.02", "continuous_torque = 1e-6", 1),
        # 5 kg·m² for 5e-6: the motor would take 5e4 s to spin its own rotor up
        "act_heavy_rotor.toml": act.replace("rotor_inertia = 5e-6", "rotor_inertia = 5", 1),
        # sweep grids
        "grid_good.toml": sweep,
        "grid_unknown.toml": "speed = 3\n" + sweep,
        "grid_bad_key.toml": "[grid]\n'chain0.x33' = [0.33]\n",
        "grid_bad_value.toml": "[grid]\n'chain0.x32' = ['long']\n",
        "grid_nan.toml": "[grid]\n'chain0.x32' = [nan]\n",
        "grid_mm.toml": "[grid]\n'chain0.x32' = [330]\n",
        "grid_empty_list.toml": "[grid]\n'chain0.x32' = []\n",
        "grid_scalar.toml": "[grid]\n'chain0.x32' = 0.33\n",
        "grid_samples.toml": "samples = 0\n[grid]\n'chain0.x32' = [0.33]\n",
        "grid_duration.toml": "duration = -1\n[grid]\n'chain0.x32' = [0.33]\n",
        "grid_traj.toml": "trajectory = 'nope.csv'\n[grid]\n'chain0.x32' = [0.33]\n",
        "grid_bad_traj.toml": "trajectory = 'nan_row.csv'\n[grid]\n'chain0.x32' = [0.33]\n",
        "grid_variant.toml": "[[variant]]\nname = 'a'\n'chain0.x33' = 0.3\n",
        "grid_variant_table.toml": "variant = 3\n",
        "grid_params.toml": "params = 'nope.toml'\n[grid]\n'chain0.x32' = [0.33]\n",
        # paint jobs, and damaged workspace and paint output folders (view --workspace/--paint)
        **_jobs(),
        **_parts(),
        **_output_folders(good, with_row(5, {1: "nan"})),
        # existing outputs that failures must leave untouched
        "existing.csv": PRECIOUS, "existing.md": PRECIOUS, "existing.urdf": PRECIOUS,
        "existing.html": PRECIOUS, "existing.xml": PRECIOUS, "existing.parquet": PRECIOUS,
        "afile": "not a folder\n",
        "afolder/": None,
        "empty_folder/": None,
    }


def _parts() -> dict[str, bytes | str]:
    """A [part] job over a copy of examples/parts/curved_panel.stl, broken meshes, and bad
    part jobs (part_*.toml)."""
    job = (EXAMPLES / "parts" / "curved_panel.toml").read_text()

    def sub(old: str, new: str, text: str = job) -> str:
        assert old in text, old
        return text.replace(old, new, 1)

    def mesh(name: str) -> str:
        return sub('"curved_panel.stl"', f'"{name}"')

    square = "v 0.7 -0.1 0.1\nv 0.7 0.1 0.1\nv 0.7 0.1 0.2\n"
    line = "[line]\nspeed = 0.03\ndirection = [0.0, 1.0, 0.0]\n"
    return {
        "curved_panel.stl": (EXAMPLES / "parts" / "curved_panel.stl").read_bytes(),
        "mesh_broken.stl": b"solid part\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n",
        "mesh_empty.obj": "v 0 0 0\nv 1 0 0\n",
        "mesh_nan.obj": square.replace("0.2", "nan") + "f 1 3 2\n",
        "mesh_flat.obj": "v 0.7 0 0.1\nv 0.7 0 0.2\nv 0.7 0 0.3\nf 1 2 3\n",
        "mesh_png.stl": b"\x89PNG\r\n\x1a\n" + bytes(range(256)),
        # a facet of two corners, ASCII (the reader said "cannot reshape array") and binary
        "mesh_two_corners.stl": "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0.7 0 0.1\n"
                                "vertex 0.7 0.1 0.1\nendloop\nendfacet\nendsolid s\n",
        "mesh_two_corners_binary.stl": bytes(80) + (1).to_bytes(4, "little") + bytes(12 + 24 + 2),
        "part_missing_mesh.toml": mesh("nope.stl"),
        "part_broken.toml": mesh("mesh_broken.stl"),
        "part_empty.toml": mesh("mesh_empty.obj"),
        "part_nan.toml": mesh("mesh_nan.obj"),
        "part_degenerate.toml": mesh("mesh_flat.obj"),
        "part_png.toml": mesh("mesh_png.stl"),
        "part_two_corners.toml": mesh("mesh_two_corners.stl"),
        "part_two_corners_binary.toml": mesh("mesh_two_corners_binary.stl"),
        "part_format.toml": mesh("part.step"),
        "part_no_extension.toml": mesh("/dev/stdin"),  # was "format '.' is not a mesh"
        "part_facing.toml": sub("max_angle = 45.0", "max_angle = 10.0",
                                sub("facing = [-1.0, 0.0, 0.0]", "facing = [0.0, 1.0, 0.0]")),
        "part_units.toml": sub('units = "m"', 'units = "ft"'),
        "part_mm_as_m.toml": sub('units = "m"', 'units = "mm"'),
        "part_and_panel.toml": job + "[panel]\ncenter = [0.7, 0, 0.16]\n",
        "part_no_mesh.toml": sub('mesh = "curved_panel.stl"', ""),
        "part_mesh_number.toml": sub('mesh = "curved_panel.stl"', "mesh = 3"),
        "part_rotation.toml": sub("rotation = [0.0, 0.0, 0.0]", "rotation = [0.0, 'x', 0.0]"),
        "part_max_angle.toml": sub("max_angle = 45.0", "max_angle = 200.0"),
        "part_zero_facing.toml": sub("facing = [-1.0, 0.0, 0.0]", "facing = [0.0, 0.0, 0.0]"),
        "part_far.toml": sub("position = [0.0, 0.0, 0.0]", "position = [0.4, 0.0, 0.0]"),
        # a part on a moving line (docs/model.md §24)
        "part_line.toml": job + line,
        "part_line_zero.toml": job + line.replace("[0.0, 1.0, 0.0]", "[0.0, 0.0, 0.0]"),
        "part_line_coats.toml": job + "coats = 2\n" + line,
        "part_line_past.toml": sub("position = [0.0, 0.0, 0.0]",
                                   "position = [0.0, 2.5, 0.0]") + line,
        # malformed meshes, faces nobody can paint, absurd values
        "mesh_zero_based.obj": square + "f 0 2 1\n",
        "mesh_relative_out.obj": square + "f 1 3 -4\n",
        "mesh_counts.ply": "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                           "property float y\nproperty float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n"
                           + square.replace("v ", "") + "3 0 2 1\n",
        "mesh_negative.ply": "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n"
                             + square.replace("v ", "") + "3 0 2 -1\n",
        "mesh_table.obj": "v 0.39 -0.06 0\nv 0.51 -0.06 0\nv 0.51 0.06 0\nv 0.39 0.06 0\n"
                          "f 1 2 3\nf 1 3 4\n",
        # a plate behind a sheet turned away from the robot
        "mesh_hidden.obj": square + "v 0.6 -0.3 0\nv 0.6 0.3 0\nv 0.6 0.3 0.4\n"
                           "f 1 3 2\nf 4 5 6\n",
        "part_zero_based.toml": mesh("mesh_zero_based.obj"),
        "part_relative_out.toml": mesh("mesh_relative_out.obj"),
        "part_counts.toml": mesh("mesh_counts.ply"),
        "part_negative.toml": mesh("mesh_negative.ply"),
        "part_table.toml": sub("facing = [-1.0, 0.0, 0.0]", "facing = [0.0, 0.0, 1.0]",
                               mesh("mesh_table.obj")),
        "part_hidden.toml": mesh("mesh_hidden.obj"),
        "part_max_angle_90.toml": sub("max_angle = 45.0", "max_angle = 90.0"),
        "part_coats.toml": job + "coats = 1000000000\n",
        "part_spacing.toml": job + "spacing = 1e-5\n",
    }


def _jobs() -> dict[str, bytes | str]:
    """examples/paint.toml and every bad job derived from it (job_*.toml)."""
    job = (EXAMPLES / "paint.toml").read_text()

    def sub(old: str, new: str) -> str:
        assert old in job, old
        return job.replace(old, new, 1)

    normal = "normal = [-1.0, 0.0, 0.0]"
    return {
        "job_good.toml": job,
        "job_unknown_key.toml": sub("width = 0.26", "width = 0.26\ncolour = 'red'"),
        "job_unknown_table.toml": job + "\n[conveyor]\nspeed = 1\n",
        "job_robot_table.toml": job + "\n[robot]\nspeed = 1\n",
        "job_top_level_key.toml": "units = 'SI'\n" + job,
        "job_missing_key.toml": sub("flow = 1.5e-7", ""),
        "job_missing_table.toml": job.split("[job]")[0],
        "job_table_not_table.toml": "job = 3\n" + job.split("[job]")[0],
        "job_nan.toml": sub("sigma = 0.010", "sigma = nan"),
        "job_inf.toml": sub("center = [0.70, 0.0, 0.16]", "center = [inf, 0.0, 0.16]"),
        "job_zero_width.toml": sub("width = 0.26", "width = 0"),
        "job_negative_height.toml": sub("height = 0.12", "height = -0.12"),
        "job_negative_standoff.toml": sub("standoff = 0.15", "standoff = -0.15"),
        "job_zero_flow.toml": sub("flow = 1.5e-7", "flow = 0.0"),
        "job_zero_thickness.toml": sub("thickness = 25e-6", "thickness = 0"),
        "job_zero_normal.toml": sub(normal, "normal = [0.0, 0.0, 0.0]"),
        "job_tiny_normal.toml": sub(normal, "normal = [1e-300, 0.0, 0.0]"),
        "job_vertical_normal.toml": sub(normal, "normal = [0.0, 0.0, -2.0]"),
        "job_normal_2.toml": sub(normal, "normal = [-1.0, 0.0]"),
        "job_normal_4.toml": sub(normal, "normal = [-1.0, 0.0, 0.0, 0.0]"),
        "job_normal_string.toml": sub(normal, "normal = 'towards the robot'"),
        "job_normal_text_entry.toml": sub(normal, "normal = [-1.0, 0.0, '0']"),
        "job_normal_nested.toml": sub(normal, "normal = [[-1.0], [0.0], [0.0]]"),
        "job_string_number.toml": sub("width = 0.26", "width = '0.26'"),
        "job_bool.toml": sub("height = 0.12", "height = true"),
        "job_date.toml": sub("standoff = 0.15", "standoff = 1979-05-27"),
        "job_mm.toml": sub("width = 0.26", "width = 260"),
        "job_huge_center.toml": sub("center = [0.70, 0.0, 0.16]", "center = [700, 0, 160]"),
        "job_direction.toml": job + "direction = 'diagonal'\n",
        "job_coats_zero.toml": job + "coats = 0\n",
        "job_coats_float.toml": job + "coats = 1.5\n",
        "job_spacing.toml": job + "spacing = -0.005\n",
        "job_speed.toml": job + "speed = 0\n",
        "job_wide_spacing.toml": job + "spacing = 0.2\n",
        "job_actuators_missing.toml": job + "actuators = 'nope.toml'\n",
        "job_actuators_number.toml": job + "actuators = 3\n",
        "job_actuators_empty.toml": job + "actuators = ''\n",
        "job_actuators_bad.toml": job + "actuators = 'act_nan.toml'\n",
        "job_duplicate.toml": sub("width = 0.26", "width = 0.26\nwidth = 0.3"),
        "job_latin1.toml": "# Pollard m\xfcde\n".encode("latin-1") + job.encode(),
        "job_nul.toml": job.encode().replace(b"0.26", b"0.2\x006"),
        "job_out_of_reach.toml": sub("center = [0.70, 0.0, 0.16]", "center = [2.0, 0.0, 0.16]"),
        "job_too_big.toml": sub("width = 0.26", "width = 2.6"),
        "job_thin.toml": sub("thickness = 25e-6", "thickness = 1e-9"),
        "job_thin_coats.toml": job + "coats = 40\n",
        "job_flow_slip.toml": sub("flow = 1.5e-7", "flow = 150"),  # m³/s: 1.5e-7 meant
        "job_fast.toml": job + "speed = 50.0\n",
        # a moving line (docs/model.md §24)
        "job_line_zero.toml": job + "[line]\nspeed = 0.03\ndirection = [0.0, 0.0, 0.0]\n",
        "job_line_still.toml": job + "[line]\nspeed = 0\ndirection = [0.0, 1.0, 0.0]\n",
        "job_line_absurd.toml": job + "[line]\nspeed = 30\ndirection = [0.0, 1.0, 0.0]\n",
        "job_line_text.toml": job + "[line]\nspeed = 'fast'\ndirection = [0.0, 1.0, 0.0]\n",
        "job_line_key.toml": job + "[line]\nspeed = 0.03\ndirection = [0, 1, 0]\npitch = 1\n",
        "job_line_table.toml": "line = 3\n" + job,
        # two robots whose folders are one on a case-insensitive file system
        "job_robots_case.toml": job + "[line]\nspeed = 0.03\ndirection = [0.0, 1.0, 0.0]\n"
                                "[[robot]]\nname = 'low'\nbase = [0.0, 0.0, 0.0]\n"
                                "[[robot]]\nname = 'LOW'\nbase = [0.0, 0.75, 0.0]\n",
    }


def _output_folders(path_csv: str, nan_csv: str) -> dict[str, bytes | str | None]:
    """Folders of the kind ``workspace`` and ``paint`` write, each broken in one way."""
    ws_header = "x,y,z,psi,theta,phi,reachable,reason,conditioning\n"
    ws_row = "0.55,0,0.16,0,0,0,1,0,0.3\n"
    film = "x,y,z,u,v,thickness\n" + "".join(
        f"0.55,{u},{v},{u},{v},2.5e-05\n" for v in (0, 0.1) for u in (0, 0.1))
    report = '{"grid": {"nu": 2, "nv": 2, "resolution": 0.1}, "target": 2.5e-05}\n'

    def paint(name: str, path: str = path_csv, table: str | bytes = film,
              json: str | bytes = report) -> dict:
        return {f"{name}/path.csv": path, f"{name}/thickness.csv": table,
                f"{name}/paint.json": json}

    return {
        "ws_empty/": None,
        "ws_header/workspace.csv": ws_header,
        "ws_wrong/workspace.csv": "a,b\n1,2\n",
        "ws_binary/workspace.csv": b"\x89PNG\r\n\x1a\n" + bytes(range(256)),
        "ws_garbage/workspace.parquet": b"PAR1garbage",
        "ws_text/workspace.csv": ws_header + ws_row.replace("0.3", "abc"),
        "ws_nan/workspace.csv": ws_header + ws_row.replace("0.55", "nan"),
        "ws_folder/workspace.csv/": None,
        "ws_precious/workspace.csv": PRECIOUS, "ws_precious/workspace.json": PRECIOUS,
        "ws_precious/workspace.png": PRECIOUS, "ws_precious/workspace.parquet": PRECIOUS,
        "paint_empty/": None,
        **paint("paint_no_json", json=None),
        **paint("paint_bad_json", json="{"),
        **paint("paint_list_json", json="[]"),
        **paint("paint_binary_json", json=b"\x89PNG\r\n\x1a\n"),
        **paint("paint_no_grid", json='{"target": 2.5e-05}'),
        **paint("paint_text_grid", json=report.replace("2,", '"two",')),
        **paint("paint_mismatch", table=film + "0.55,0,0,0,0,2.5e-05\n"),
        **paint("paint_no_thickness", table=film.replace("thickness", "film")),
        **paint("paint_text_table", table=film.replace("2.5e-05", "abc")),
        **paint("paint_nan_table", table=film.replace("2.5e-05", "nan").replace(
            "nan", "2.5e-05", 2)),
        **paint("paint_binary_table", table=b"\x89PNG\r\n\x1a\n" + bytes(range(256))),
        **paint("paint_bad_path", path=nan_csv),
        **paint("paint_empty_path", path=""),
        **paint("paint_precious", path=PRECIOUS, table=PRECIOUS, json=PRECIOUS),
        "paint_precious/thickness.png": PRECIOUS, "paint_precious/thickness.parquet": PRECIOUS,
        **paint("paint_garbage_parquet", table=None),
        "paint_garbage_parquet/thickness.parquet": b"PAR1garbage",
    }


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    root = tmp_path_factory.mktemp("fuzz")
    for name, content in _files().items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        if name.endswith("/"):
            (root / name).mkdir()
        elif content is None:  # a file left out of its folder
            continue
        elif isinstance(content, bytes):
            (root / name).write_bytes(content)
        else:
            (root / name).write_text(content, encoding="utf-8")
    import pyarrow as pa
    import pyarrow.parquet as pq

    rows = [[float(c) for c in r.split(",")] for r in _good_rows()]
    pq.write_table(pa.table({n: [r[i] for r in rows] for i, n in enumerate(HEADER.split(","))}),
                   root / "traj.parquet")  # a real Parquet trajectory
    _simulation_files(root)
    sock = socket.socket(socket.AF_UNIX)  # a socket: exists, cannot be opened as a file
    sock.bind(str(root / "socket.csv"))
    yield root
    sock.close()


def _simulation_files(root: Path) -> None:
    """A real simulation and run table of good.csv, and damaged copies of the simulation."""
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        for argv in (["simulate", "--out", "sim.csv"], ["simulate", "--out", "sim.parquet"],
                     ["run", "--out", "run.csv"]):
            assert main([*argv[:2], str(root / argv[2]), "--trajectory",
                         str(root / "good.csv")]) == 0
    header, *rows = (root / "sim.csv").read_text().splitlines()

    def write(name, lines):
        (root / name).write_text("\n".join(lines) + "\n")

    def cell(r, c, value):
        out = [line.split(",") for line in rows]
        out[r][c] = value
        return [",".join(line) for line in out]

    write("sim_header.csv", [header])
    write("sim_one.csv", [header, rows[0]])
    write("sim_nan.csv", [header, *cell(3, 0, "NaN")])
    write("sim_inf.csv", [header, *cell(5, 7, "-inf")])
    write("sim_empty_cell.csv", [header, *cell(5, 7, "")])
    write("sim_text_cell.csv", [header, *cell(5, 7, "abc")])
    write("sim_swap.csv", [header, *rows[:3], rows[4], rows[3], *rows[5:]])
    write("sim_repeat.csv", [header, *rows[:4], rows[3], *rows[4:]])
    write("sim_truncated.csv", [header, *rows[:-1], rows[-1][:20]])
    write("sim_duplicate.csv", [header + ",t", *(r + ",0" for r in rows)])
    (root / "sim_parquet.csv").write_bytes((root / "sim.parquet").read_bytes())


# --- the cases ---------------------------------------------------------------------------------
TRAJ_COMMANDS = {  # argv prefix of each command that takes --trajectory; nothing else needed
    "run": ["run", "--out", "out.csv"],
    "view": ["view", "--html", "out.html"],
    "plot": ["plot", "--out", "plots"],
    "report": ["report", "--no-cross-check", "--out", "out.md"],
    "size": ["size", "--actuators", ACT, "--out", "out.md"],
    "simulate": ["simulate", "--out", "out.csv"],
    "stiffness": ["stiffness", "--actuators", ACT, "--out", "out.csv"],
}
SIM = ["simulate", "--trajectory", "good.csv", "--out", "out.csv"]  # 0.22 s: 220 steps
SHORT = ["--samples", "11", "--duration", "0.2"]  # a short thesis trajectory

# every command, every bad trajectory file
BAD_TRAJECTORIES = [
    ("missing.csv", "No such file"),
    ("afolder", "Is a directory"),
    ("socket.csv", "cannot read trajectory file"),
    ("empty.csv", "empty file"),
    ("blank.csv", "empty file"),
    ("comments.csv", "empty file"),
    ("header_only.csv", "need at least 2 samples, found 0"),
    ("one_row.csv", "need at least 2 samples, found 1"),
    ("three_rows.csv", "too few for the quintic spline"),
    ("truncated.csv", "fields, expected 7"),
    ("cut_number.csv", "is not a number"),
    ("nan_row.csv", "is not finite"),
    ("inf_row.csv", "is not finite"),
    ("empty_cell.csv", "'' is not a number"),
    ("text_cell.csv", "'abc' is not a number"),
    ("comma_decimal.csv", "fields, expected 7"),
    ("decreasing_t.csv", "decreasing time"),
    ("duplicate_t.csv", "duplicate time"),
    ("duplicate_column.csv", "duplicate column"),
    ("unknown_column.csv", "unknown column 'speed'"),
    ("missing_column.csv", "missing column(s) phi"),
    ("mm.csv", "looks like millimetres"),
    ("deg.csv", "looks like degrees"),
    ("no_t.csv", "missing column(s) t"),
    ("trailing_comma.csv", "row 2 has 8 fields, expected 7"),
    ("partial_derivatives.csv", "must come as a full set"),
    ("semicolon.csv", "unknown column"),
    ("tabs.csv", "unknown column"),
    ("nul.csv", "NUL"),
    ("latin1.csv", "not UTF-8 text"),
    ("utf16.csv", "not UTF-8 text"),
    ("png.csv", "not UTF-8 text"),
    ("gzip.csv", "not UTF-8 text"),
    ("long_field.csv", "not CSV (field larger than field limit"),
    ("fast.csv", "column d_x disagrees with the positions"),
    ("tiny_dt.csv", "time step too small"),
    ("", "an empty name"),
    ("garbage.parquet", "Parquet"),
    ("parquet.csv", "Parquet"),
    ("traj.parquet", "Parquet"),
]
CASES = [([*prefix, "--trajectory", name], says)
         for prefix in TRAJ_COMMANDS.values() for name, says in BAD_TRAJECTORIES]

# numbers: every numeric option, every way a number can be wrong
POSITIVE = [("0", "must be > 0"), ("-1", "must be > 0"), ("nan", "finite"),
            ("inf", "finite"), ("-inf", "finite"), ("abc", "not a number"),
            ("", "not a number"), ("1e999", "finite"), ("0x10", "not a number"),
            ("1,5", "not a number")]
NONNEGATIVE = [("-1", "must be >= 0"), ("-1e-300", "must be >= 0"), ("nan", "finite"),
               ("inf", "finite"), ("abc", "not a number"), ("", "not a number")]
FINITE = [("nan", "finite"), ("inf", "finite"), ("abc", "not a number")]
OPTIONS = [  # (argv prefix, option, bad values)
    (["run", "--out", "out.csv"], "--duration", POSITIVE),
    (["run", "--out", "out.csv"], "--wrist-margin", NONNEGATIVE),
    (["run", "--out", "out.csv"], "--singularity-margin", NONNEGATIVE),
    (["view", *SHORT, "--html", "out.html"], "--fps", POSITIVE),
    (SIM, "--wn", NONNEGATIVE),
    (SIM, "--zeta", NONNEGATIVE),
    (SIM, "--torque-limit", POSITIVE[:7]),
    (SIM, "--payload", NONNEGATIVE),
    (SIM, "--mass-error", FINITE),
    (SIM, "--armature", NONNEGATIVE[:4]),
    (SIM, "--viscous", NONNEGATIVE[:4]),
    (SIM, "--coulomb", NONNEGATIVE[:4]),
    (SIM, "--noise", NONNEGATIVE[:4]),
    (SIM, "--velocity-noise", NONNEGATIVE[:4]),
    (SIM, "--dt", FINITE),  # parsing only; the step's meaning: helper control
    (SIM, "--control-period", FINITE),
]
CASES += [([*prefix, option, value], says)
          for prefix, option, values in OPTIONS for value, says in values]
COUNTS = [("0", None), ("-3", None), ("2.5", "not an integer"), ("abc", "not an integer"),
          ("", "not an integer"), ("nan", "not an integer"), ("1e3", "not an integer")]
CASES += [([*prefix, option, value], says or "must be")
          for prefix, option, low in ((["run", "--out", "out.csv"], "--samples", 2),
                                      (["view", "--html", "out.html"], "--samples", 2),
                                      (["run", "--out", "out.csv"], "--workers", 1),
                                      (["sweep", "--grid", "grid_good.toml"], "--workers", 1),
                                      (["plot", "--out", "plots"], "--dpi", 10),
                                      (SIM, "--seed", 0))
          for value, says in COUNTS if not (value == "0" and low == 0)]

# huge and absurd values that parse
CASES += [
    (["view", "--samples", "10000000000", "--html", "out.html"], "over the budget of 1e+06"),
    (["plot", "--samples", "10000000000", "--out", "plots"], "over the budget of 1e+06"),
    (["simulate", "--samples", "10000000000"], "over the budget of 1e+06"),
    (["run", "--workers", "65", "--out", "out.csv"], "must be between 1 and 64"),
    (["plot", "--dpi", "100000", "--out", "plots"], "must be between 10 and 1200"),
    (["run", "--duration", "1e-300", *SHORT[:2], "--out", "out.csv"], "duration"),
    (["view", *SHORT, "--fps", "1e300", "--html", "out.html"], "--fps 1e+300: 1e+300 key frames/s"),
    (["view", *SHORT, "--fps", "1e6", "--html", "out.html"], "more than 100000: lower"),
    (["run", *SHORT, "--wrist-margin", "2", "--out", "out.csv"], "must be at most 1, got 2"),
    ([*SIM, "--mass-error", "-1"], "mass"),
    ([*SIM, "--mass-error", "-2.5"], "mass"),
    ([*SIM, "--torque-limit", "1", "2"], "takes 1 value (all actuators) or 6, got 2"),
    ([*SIM, "--wn", "1e300"], "must be at most 1e+06 rad/s"),
    # one tick only: the controller would act once, at the start
    ([*SIM, "--control-period", "1e300"], "--control-period 1e+300 s is longer than the "
                                          "trajectory (0.22 s)"),
    ([*SIM, "--control-period", "0.3", "--dt", "1e-3"], "longer than the trajectory"),
    # --force does not pass what memory holds
    ([*SIM, "--dt", "1e-300", "--force"], "2.2e+299 RK4 steps (0.22 s, --control-period "
                                          "0.001 s, --dt 1e-300 s): more than a simulation"),
    ([*SIM, "--control-period", "1e-300", "--force"], "even with --force"),
    # a run that starts says so (progress, silenced by --quiet); then its failure is one line
    ([*SIM, "--quiet", "--payload", "1e300"], "diverged"),
    ([*SIM, "--quiet", "--wn", "1e4"], "the gains are too high for the control period (ω·T = 10"),
    # the plant runs away within a tick: the encoders' angles close no loop
    (["simulate", "--duration", "2", "--quiet", "--wn", "1e6", "--out", "out.csv"],
     "the sensed actuator angles close no loop (leg"),
    # saturated, the robot falls: stopped where it leaves its joint limits (docs/model.md §18)
    (["simulate", "--trajectory", str(EXAMPLES / "figure8.csv"), "--out", "out.csv", "--quiet",
      "--torque-limit", "0.5"], "the plant left its joint limits: joint theta43"),
]

# model parameters: files and --set, on the commands that load the model
BAD_PARAMS = [
    ("missing.toml", "does not exist"),
    ("afolder", "cannot be read"),
    ("socket.csv", "cannot be read"),
    ("empty.csv", "not valid TOML"),  # fine as TOML? an empty file is a valid partial file
    ("broken.toml", "is not valid TOML"),
    ("latin1.toml", "is not UTF-8 text"),
    ("nul.toml", "is not valid TOML"),
    ("png.csv", "is not UTF-8 text"),
    ("huge.toml", "must be at most 10 m"),
    ("mm.toml", "must be at most 10 m"),
    ("nan.toml", "finite"),
    ("inf.toml", "finite"),
    ("negative_mass.toml", "must be > 0"),
    ("zero_mass.toml", "must be > 0"),
    ("string.toml", "must be a number"),
    ("bool.toml", "must be a number"),
    ("array.toml", "must be a number"),
    ("unknown_section.toml", "chain9"),
    ("unknown_key.toml", "x33"),
    ("short_com.toml", "com"),
]
del BAD_PARAMS[3]  # an empty parameter file is a valid partial file: the shipped model
MODEL_COMMANDS = [["urdf", "--out", "out.urdf"], ["info"], ["export", "--out", "out.xml"],
                  ["run", *SHORT, "--out", "out.csv"]]
CASES += [([*prefix, "--params", name], says)
          for prefix in MODEL_COMMANDS[:2] for name, says in BAD_PARAMS]
CASES += [([*prefix, "--params", name], says)
          for prefix in MODEL_COMMANDS[2:] for name, says in BAD_PARAMS[::4]]
BAD_SETS = [
    ("chain0.x32", "expected KEY=VALUE"),
    ("=0.3", "expected KEY=VALUE"),
    ("chain0.x32=", "not a number"),
    ("chain0.x32=abc", "not a number"),
    ("chain0.x32=0,33", "not a number"),
    ("chain0.x32=nan", "finite"),
    ("chain0.x32=inf", "finite"),
    ("chain0.x32=-0.33", "must be"),
    ("chain0.x32=0", "must be"),
    ("chain0.x32=330", "must be at most 10 m"),
    ("chain0.x32=1e400", "finite"),
    ("chain0.x32=true", "must be a number"),
    ("chain0.x32=[0.33]", "must be a number"),
    ("chain0.x33=0.33", "names no parameter"),
    ("chain9.x32=0.33", "names no parameter"),
    ("bodies.gun.mass=-1", "must be > 0"),
    ("bodies.gun.mass=0", "must be > 0"),
    ("bodies.gun.com[7]=0", "com"),
    ("bodies.gun.com[x]=0", "com"),
    ("bodies.gun.com=[0, 0]", "com"),
    ("home.tip=[2.9, 0, 0.16]", "home"),
    ("leg1.side=2", "side"),
    ("chain0.x32 = 0.33 = 1", "not a number"),
    ("chain0..x32=0.33", "not a dotted parameter key"),
    ("home.orientation=[0, 0, 1e9]", "phi = 1.74533e+07 is absurd"),
    ("home.tip=[0.55, 0, 9]", "is unreachable"),
    ("leg1.x87=0.01", "is unreachable"),
    ("bodies.gun.inertia=[[1, 0, 0], [0, 1, 0], [0, 0, -1]]", "positive definite"),
    ("bodies.gun.inertia=[[1, 2, 0], [0, 1, 0], [0, 0, 1]]", "symmetric"),
    ("bodies.gun.inertia=[[1, 0, 0], [0, 1, 0], [0, 0, 5]]", "triangle inequality"),
    ("bodies.gun.com=[nan, 0, 0]", "must be a finite number"),
    ("limits.theta21.lower=10", "must be greater than"),
    ("branches.chain0=7", "must be -1 or +1"),
]
CASES += [([*prefix, "--set", text], says)
          for prefix in MODEL_COMMANDS for text, says in BAD_SETS[:: 1 if prefix[0] == "urdf"
                                                                   else 3]]

# actuator files (size; simulate --actuators)
BAD_ACTUATORS = [
    ("missing.toml", "does not exist"),
    ("afolder", "cannot be read"),
    ("empty.csv", "missing table"),
    ("broken.toml", "is not valid TOML"),
    ("latin1.toml", "is not UTF-8 text"),
    ("act_missing_table.toml", "missing table(s) [theta1817]"),
    ("act_unknown_table.toml", "[theta99] is not an actuator"),
    ("act_missing_key.toml", "max_speed' is missing"),
    ("act_unknown_key.toml", "unknown key"),
    ("act_negative.toml", "must be > 0"),
    ("act_zero.toml", "must be > 0"),
    ("act_nan.toml", "must be a finite number"),
    ("act_inf.toml", "must be a finite number"),
    ("act_string.toml", "must be a number"),
    ("act_huge.toml", "must be between"),
    ("act_continuous.toml", "exceeds"),
    ("act_heavy_rotor.toml", "'theta21.rotor_inertia' = 5: the motor would take 5e+04 s to "
                             "bring its own rotor to max_speed at peak_torque (Jm·ω/τ), 5e+03 "
                             "times the 10 s of any motor"),
]
CASES += [(["size", *SHORT, "--out", "out.md", "--actuators", name], says)
          for name, says in BAD_ACTUATORS]
CASES += [([*SIM, "--actuators", name], says) for name, says in BAD_ACTUATORS[::3]]

# sweep grids
SWEEP = ["sweep", "--out", "out.csv", "--workers", "1", "--grid"]
CASES += [([*SWEEP, name], says) for name, says in [
    ("missing.toml", "does not exist"),
    ("afolder", "cannot be read"),
    ("broken.toml", "not valid TOML"),
    ("latin1.toml", "not UTF-8 text"),
    ("png.csv", "not UTF-8 text"),
    ("empty.csv", "variant"),
    ("grid_unknown.toml", "unknown entry 'speed'"),
    ("grid_bad_key.toml", "x33"),
    ("grid_bad_value.toml", "long"),
    ("grid_nan.toml", "finite"),
    ("grid_mm.toml", "must be at most 10 m"),
    ("grid_empty_list.toml", "empty"),
    ("grid_scalar.toml", "list"),
    ("grid_samples.toml", "samples"),
    ("grid_duration.toml", "duration"),
    ("grid_traj.toml", "nope.csv"),
    ("grid_bad_traj.toml", "is not finite"),
    ("grid_variant.toml", "x33"),
    ("grid_variant_table.toml", "'variant' must be an array of tables"),
    ("grid_params.toml", "nope.toml"),
]]

# result tables given to plot/report --simulation
BAD_SIMULATIONS = [
    ("missing.csv", "no such result file"),
    ("afolder", "is a folder"),
    ("empty.csv", "not a readable csv result table"),
    ("ab.csv", "ab.csv"),
    ("ab_rows.csv", "ab_rows.csv"),
    ("t_only.csv", "t_only.csv"),
    ("sim_text.csv", "not a readable csv result table"),
    ("latin1.csv", "not UTF-8 text"),
    ("garbage.parquet", "not a readable parquet result table"),
    ("good.csv", "not a simulation table"),  # a trajectory
    ("run.csv", "not a simulation table"),
    ("sim_header.csv", "no rows"),
    ("sim_one.csv", "needs at least 2 rows"),
    ("sim_nan.csv", "sample 3, column 't': nan is not finite"),
    ("sim_inf.csv", "is not finite"),
    ("sim_empty_cell.csv", "line 7, column 'theta21_1': no value"),
    ("sim_text_cell.csv", "not a readable csv result table"),
    ("sim_swap.csv", "does not follow"),
    ("sim_repeat.csv", "does not follow"),
    ("sim_truncated.csv", "line 13, column 'theta43': no value"),
    ("sim_duplicate.csv", "duplicate column 't'"),
    ("sim_parquet.csv", "not UTF-8 text"),
    ("socket.csv", "socket.csv"),
]
CASES += [([*prefix, "--simulation", name], says)
          for prefix in (["plot", "--out", "plots"], ["report", *SHORT, "--out", "out.md"])
          for name, says in BAD_SIMULATIONS]

# outputs that cannot be written, and existing ones a failure must not touch
CASES += [
    (["run", *SHORT, "--out", ""], "an empty name"),
    (["view", *SHORT, "--html", ""], "an empty name"),
    (["info", "--params", ""], "an empty name"),
    (["size", *SHORT, "--actuators", ""], "an empty name"),
    (["sweep", "--grid", ""], "an empty name"),
    (["plot", "--simulation", "", "--out", "plots"], "an empty name"),
    (["run", "--out", "-", "--trajectory", "nan_row.csv"], "is not finite"),
    (["run", "--out", "-", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["simulate", "--out", "-", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["urdf", "--out", "-", "--set", "chain0.x32=nan"], "finite"),
    (["export", "--out", "-", "--set", "chain0.x32=abc"], "not a number"),
    (["report", *SHORT, "--out", "-", "--simulation", "sim_nan.csv"], "is not finite"),
    (["size", "--actuators", ACT, "--out", "-", "--trajectory", "still.csv"],
     "the path does not move the actuators"),
    (["urdf", "--out", "afile/x.urdf"], "afile is a file, not a folder"),
    (["urdf", "--out", "afolder"], "is a folder"),
    (["urdf", "--out", "/proc/pollard.urdf"], "/proc/pollard.urdf"),
    (["urdf", "--out", "existing.urdf", "--set", "chain0.x32=nan"], "finite"),
    (["export", "--out", "afolder"], "is a folder"),
    (["export", "--out", "/proc/pollard.xml"], "/proc/pollard.xml"),
    (["export", "--out", "existing.xml", "--params", "broken.toml"], "not valid TOML"),
    (["export", "--format", "urdf"], "invalid choice"),
    (["run", *SHORT, "--out", "afile/run.csv"], "not a folder"),
    (["run", *SHORT, "--out", "afolder"], "is a folder"),
    # a folder's trailing '/': was written as the file run.csv
    (["run", *SHORT, "--out", "run.csv/"], "run.csv/: ends in '/', as a folder's name does, "
                                           "but a file is expected"),
    (["run", *SHORT, "--out", "/proc/run.csv"], "/proc/run.csv"),
    (["run", *SHORT, "--out", "/proc/run.parquet"], "/proc/run.parquet"),
    (["run", "--out", "existing.csv", "--trajectory", "nan_row.csv"], "is not finite"),
    (["run", "--out", "existing.parquet", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["run", "--out", "existing.csv", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["view", *SHORT, "--html", "afolder"], "is a folder"),
    (["view", *SHORT, "--html", "/proc/v.html"], "/proc/v.html"),
    (["view", "--html", "existing.html", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["plot", *SHORT, "--out", "afile"], "names a file"),
    (["plot", *SHORT, "--out", "afile/p"], "not a folder"),
    (["plot", "--out", "plots", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["report", *SHORT, "--out", "afolder"], "is a folder"),
    (["report", *SHORT, "--out", "/proc/r.md"], "/proc/r.md"),
    (["report", "--out", "existing.md", "--trajectory", "unreachable.csv"], "cannot reach"),
    (["size", *SHORT, "--actuators", ACT, "--out", "afolder"], "is a folder"),
    (["size", *SHORT, "--actuators", ACT, "--retime", "afolder"], "is a folder"),
    (["size", *SHORT, "--actuators", ACT, "--retime", "afile/r.csv"], "not a folder"),
    (["size", *SHORT, "--actuators", ACT, "--plot", "afile"], "names a file"),
    (["size", *SHORT, "--actuators", ACT, "--retime", "-"], "standard output"),
    (["size", *SHORT, "--actuators", ACT, "--out", "/proc/s.md"], "/proc/s.md"),
    (["size", "--actuators", ACT, "--out", "existing.md", "--trajectory", "still.csv"],
     "the path does not move the actuators"),
    (["size", "--actuators", ACT, "--trajectory", "still.csv"],
     "the path does not move the actuators"),
    (["size", "--actuators", "act_weak.toml", "--out", "existing.md", *SHORT], "rating"),
    (["size", *SHORT, "--out", "out.md"], "required"),
    ([*SIM, "--out", "afolder"], "is a folder"),
    ([*SIM, "--out", "afile/s.csv"], "not a folder"),
    ([*SIM, "--out", "/proc/s.csv"], "/proc/s.csv"),
    (["simulate", "--out", "existing.csv", "--trajectory", "unreachable.csv"], "cannot reach"),
    ([*SIM, "--controller", "lqr"], "invalid choice"),
    ([*SIM, "--start", "middle"], "invalid choice"),
    (["sweep", "--grid", "grid_good.toml", "--out", "afolder"], "is a folder"),
    (["sweep", "--grid", "grid_good.toml", "--out", "/proc/s.csv"], "/proc/s.csv"),
    (["sweep", "--out", "out.csv"], "required"),
    (["report", *SHORT, "--format", "html"], "invalid choice"),
    (["run", "--frobnicate"], "unrecognized arguments"),
    (["run", "--out"], "expected one argument"),
    (["info", "extra"], "unrecognized arguments"),
    (["frobnicate"], "invalid choice"),
]

# workspace: every case fails before the map is computed (the misses: one coarse look for the
# reachable box, ~0.3 s)
WS = ["workspace", "--quiet", "--out", "ws"]
VOLUME_MISS = ["--volume", "--resolution", "0.5", "--bounds", "x=5:6,y=5:6,z=5:6"]
REACHABLE_BOX = "reachable region spans x ∈ [0.328, 0.697], y ∈ [-0.287, 0.287]"
CASES += [([*WS, *extra], says) for extra, says in [
    (["--plane", "x"], "--plane: plane 'x': expected AXIS=VALUE"),
    (["--plane", "x="], "plane x = '' is not a number [m]"),
    (["--plane", "w=0.5"], "the axis must be x, y or z, got 'w'"),
    (["--plane", "=0.5"], "the axis must be x, y or z, got ''"),
    (["--plane", ""], "plane '': expected AXIS=VALUE"),
    (["--plane", "x=abc"], "plane x = 'abc' is not a number"),
    (["--plane", "x=0.5=1"], "is not a number"),
    (["--plane", "x=0,55"], "is not a number"),
    (["--plane", "x=nan"], "must be a finite number"),
    (["--plane", "x=inf"], "must be a finite number"),
    (["--plane", "x=1e9"], f"plane x = 1e+09 m misses the robot (its reach at this "
                           f"orientation is x ∈ [-0.74, 0.86] m at most); at orientation "
                           f"(0, 0, 0) deg the {REACHABLE_BOX}"),  # (said with less: 250)
    (["--plane", "z=-5"], "misses the robot"),
    (["--plane", "x=0.55", "--bounds", "y=5:6,z=5:6"], "no point of plane x = 0.55 m is "
                                                       "reachable on its grid y ∈ [5, 6] m, "
                                                       "z ∈ [5, 6] m (step 0.005 m); at "
                                                       "orientation"),
    (["--plane", "x=0.5", "--volume"], "not allowed with argument --plane"),
    (["--resolution", "0"], "must be > 0"),
    (["--resolution", "-1"], "must be > 0"),
    (["--resolution", "nan"], "finite"),
    (["--resolution", "inf"], "finite"),
    (["--resolution", "abc"], "not a number"),
    (["--resolution", "1e-9"], "resolution = 1e-09 m gives a grid of 2.56e+18 points (budget "
                               "1.074e+07), which would need 4.77e+11 GiB of memory (budget 2 "
                               "GiB); use a resolution of at least 0.000513 m"),
    (["--resolution", "1e-4", "--volume"], "would need about 1.71e+04 h"),
    (["--orientation", "0,0"], "expected three finite numbers PSI,THETA,PHI in degrees"),
    (["--orientation", "0,0,0,0"], "expected three finite numbers"),
    (["--orientation", "0,0,nan"], "expected three finite numbers"),
    (["--orientation", "0,inf,0"], "expected three finite numbers"),
    (["--orientation", "a,b,c"], "expected three finite numbers"),
    (["--orientation", ""], "expected three finite numbers"),
    (["--orientation", "0;0;0"], "expected three finite numbers"),
    (["--orientation", "0,0,1e300"], "phi = 1e+300 deg is absurd"),
    (["--bounds", "y"], "expected AXIS=LOW:HIGH items"),
    (["--bounds", "y=1"], "expected AXIS=LOW:HIGH items"),
    (["--bounds", ""], "expected AXIS=LOW:HIGH items"),
    (["--bounds", "w=0:1"], "expected AXIS=LOW:HIGH items"),
    (["--bounds", "y=a:b"], "expected AXIS=LOW:HIGH items"),
    (["--bounds", "y=1:0"], "--bounds 'y=1:0': bounds of y: the lower bound 1 m must be below "
                            "the upper bound 0 m"),
    (["--bounds", "y=0:0"], "must be below the upper bound"),
    (["--bounds", "y=nan:1"], "lower bound of y = nan must be a finite number"),
    (["--bounds", "y=-1e9:1e9"], "within ±1000 m"),
    (["--bounds", "y=0:1,y=0:1"], "y is given twice"),
    (["--bounds", "x=0:1"], "the plane fixes x = 0.55 m; give bounds for the other two axes"),
    (["--volume", "--bounds", "x=-1e3:1e3"], "would need about"),
    (["--wrist-margin", "-1"], "must be >= 0"),
    (["--wrist-margin", "2"], "--wrist-margin: must be at most 1"),
    (["--wrist-margin", "nan"], "finite"),
    (["--singularity-margin", "-1"], "must be >= 0"),
    (["--singularity-margin", "inf"], "finite"),
    (["--singularity-margin", "1e300"], "no tool position at all is reachable"),
    (["--dpi", "0"], "must be between 10 and 1200"),
    (["--format", "xlsx"], "invalid choice"),
    (["--format", ""], "invalid choice"),
    (["--out", ""], "an empty name"),
    (["--out", "afile"], "--out afile: exists and is not a folder"),
    (["--out", "existing.csv"], "exists and is not a folder"),
    (["--out", "afile/ws"], "afile is a file, not a folder"),
    (["--out", "/proc/ws"], "/proc/ws"),
    # '..' out of a folder that does not exist: it was made, and left behind empty
    (["--out", "w/../w2/"], "w/../w2: '..' climbs out of w, which does not exist (it would be "
                            "made only to be left empty): give w2"),
    (["--out", "afolder/../ws", "--resolution", "1e-9"], "would need"),  # out of one that is
    (["--out", "afolder", "--plane", "x=9"], "misses the robot"),  # an existing folder
    (["--out", "empty_folder", "--volume", "--resolution", "1e-9"], "would need"),
    # a streamed volume fails after its folder is made: new folders go, old files stay
    *(([*VOLUME_MISS, "--out", out, *fmt], "no point of the volume is reachable")
      for out in ("new/deep/ws", "ws_precious") for fmt in ([], ["--format", "parquet"])),
    (["--plane", "x=0.55", "--bounds", "y=5:6,z=5:6", "--out", "ws_precious"], "no point"),
    *((["--actuators", name], says) for name, says in BAD_ACTUATORS[::2]),
    (["--actuators", ""], "an empty name"),
    *((["--params", name], says) for name, says in BAD_PARAMS[::5]),
    *((["--set", text], says) for text, says in BAD_SETS[::6]),
    (["extra"], "unrecognized arguments"),
]]

# paint: bad job files fail as they are read; the plans that fail, within 0.3 s
PAINT = ["paint", "--out", "p", "--job"]
CASES += [([*PAINT, name], says) for name, says in [
    ("missing.toml", "paint job file 'missing.toml' does not exist"),
    ("afolder", "paint job file 'afolder' cannot be read"),
    ("socket.csv", "cannot be read"),
    ("empty.csv", "empty.csv: missing table [panel]"),
    ("blank.csv", "missing table [panel]"),
    ("broken.toml", "is not valid TOML"),
    ("good.csv", "is not valid TOML"),
    ("png.csv", "is not UTF-8 text"),
    ("gzip.csv", "is not UTF-8 text"),
    ("job_latin1.toml", "is not UTF-8 text (byte 11"),
    ("job_nul.toml", "is not valid TOML"),
    ("job_duplicate.toml", "is not valid TOML"),
    ("job_unknown_key.toml", "'panel.colour' = 'red': unknown key; [panel] takes center, "
                             "normal, width, height"),
    ("job_unknown_table.toml", "[conveyor] is not a table of a paint job"),
    ("job_robot_table.toml", "'robot' = {'speed': 1}: must be an array of tables [[robot]]"),
    ("job_top_level_key.toml", "[units] is not a table of a paint job"),
    ("job_missing_key.toml", "'gun.flow' is missing ([gun] needs standoff, sigma, flow)"),
    ("job_missing_table.toml", "missing table [job]"),
    ("job_table_not_table.toml", "'job' = 3: must be a table [job]"),
    ("job_nan.toml", "'gun.sigma' = nan: must be a finite number"),
    ("job_inf.toml", "'panel.center[0]' = inf: must be a finite number"),
    ("job_zero_width.toml", "'panel.width' = 0: must be > 0"),
    ("job_negative_height.toml", "'panel.height' = -0.12: must be > 0"),
    ("job_negative_standoff.toml", "'gun.standoff' = -0.15: must be > 0"),
    ("job_zero_flow.toml", "'gun.flow' = 0.0: must be > 0"),
    ("job_zero_thickness.toml", "'job.thickness' = 0: must be > 0"),
    ("job_zero_normal.toml", "'panel.normal' = [0.0, 0.0, 0.0]: has zero length"),
    ("job_tiny_normal.toml", "has zero length"),
    ("job_vertical_normal.toml", "'panel.normal' = [0.0, 0.0, -2.0]: is vertical"),
    ("job_normal_2.toml", "'panel.normal' = [-1.0, 0.0]: must be a list of 3 numbers"),
    ("job_normal_4.toml", "must be a list of 3 numbers"),
    ("job_normal_string.toml", "must be a list of 3 numbers"),
    ("job_normal_text_entry.toml", "'panel.normal[2]' = '0': must be a number"),
    ("job_normal_nested.toml", "'panel.normal[0]' = [-1.0]: must be a number"),
    ("job_string_number.toml", "'panel.width' = '0.26': must be a number"),
    ("job_bool.toml", "'panel.height' = True: must be a number"),
    ("job_date.toml", "'gun.standoff' = datetime.date(1979, 5, 27): must be a number"),
    ("job_mm.toml", "'panel.width' = 260: must be at most 10 m"),
    ("job_huge_center.toml", "'panel.center[0]' = 700: must be at most 10 m"),
    ("job_direction.toml", "'job.direction' = 'diagonal': must be 'horizontal' or 'vertical'"),
    ("job_coats_zero.toml", "'job.coats' = 0: must be a whole number >= 1"),
    ("job_coats_float.toml", "'job.coats' = 1.5: must be a whole number >= 1"),
    ("job_spacing.toml", "'job.spacing' = -0.005: must be > 0"),
    ("job_speed.toml", "'job.speed' = 0: must be > 0"),
    ("job_wide_spacing.toml", "spacing 0.2 m is too wide for σ = 0.01 m"),
    ("job_actuators_missing.toml", "actuator file 'nope.toml' does not exist"),
    ("job_actuators_number.toml", "'job.actuators' = 3: must be a file name"),
    ("job_actuators_empty.toml", "'job.actuators' = '': must be a file name"),
    ("job_actuators_bad.toml",
     "act_nan.toml: 'theta21.rotor_inertia' = nan: must be a finite number"),
    ("job_out_of_reach.toml", "the path leaves the workspace on a pass at panel (u, v) = "
                              "(-170, -73) mm: "),
    ("job_too_big.toml", "the largest panel that fits (same centre, proportions) is "
                         "0.446 × 0.020 m, planned in full"),
    # an absurd pass speed is a unit slip, said as a part's is (not the motors' 1.8 m/s) ...
    ("job_thin.toml", "the target needs a gun speed of 8264 m/s (gun.flow 1.5e-07 m³/s, 1 "
                      "coat(s) of 0.001 µm at spacing 18.15 mm), 826 times the 10 m/s of any "
                      "spray pass: gun.flow in m³/s, job.thickness in m?"),
    ("job_flow_slip.toml", "needs a gun speed of 3.306e+08 m/s (gun.flow 150 m³/s, 1 coat(s) "
                           "of 25 µm at spacing 18.15 mm), 3.31e+07 times the 10 m/s of any "
                           "spray pass: gun.flow in m³/s"),
    # ... while too many coats (13 m/s, one coat's 0.33) keep the motors' advice
    ("job_thin_coats.toml", "the target needs a gun speed of 13.22 m/s (40 coat(s) of 0.625 µm "
                            "at spacing 18.15 mm) but the motors allow 1.825 m/s: the thinnest "
                            "film per coat is 4.528 µm; at most 5 coat(s) of this target"),
    ("job_line_zero.toml", "'line.direction' = [0.0, 0.0, 0.0]: has zero length"),
    ("job_line_still.toml", "'line.speed' = 0: must be > 0"),
    ("job_line_absurd.toml", "'line.speed' = 30: must be at most 2 m/s"),
    ("job_line_text.toml", "'line.speed' = 'fast': must be a number"),
    ("job_line_key.toml", "'line.pitch' = 1: unknown key"),
    ("job_line_table.toml", "'line' = 3: must be a table [line]"),
    ("job_robots_case.toml", "robots 'low' and 'LOW' differ only in case (robot[0] and "
                             "robot[1]); each names its own output folder, and the two "
                             "collide on a case-insensitive file system"),
    ("part_missing_mesh.toml", "mesh file 'nope.stl' does not exist"),
    ("part_broken.toml", "mesh_broken.stl: line 4: 'vertex 1 2': an ASCII STL vertex is "
                         "'vertex x y z', three numbers"),
    ("part_two_corners.toml", "mesh_two_corners.stl: line 2: an ASCII STL facet with 2 "
                              "vertices (a triangle has 3)"),
    ("part_two_corners_binary.toml", "mesh_two_corners_binary.stl: a binary STL whose header "
                                     "counts 1 triangles (134 bytes), but the file has 122 bytes"),
    ("part_empty.toml", "mesh_empty.obj: no triangles"),
    ("part_nan.toml", "is not finite"),
    ("part_degenerate.toml", "faces have zero area"),
    ("part_png.toml", "mesh_png.stl: a binary STL whose header counts 1263159624 triangles "
                      "(63157981284 bytes), but the file has 264 bytes"),
    ("part_format.toml", "format '.step' is not a mesh this reads"),
    ("part_no_extension.toml", "/dev/stdin: a name without an extension is not a mesh this "
                               "reads (STL, OBJ or PLY)"),
    ("part_facing.toml", "no face has its outward normal within 10°"),
    ("part_units.toml", "'part.units' = 'ft': must be 'm', 'cm', 'mm', 'in'"),
    ("part_mm_as_m.toml", "read as millimetres (part.units)?"),
    ("part_and_panel.toml", "a job paints a [panel] or a [part], not both"),
    ("part_no_mesh.toml", "'part.mesh' is missing"),
    ("part_mesh_number.toml", "'part.mesh' = 3: must be a mesh file name"),
    ("part_rotation.toml", "'part.rotation[1]' = 'x': must be a number"),
    ("part_max_angle.toml", "max_angle = 200° must be in (0, 90)"),
    ("part_zero_facing.toml", "has zero length"),
    ("part_far.toml", "move the part by (-0.410, -0.000, -0.056) m (75 mm of margin"),
    ("part_line_zero.toml", "'line.direction' = [0.0, 0.0, 0.0]: has zero length"),
    ("part_line_coats.toml", "job.coats = 2: a part on the line is painted in one coat"),
    ("part_line_past.toml", "the part never comes within reach: the gun's track at the part's "
                            "centre runs through (0.556, 2.500, 0.160) m along (0, 1, 0)"),
    ("part_zero_based.toml", "line 4: face index 0 (OBJ indices start at 1"),
    ("part_relative_out.toml", "line 4: face index -4 refers to vertex 0, but 3 vertices"),
    ("part_counts.toml",
     "the PLY header declares 2 vertex and 1 face (3 lines) but the data has 4 lines"),
    ("part_negative.toml", "face 0 has vertex index -1, outside 0..2"),
    ("part_table.toml", "is outside its limits"),
    ("part_hidden.toml", "all 1 faces within 45° of facing are hidden from a gun at 0.15 m"),
    ("part_max_angle_90.toml", "max_angle = 90° must be in (0, 90)"),
    ("part_coats.toml", "'job.coats' = 1000000000: must be at most 5 for a part"),
    # the pass speed that spacing asks (flow/(thickness·spacing), 600 m/s) is refused first
    ("part_spacing.toml", "needs a gun speed of 600 m/s (gun.flow 1.5e-07 m³/s, 1 coat(s) of "
                          "25 µm at spacing 0.01 mm), 60 times the 10 m/s of any spray pass: "
                          "gun.flow in m³/s, job.thickness and job.spacing in m?"),
    ("", "an empty name"),
]]
CASES += [([*PAINT, "part_line.toml", "--resolution", "0.011"],
           "--resolution: film point spacing 0.011 m must be > 0 and at most")]
GOOD_JOB = [*PAINT, "job_good.toml"]
CASES += [([*GOOD_JOB, *extra], says) for extra, says in [
    (["--resolution", "0"], "must be > 0"),
    (["--resolution", "-1"], "must be > 0"),
    (["--resolution", "nan"], "finite"),
    (["--resolution", "abc"], "not a number"),
    (["--resolution", "1e-6"], "--resolution: film grid spacing 1e-06 m makes 3.12e+10 film "
                               "points on the 0.26 × 0.12 m panel, budget 2e+06"),
    (["--resolution", "0.011"], "--resolution: film grid spacing 0.011 m must be > 0 and at "
                                "most the spray spot's σ = 0.01 m"),
    (["--resolution", "1e300"], "at most the spray spot's σ"),
    (["--format", "xlsx"], "invalid choice"),
    (["--format", "csv", "--format", "png"], "invalid choice"),
    *((["--actuators", name], says) for name, says in BAD_ACTUATORS[::2]),
    (["--actuators", ""], "an empty name"),
    (["--actuators", "act_weak.toml"], "the motors cannot hold the gun on the passes: theta21"),
    (["--out", "afile"], "afile: names a file, but a folder is expected"),
    (["--out", "existing.csv"], "names a file, but a folder is expected"),
    (["--out", "afile/p"], "afile is a file, not a folder"),
    (["--out", "/proc/p"], "/proc/p"),
    (["--out", ""], "an empty name"),
    (["--out", "paint_precious", "--format", "parquet", "--actuators", "act_weak.toml"],
     "cannot hold the gun"),
    (["--params", "broken.toml"], "is not valid TOML"),
    (["--params", "nan.toml"], "finite"),
    (["--set", "chain0.x32=nan"], "finite"),
    (["--set", "chain0.x33=0.3"], "names no parameter"),
    (["--set", "leg1.x87=0.01"], "is unreachable"),
]]
CASES += [(["paint", "--out", "p"], "the following arguments are required: --job")]

# view of a workspace or paint folder that is missing, empty or damaged: read before solving
VIEW_WS = ["view", *SHORT, "--html", "out.html", "--workspace"]
CASES += [([*VIEW_WS, name], says) for name, says in [
    ("nope", "nope: no such folder"),
    ("afile", "afile: is a file, not a folder"),
    ("", "an empty name"),
    ("ws_empty", "ws_empty: no workspace.csv or workspace.parquet"),
    ("ws_folder", "no workspace.csv or workspace.parquet"),
    ("ws_header", "ws_header/workspace.csv: no rows"),
    ("ws_wrong", "column 'a' is not one pollard-pin writes"),
    ("ws_binary", "not UTF-8 text"),
    ("ws_garbage", "not a readable parquet result table"),
    ("ws_text", "not a readable csv result table"),
    ("ws_nan", "ws_nan/workspace.csv: row 1: a reachable point with a non-finite"),
]]
VIEW_PAINT = ["view", "--html", "out.html", "--paint"]
CASES += [([*VIEW_PAINT, name], says) for name, says in [
    ("nope", "--paint nope: not a paint output folder"),
    ("afile", "not a paint output folder"),
    ("", "an empty name"),
    ("paint_empty", "not a paint output folder"),
    ("paint_no_json", "not a paint output folder"),
    ("paint_bad_json", "paint_bad_json/paint.json: not a paint report"),
    ("paint_list_json", "not a paint report"),
    ("paint_binary_json", "not a paint report"),
    ("paint_no_grid", "not a paint report"),
    ("paint_text_grid", "not a paint report (grid nu = 'two'"),
    ("paint_mismatch", "not the film of paint.json's 2 × 2 grid"),
    ("paint_no_thickness", "column 'film' is not one pollard-pin writes"),
    ("paint_text_table", "not a readable csv result table"),
    ("paint_nan_table", "paint_nan_table/thickness.csv: row 3: thickness not finite"),
    ("paint_binary_table", "not UTF-8 text"),
    ("paint_garbage_parquet", "not a readable parquet result table"),
    ("paint_precious", "paint_precious/paint.json: not a paint report"),
    ("paint_bad_path", "paint_bad_path/path.csv: row 7, column 'x': value 'nan' is not "
                       "finite"),
    ("paint_empty_path", "paint_empty_path/path.csv: empty file"),
]]
CASES += [([*VIEW_PAINT, "paint_bad_path", "--trajectory", "good.csv"],
           "--paint DIR shows DIR/path.csv: give no --trajectory with it")]
IDS = [" ".join(argv) for argv, _ in CASES]


@pytest.mark.parametrize("argv, says", CASES, ids=IDS)
def test_bad_input_gives_one_line_exit_2_and_writes_nothing(scratch, monkeypatch, capsys, argv,
                                                            says):
    monkeypatch.chdir(scratch)
    before, beside = tree_state(scratch), sorted(os.listdir(scratch.parent))
    code, out, err = run_cli(argv, capsys)
    lines = err.strip().splitlines()
    assert code == 2, (code, out[-300:], err[-2000:])
    assert out == "", out[:300]  # nothing half-written on standard output either
    assert len(lines) == 1 and lines[0].startswith("pollard-pin"), err[-2000:]
    assert says in lines[0] and "Traceback" not in err, lines[0]
    # the refusal itself (without the command's prefix, the 'nothing written to' suffix and
    # the scratch folder's name) is at most 250 characters
    core = re.sub(r"^pollard-pin \S+: error: ", "", lines[0])
    core = re.sub(r" \(nothing written to [^)]*\)$", "", core).replace(str(scratch), "D")
    assert len(core) <= 250, (len(core), core)
    assert tree_state(scratch) == before  # nothing written, nothing changed
    assert sorted(os.listdir(scratch.parent)) == beside  # nor beside the scratch folder


def test_the_fuzz_has_at_least_200_cases():
    assert len(CASES) >= 200 and len(set(IDS)) == len(IDS)
    per_command = {c: sum(argv[0] == c for argv, _ in CASES) for c in ("workspace", "paint")}
    assert min(per_command.values()) >= 60, per_command


# --- what must still work ------------------------------------------------------------------------
@pytest.mark.parametrize("name, content", [
    ("bom.csv", "\ufeff" + _files()["good.csv"]),  # Excel's "CSV UTF-8" starts with a BOM
    ("crlf.csv", _files()["good.csv"].replace("\n", "\r\n")),
])
def test_a_bom_or_crlf_trajectory_runs_and_its_note_follows_the_work(tmp_path, monkeypatch,
                                                                     capsys, name, content):
    monkeypatch.chdir(tmp_path)
    Path(name).write_text(content, encoding="utf-8", newline="")
    assert main(["run", "--trajectory", name, "--out", "out.csv"]) == 0
    out, err = capsys.readouterr()
    assert "wrote out.csv (12 rows)" in err
    # the spline note is said once, after the work (an error would have been the only line)
    assert err.strip().splitlines()[-1] == (f"note: {name}: no d_*/dd_* columns; derivatives "
                                            "taken from a quintic interpolating spline through "
                                            "the samples")


def test_negative_values_with_an_exponent_are_values_not_options(tmp_path, monkeypatch, capsys):
    # argparse took "-1e-2" for an option: "expected one argument"
    monkeypatch.chdir(tmp_path)
    Path("good.csv").write_text(_files()["good.csv"])
    assert main(["simulate", "--trajectory", "good.csv", "--mass-error", "-1e-2",
                 "--out", "sim.csv"]) == 0
    assert "wrote sim.csv" in capsys.readouterr().err
