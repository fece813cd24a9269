"""URDF and SRDF of the open tree (docs/model.md §3) generated from
:class:`~pollard_pin.model.params.Params`.

The two cut spherical joints (docs/model.md §4) are written as ``<loop_closure>`` elements,
which plain URDF parsers ignore and :mod:`pollard_pin.model.build` reads, so the file is
self-contained. The closure points are fixed frames ``closure{i}_A`` (on ``link_i``, the leg side) and
``closure{i}_B`` (on ``platform``, at A_i).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from xml.sax.saxutils import quoteattr

import numpy as np

from .params import Params

# Wide limits keep nq = nv (a URDF 'continuous' joint has nq = 2) without ever binding.
JOINT_LIMIT = 4.0 * math.pi
EFFORT_LIMIT = 50.0  # N·m, not used by the model; URDF requires it
VELOCITY_LIMIT = 20.0  # rad/s

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
        "gun": [Shape("box", (0.5 * p.x1918 * 0.7, 0, 0), size=(0.7 * p.x1918, 0.022, 0.03),
                      colour="gun"),
                Shape("cylinder", (0.7 * p.x1918, 0, 0), _ex(p.x1918), (0.004,), colour="gun")],
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
           "     (ignored by plain URDF parsers, read by pollard_pin.load()). -->",
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
    for j in joints:
        kind = "fixed" if j.axis is None else "revolute"
        out += [f'  <joint name="{j.name}" type="{kind}">',
                f'    <parent link="{j.parent}"/>',
                f'    <child link="{j.child}"/>',
                f'    <origin xyz="{_vec(j.xyz)}" rpy="{_vec(j.rpy)}"/>']
        if j.axis is not None:
            out += [f'    <axis xyz="{_vec(j.axis)}"/>',
                    f'    <limit lower="{_f(-JOINT_LIMIT)}" upper="{_f(JOINT_LIMIT)}"'
                    f' effort="{_f(EFFORT_LIMIT)}" velocity="{_f(VELOCITY_LIMIT)}"/>']
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
