"""URDF and SRDF of the open tree (docs/model.md §3) generated from
:class:`~pollard_pin.model.params.Params`.

The two cut spherical joints (docs/model.md §4) are written as ``<loop_closure>`` elements,
which plain URDF parsers ignore and :mod:`pollard_pin.model.build` reads, so the file is
self-contained. The closure points are fixed frames ``closure{i}_A`` (on ``link_i``, the leg
side) and ``closure{i}_B`` (on ``platform``, at A_i).

Joint limits (docs/model.md §3) come from the ``[limits]`` table of the parameter file; the
thesis gives neither joint ranges nor actuator data, so they are design values:

- position: the range the closed-form IK (docs/model.md §7) needs over the design workspace
  :data:`WORKSPACE` about the home pose, widened and rounded outward (:func:`position_limits`
  recomputes the shipped numbers; a test checks they agree);
- effort: 0 on the passive joints (no actuator); on the actuators, twice the peak |τ| of their
  group (base, wrist) on the default trajectory (docs/model.md §9), rounded up;
- velocity: twice the peak |q̇| of the group (base, wrist, passive) on the default trajectory.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from xml.sax.saxutils import quoteattr

import numpy as np

from ..names import TREE_JOINTS
from .params import Params

# Design workspace of the position limits: ± half-widths about the home pose in (x, y, z) [m]
# and (ψ, θ, φ) [rad] (docs/model.md §2). It holds the thesis curve (docs/model.md §9: x from
# −36 mm to 0, y ± 189 mm, z ± 100 mm) with 2–3 cm to spare, and spray-gun tilts.
WORKSPACE = (0.06, 0.22, 0.12, math.radians(20.0), math.radians(20.0), math.radians(30.0))
WORKSPACE_SAMPLES = 5  # grid points per axis: 5⁶ = 15,625 poses
WORKSPACE_WRIST_MARGIN = 0.05  # |sin θ1716| below: singular, left out (kinematics default)
LIMIT_MARGIN = 5.0  # deg each side: the grid's spacing (7⁶ grid, 2·10⁵ random poses: inside)
LIMIT_STEP = 5.0  # deg, rounding outward
# Caps in deg: θ1716 stays on the closed form's wrist branch (acos: 0–180°, 0 is singular);
# the wrist rolls (and any joint) get at most one turn centred on home (see position_limits).
BRANCH = {"theta1716": (0.0, 180.0)}

ROBOT_NAME = "pollard"
CHAIN_COLOURS = {  # one colour per chain (docs/model.md §1)
    "base": (0.55, 0.55, 0.58, 1.0),
    "chain0": (0.16, 0.40, 0.80, 1.0),
    "leg1": (0.90, 0.45, 0.10, 1.0),
    "leg2": (0.15, 0.65, 0.30, 1.0),
    "gun": (0.20, 0.20, 0.22, 1.0),
}
ARM_RADIUS = 0.008
JOINT_RADIUS = 0.014
CLOSURE_RADIUS = 0.010
# The gun link: a box of this cross-section [m] over this share of x1918 from the wrist
# centre, then the nozzle (a cylinder of NOZZLE_RADIUS [m]) to the tip.
GUN_BOX_SECTION = (0.022, 0.03)
GUN_BOX_SHARE = 0.7
NOZZLE_RADIUS = 0.004


@dataclass(frozen=True)
class Joint:
    name: str
    parent: str
    child: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]
    axis: tuple[float, float, float] | None  # None: fixed


@dataclass(frozen=True)
class Shape:
    kind: str  # "cylinder" (along the segment), "sphere", "box"
    a: tuple[float, float, float]  # cylinder start / sphere or box centre
    b: tuple[float, float, float] | None = None  # cylinder end
    size: tuple[float, ...] = ()  # radius, or box extents
    colour: str = "chain0"


def _ex(d):
    return (float(d), 0.0, 0.0)


def tree(p: Params) -> tuple[list[str], list[Joint], dict[str, list[Shape]], dict[str, str]]:
    """Links, joints, shapes per link and link→chain of the open tree of docs/model.md §3."""
    L = p.x65 + p.x1514
    joints = [
        Joint("theta21", "base", "arm0", (0.0, 0.0, p.z10), (0, 0, 0), (0, 1, 0)),
        Joint("theta43", "arm0", "cross0", _ex(p.x32), (0, 0, 0), (0, 1, 0)),
        Joint("theta54", "cross0", "platform", (0, 0, 0), (0, 0, 0), (0, 0, 1)),
        Joint("theta1615", "platform", "wrist1", _ex(L), (0, 0, 0), (1, 0, 0)),
        Joint("theta1716", "wrist1", "wrist2", (0, 0, 0), (0, 0, 0), (0, 0, 1)),
        Joint("theta1817", "wrist2", "gun", (0, 0, 0), (0, 0, 0), (1, 0, 0)),
        Joint("tip_joint", "gun", "tip", _ex(p.x1918), (0, 0, 0), None),
    ]
    shapes: dict[str, list[Shape]] = {
        "base": [Shape("box", (0.0, 0.0, -0.01), size=(0.12, 0.26, 0.02), colour="base")],
        "arm0": [Shape("sphere", (0, 0, 0), size=(JOINT_RADIUS,)),
                 Shape("cylinder", (0, 0, 0), _ex(p.x32), (ARM_RADIUS,))],
        "cross0": [Shape("sphere", (0, 0, 0), size=(JOINT_RADIUS,))],
        "platform": [Shape("cylinder", (0, 0, 0), _ex(L), (ARM_RADIUS,))],
        "wrist1": [Shape("sphere", (0, 0, 0), size=(JOINT_RADIUS * 1.2,))],
        "wrist2": [Shape("cylinder", (0, 0, -0.012), (0, 0, 0.012), (0.007,))],
        "gun": [Shape("box", (0.5 * p.x1918 * GUN_BOX_SHARE, 0, 0),
                      size=(GUN_BOX_SHARE * p.x1918, *GUN_BOX_SECTION), colour="gun"),
                Shape("cylinder", (GUN_BOX_SHARE * p.x1918, 0, 0), _ex(p.x1918),
                      (NOZZLE_RADIUS,), colour="gun")],
        "tip": [],
    }
    chain = {"base": "base", "arm0": "chain0", "cross0": "chain0", "platform": "chain0",
             "wrist1": "chain0", "wrist2": "chain0", "gun": "gun", "tip": "gun"}
    for i, leg in enumerate(p.legs, start=1):
        arm, cross, link = f"arm_{i}", f"cross_{i}", f"link_{i}"
        elbow = (leg.x43, 0.0, -leg.z32)
        joints += [
            Joint(f"theta21_{i}", "base", arm, (0.0, leg.side * leg.y10, 0.0), (0, 0, 0),
                  (0, 0, 1)),
            Joint(f"theta65_{i}", arm, cross, elbow, (leg.beta54, 0, 0), (0, 1, 0)),
            Joint(f"theta76_{i}", cross, link, (0, 0, 0), (0, 0, 0), (0, 0, 1)),
            Joint(f"closure{i}_A_joint", link, f"closure{i}_A", _ex(leg.x87), (0, 0, 0), None),
            Joint(f"closure{i}_B_joint", "platform", f"closure{i}_B",
                  tuple(float(v) for v in p.attachment(i - 1)), (0, 0, 0), None),
        ]
        c = f"leg{i}"
        shapes[arm] = [Shape("cylinder", (0, 0, 0.01), (0, 0, -leg.z32), (ARM_RADIUS,), colour=c),
                       Shape("cylinder", (0, 0, -leg.z32), elbow, (ARM_RADIUS,), colour=c),
                       Shape("sphere", (0, 0, 0), size=(JOINT_RADIUS,), colour=c)]
        shapes[cross] = [Shape("sphere", (0, 0, 0), size=(JOINT_RADIUS,), colour=c)]
        shapes[link] = [Shape("cylinder", (0, 0, 0), _ex(leg.x87), (ARM_RADIUS * 0.8,), colour=c)]
        # Both halves of the ball joint, drawn as coinciding spheres when the loop is closed.
        shapes[f"closure{i}_A"] = [Shape("sphere", (0, 0, 0), size=(CLOSURE_RADIUS,), colour=c)]
        shapes[f"closure{i}_B"] = [Shape("sphere", (0, 0, 0), size=(CLOSURE_RADIUS * 0.9,))]
        # Bracket from the platform axis to A_i.
        shapes["platform"].append(Shape("cylinder", _ex(p.x65),
                                        tuple(float(v) for v in p.attachment(i - 1)), (0.004,)))
        chain.update({arm: c, cross: c, link: c, f"closure{i}_A": c, f"closure{i}_B": "chain0"})
    links = ["base"] + [j.child for j in joints]
    return links, joints, shapes, chain


def workspace_ranges(p: Params, half_widths=WORKSPACE, samples: int = WORKSPACE_SAMPLES,
                     wrist_margin: float = WORKSPACE_WRIST_MARGIN) -> dict[str, tuple]:
    """(min, max) [rad] of each tree joint over a ``samples``⁶ grid of poses home ± half_widths,
    by the closed-form IK (docs/model.md §7). Unreachable and wrist-singular poses are left
    out; angles are taken within ±π of the home configuration."""
    from ..analytic.closed_form import UnreachableError, position_ik

    home = np.asarray(p.home_pose, dtype=float)
    axes = [np.linspace(-h, h, samples) for h in half_widths]
    poses = home + np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 6)
    q_home = position_ik(p, home[None])[0, :12]

    def solve(block):  # bisect around the unreachable poses (the closed form raises)
        try:
            return [position_ik(p, block, wrist_margin=wrist_margin)[:, :12]]
        except UnreachableError:
            if len(block) == 1:
                return []
            h = len(block) // 2
            return solve(block[:h]) + solve(block[h:])

    q = np.concatenate([q_home[None]] + solve(poses))
    q = q_home + (np.pi - np.mod(np.pi - (q - q_home), 2.0 * np.pi))  # into home ± π
    return {n: (float(lo), float(hi)) for n, lo, hi in zip(TREE_JOINTS, q.min(0), q.max(0))}


def position_limits(p: Params, **workspace) -> dict[str, tuple[float, float]]:
    """Position limits [deg] from :func:`workspace_ranges`: widened by :data:`LIMIT_MARGIN`,
    rounded outward to :data:`LIMIT_STEP`, capped by :data:`BRANCH` and to home ± 180°."""
    from ..analytic.closed_form import position_ik

    home = np.degrees(position_ik(p, np.asarray(p.home_pose)[None])[0, :12])
    out, step, eps = {}, LIMIT_STEP, 1e-9  # eps: round-off at exact multiples of the step
    for (n, (lo, hi)), h in zip(workspace_ranges(p, **workspace).items(), home):
        lo = math.floor((math.degrees(lo) - LIMIT_MARGIN) / step + eps) * step
        hi = math.ceil((math.degrees(hi) + LIMIT_MARGIN) / step - eps) * step
        cap_lo, cap_hi = BRANCH.get(n, (-math.inf, math.inf))
        cap_lo = max(cap_lo, math.ceil((h - 180.0) / step - eps) * step)
        cap_hi = min(cap_hi, math.floor((h + 180.0) / step + eps) * step)
        out[n] = (max(lo, cap_lo), min(hi, cap_hi))
    return out


def _f(x: float) -> str:
    return repr(float(x)) if x != 0 else "0"


def _vec(v) -> str:
    return " ".join(_f(x) for x in v)


def _shape_xml(s: Shape, tag: str, indent: str) -> list[str]:
    if s.kind == "cylinder":
        a, b = np.array(s.a), np.array(s.b)
        d = b - a
        length = float(np.linalg.norm(d))
        # URDF cylinders run along z: rotate z onto d (pitch then yaw).
        yaw = math.atan2(d[1], d[0])
        pitch = math.atan2(math.hypot(d[0], d[1]), d[2])
        xyz, rpy = 0.5 * (a + b), (0.0, pitch, yaw)
        geom = f'<cylinder radius="{_f(s.size[0])}" length="{_f(length)}"/>'
    elif s.kind == "sphere":
        xyz, rpy = s.a, (0, 0, 0)
        geom = f'<sphere radius="{_f(s.size[0])}"/>'
    else:
        xyz, rpy = s.a, (0, 0, 0)
        geom = f'<box size="{_vec(s.size)}"/>'
    out = [f"{indent}<{tag}>",
           f'{indent}  <origin xyz="{_vec(xyz)}" rpy="{_vec(rpy)}"/>',
           f"{indent}  <geometry>{geom}</geometry>"]
    if tag == "visual":
        out.append(f'{indent}  <material name="{s.colour}"/>')
    out.append(f"{indent}</{tag}>")
    return out


def generate_urdf(p: Params) -> str:
    """The URDF text of docs/model.md §3 for these parameters (deterministic: same params, same
    bytes)."""
    links, joints, shapes, _ = tree(p)
    bodies = dict(p.bodies)
    out = ['<?xml version="1.0"?>',
           "<!-- Pollard spray-painting robot, open tree of docs/model.md §3.",
           "     GENERATED by `pollard-pin urdf` from the parameter file; do not edit by hand.",
           f"     Parameters: {p.source}. SI units; inertias about the CoG (docs/model.md §5).",
           "     <loop_closure> elements: the cut spherical joints of docs/model.md §4",
           "     (ignored by plain URDF parsers, read by pollard_pin.load()).",
           "     Joint limits: the parameter file's [limits] (design values, docs/model.md §3):",
           "     position = range over the design workspace; effort = 0 on passive joints,",
           "     else 2 x the peak on the default trajectory; velocity likewise. -->",
           f'<robot name="{ROBOT_NAME}">']
    for name, rgba in CHAIN_COLOURS.items():
        out.append(f'  <material name="{name}"><color rgba="{_vec(rgba)}"/></material>')
    for link in links:
        out.append(f'  <link name="{link}">')
        if link in bodies:
            b = bodies[link]
            I = b.inertia
            out += ["    <inertial>",
                    f'      <origin xyz="{_vec(b.com)}" rpy="0 0 0"/>',
                    f'      <mass value="{_f(b.mass)}"/>',
                    f'      <inertia ixx="{_f(I[0][0])}" ixy="{_f(I[0][1])}" ixz="{_f(I[0][2])}"'
                    f' iyy="{_f(I[1][1])}" iyz="{_f(I[1][2])}" izz="{_f(I[2][2])}"/>',
                    "    </inertial>"]
        for s in shapes.get(link, []):
            out += _shape_xml(s, "visual", "    ")
        # The crosses keep collision spheres: MuJoCo's importer refuses massless moving
        # bodies and infers a mass from them (mujoco_peer removes the crosses instead).
        if not link.startswith("closure"):
            for s in shapes.get(link, []):
                out += _shape_xml(s, "collision", "    ")
        out.append("  </link>")
    limits = dict(p.limits)
    for j in joints:
        # 'revolute' (not 'continuous', whose nq = 2) with the [limits] of the parameter file.
        kind = "fixed" if j.axis is None else "revolute"
        out += [f'  <joint name="{j.name}" type="{kind}">',
                f'    <parent link="{j.parent}"/>',
                f'    <child link="{j.child}"/>',
                f'    <origin xyz="{_vec(j.xyz)}" rpy="{_vec(j.rpy)}"/>']
        if j.axis is not None:
            lim = limits[j.name]
            out += [f'    <axis xyz="{_vec(j.axis)}"/>',
                    f'    <limit lower="{_f(lim.lower)}" upper="{_f(lim.upper)}"'
                    f' effort="{_f(lim.effort)}" velocity="{_f(lim.velocity)}"/>']
        out.append("  </joint>")
    for i in (1, 2):
        out.append(f'  <loop_closure name="closure{i}" type="spherical"'
                   f' frame_a="closure{i}_A" frame_b="closure{i}_B"/>')
    out.append("</robot>")
    return "\n".join(out) + "\n"


def generate_srdf(p: Params, home_q: dict[str, float]) -> str:
    """SRDF in example-robot-data style: the ``home`` posture and adjacent-link collision pairs."""
    links, joints, _, _ = tree(p)
    out = ['<?xml version="1.0"?>',
           "<!-- GENERATED by `pollard-pin urdf`; home = the home pose of docs/model.md §9,",
           "     closed-form IK. -->",
           f'<robot name="{ROBOT_NAME}">',
           '  <group_state name="home" group="all">']
    # 12 decimals: stable against round-off changes in the IK; load() re-closes the loops.
    out += [f'    <joint name="{n}" value="{round(float(v), 12)!r}"/>' for n, v in home_q.items()]
    out.append("  </group_state>")
    pairs = [(j.parent, j.child) for j in joints]
    pairs += [(f"link_{i}", "platform") for i in (1, 2)]  # touching at the ball joints
    for a, b in pairs:
        out.append(f'  <disable_collisions link1={quoteattr(a)} link2={quoteattr(b)}'
                   ' reason="Adjacent"/>')
    out.append("</robot>")
    return "\n".join(out) + "\n"
