"""Draw the figures of docs/model.md from the model itself:

* ``docs/figures/kinematic_tree.png``: the kinematic graph. Nodes are the URDF links (moving
  bodies, massless U-joint crosses, and the massless frames ``tip`` and ``closure{i}_A/B``);
  edges are the tree joints, labelled with name, axis and origin; actuated joints are drawn
  thick and red; the two cut spherical joints (the loop closures) are dashed.
* ``docs/figures/home_pose.png``: a labelled line drawing of the robot at the home
  configuration, in 3-D and in side and top views.

Everything is read from ``pollard_pin.load()`` (Pinocchio model, home configuration, closures,
actuated joints)::

    .venv/bin/python scripts/model_figure.py [--out DIR] [--dpi N]
"""
import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pinocchio as pin  # noqa: E402

import pollard_pin as pp  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
AXIS_NAMES = {"JointModelRX": "x", "JointModelRY": "y", "JointModelRZ": "z"}
THESIS_BODY = {"arm0": "body 1", "platform": "body 2", "wrist1": "body 3", "wrist2": "body 4",
               "gun": "body 5", "arm_1": "body 11", "link_1": "body 21", "arm_2": "body 12",
               "link_2": "body 22"}
COLOURS = {"base": "#7f7f85", "chain0": "#2966cc", "leg1": "#e6731a", "leg2": "#26a64d"}
ACTUATED_COLOUR = "#c0182b"
CUT_COLOUR = "#7b3fa0"


def _num(x: float) -> str:
    return f"{x:.4g}" if abs(x) > 1e-12 else "0"


def _vec(v) -> str:
    return "(" + ", ".join(_num(x) for x in v) + ")"


# --- the graph -----------------------------------------------------------------------------
def graph(robot):
    """Links (BODY frames), tree edges (JOINT / FIXED_JOINT frames) and cut edges (closures)."""
    model = robot.model
    links, edges = {}, []
    for fid, f in enumerate(model.frames):
        if f.type == pin.FrameType.BODY:
            via = model.frames[f.parentFrame]
            massive = via.type == pin.FrameType.JOINT
            mass = model.inertias[f.parentJoint].mass if massive else 0.0
            links[f.name] = {"frame": fid, "mass": mass, "joint": f.parentJoint}
    for f in model.frames:
        if f.type not in (pin.FrameType.JOINT, pin.FrameType.FIXED_JOINT) or f.name == "universe":
            continue
        parent = model.frames[f.parentFrame].name
        child = next(g.name for g in model.frames
                     if g.type == pin.FrameType.BODY and model.frames[g.parentFrame].name == f.name)
        if f.type == pin.FrameType.JOINT:
            j = model.getJointId(f.name)
            M = model.jointPlacements[j]
            kind = "actuated" if f.name in robot.actuated else "passive"
            axis = M.rotation @ np.eye(3)[:, "xyz".index(AXIS_NAMES[model.joints[j].shortname()])]
            edges.append({"name": f.name, "parent": parent, "child": child, "kind": kind,
                          "axis": axis, "xyz": M.translation,
                          "rpy": pin.rpy.matrixToRpy(M.rotation)})
        else:
            edges.append({"name": f.name, "parent": parent, "child": child, "kind": "fixed",
                          "axis": None, "xyz": f.placement.translation,
                          "rpy": pin.rpy.matrixToRpy(f.placement.rotation)})
    cuts = [{"name": c.name, "a": c.frame_a, "b": c.frame_b} for c in robot.closures]
    return links, edges, cuts


def layout(robot, links, edges, cuts):
    """Depth = distance from the base; one column per chain leaving the base, ordered by the
    world y of its first joint at home (leg on −y, chain 0, leg on +y); side branches (the
    platform-side closure frames) sit halfway towards the leg they close with."""
    model, data = robot.model, robot.data
    pin.forwardKinematics(model, data, robot.home())
    children = {}
    for e in edges:
        children.setdefault(e["parent"], []).append(e["child"])
    depth = {"base": 0}
    order = ["base"]
    for n in order:
        for c in children.get(n, []):
            depth[c] = depth[n] + 1
            order.append(c)

    def height(n):
        return 1 + max((height(c) for c in children.get(n, [])), default=0)

    roots = sorted(children["base"],
                   key=lambda c: data.oMi[links[c]["joint"]].translation[1])
    col = {"base": 0.0}
    partner = {}
    for c in cuts:
        partner[c["a"]], partner[c["b"]] = c["b"], c["a"]
    pending = []
    for k, r in enumerate(roots):
        x = 4.0 * (k - (len(roots) - 1) / 2)
        stack = [(r, x)]
        while stack:
            n, x = stack.pop()
            col[n] = x
            kids = sorted(children.get(n, []), key=height, reverse=True)
            if kids:
                stack.append((kids[0], x))  # the chain continues straight down
                pending += kids[1:]  # side branches: placed once every column is known
    # A side branch goes halfway towards its partner (same depth in this robot).
    while pending:
        n = pending.pop(0)
        if n in partner and partner[n] in col:
            col[n] = 0.5 * (col[_parent(edges, n)] + col[partner[n]])
        elif n in partner:
            pending.append(n)
            continue
        else:
            col[n] = col[_parent(edges, n)] + 0.8
        for c in children.get(n, []):
            pending.append(c)
    return {n: (col[n], -depth[n]) for n in links}


def _parent(edges, child):
    return next(e["parent"] for e in edges if e["child"] == child)


def _chain_of(name, edges):
    """Colour key of a link: the chain its base joint belongs to."""
    n = name
    while True:
        p = _parent(edges, n) if n != "base" else None
        if p is None:
            return "base"
        if p == "base":
            return {"arm0": "chain0", "arm_1": "leg1", "arm_2": "leg2"}.get(n, "chain0")
        n = p


def draw_tree(robot, path: Path, dpi: int):
    links, edges, cuts = graph(robot)
    pos = layout(robot, links, edges, cuts)
    fig, ax = plt.subplots(figsize=(14.5, 11.0))
    ax.set_axis_off()
    for e in edges:
        (x0, y0), (x1, y1) = pos[e["parent"]], pos[e["child"]]
        if e["kind"] == "actuated":
            style = dict(color=ACTUATED_COLOUR, lw=4.0, ls="-")
        elif e["kind"] == "passive":
            style = dict(color="#333333", lw=1.8, ls="-")
        else:
            style = dict(color="#999999", lw=1.4, ls=":")
        # Org-chart routing: down from the parent to a bus, across, down to the child.
        ybus = y0 - 0.3
        xs, ys = ([x0, x1], [y0, y1]) if abs(x1 - x0) < 1e-9 else \
            ([x0, x0, x1, x1], [y0, ybus, ybus, y1])
        ax.plot(xs, ys, zorder=1, solid_capstyle="round", **style)
        if e["kind"] == "fixed":
            text = f"{e['name']}  (fixed)\nxyz {_vec(e['xyz'])}"
        else:
            text = (f"{e['name']}  ·  axis {_axis_name(e['axis'])}"
                    + ("  ·  actuated" if e["kind"] == "actuated" else "")
                    + f"\nxyz {_vec(e['xyz'])}")
            if np.abs(e["rpy"]).max() > 1e-12:
                text += f"  rpy {_vec(e['rpy'])}"
        colour = ACTUATED_COLOUR if e["kind"] == "actuated" else "#222222"
        ylab = 0.5 * (y0 + y1) if abs(x1 - x0) < 1e-9 else 0.5 * (ybus + y1) - 0.05
        ax.text(x1 + 0.1, ylab, text, fontsize=8.4, va="center", ha="left", color=colour,
                zorder=3, fontweight="bold" if e["kind"] == "actuated" else "normal")
    for c in cuts:
        (x0, y0), (x1, y1) = pos[c["a"]], pos[c["b"]]
        ax.plot([x0, x1], [y0, y1], color=CUT_COLOUR, lw=2.6, ls=(0, (5, 3)), zorder=1)
        i = c["name"][-1]
        ax.text(0.5 * (x0 + x1), 0.5 * (y0 + y1) - 0.2,
                f"{c['name']}: cut spherical joint\n"
                f"(theta98_{i}, theta109_{i}, theta1110_{i})\n3-D point constraint p_A = p_B",
                fontsize=8.2, ha="center", va="top", color=CUT_COLOUR, zorder=3)
    for name, (x, y) in pos.items():
        info = links[name]
        key = _chain_of(name, edges)
        if name == "base":
            label, fc, ec, fs = "base\n(world, fixed)", COLOURS["base"], "black", 10
        elif info["mass"] > 0:
            label = f"{name}\n{THESIS_BODY.get(name, '')}, {info['mass']:.3g} kg"
            fc, ec, fs = COLOURS[key], "black", 10
        elif name.startswith("cross"):
            label, fc, ec, fs = f"{name}\n(U-joint cross, massless)", "white", COLOURS[key], 9
        else:
            label, fc, ec, fs = f"{name}\n(frame)", "#f4f4f4", "#777777", 9
        txt_colour = "white" if fc not in ("white", "#f4f4f4") else "black"
        ax.text(x, y, label, ha="center", va="center", fontsize=fs, color=txt_colour,
                zorder=4, fontweight="bold" if info["mass"] > 0 else "normal",
                bbox=dict(boxstyle="round,pad=0.35", fc=fc, ec=ec, lw=1.4))
    xs = [p[0] for p in pos.values()]
    ys = [p[1] for p in pos.values()]
    ax.set_xlim(min(xs) - 0.8, max(xs) + 1.6)
    ax.set_ylim(min(ys) - 0.6, max(ys) + 0.45)
    handles = [
        plt.Line2D([], [], color=ACTUATED_COLOUR, lw=4, label="actuated revolute joint"),
        plt.Line2D([], [], color="#333333", lw=1.8, label="passive revolute joint"),
        plt.Line2D([], [], color="#999999", lw=1.2, ls=":", label="fixed joint (frame)"),
        plt.Line2D([], [], color=CUT_COLOUR, lw=2.6, ls=(0, (5, 3)),
                   label="cut spherical joint (loop closure)"),
    ]
    ax.legend(handles=handles, loc="lower left", fontsize=9, frameon=True)
    ax.set_title("Pollard robot: kinematic tree of models/pollard.urdf "
                 "(xyz in m, parent-link frame; axis in the joint frame)", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


def _axis_name(a) -> str:
    for k, n in enumerate("xyz"):
        if abs(abs(a[k]) - 1.0) < 1e-12:
            return ("−" + n) if a[k] < 0 else n
    return _vec(a)


# --- the robot at home ---------------------------------------------------------------------
def skeleton(robot):
    """World points of the home configuration: polylines per chain, joint origins and axes."""
    model, data = robot.model, robot.data
    q = robot.home()
    pin.forwardKinematics(model, data, q)
    pin.framesForwardKinematics(model, data, q)

    def jo(name):
        return data.oMi[model.getJointId(name)].translation.copy()

    def fo(name):
        return data.oMf[model.getFrameId(name)].translation.copy()

    platform = data.oMi[model.getJointId("theta54")]
    # Station on the platform axis where the closure brackets start: the closure frames'
    # platform-x coordinate.
    xb = model.frames[model.getFrameId(robot.closures[0].frame_b)].placement.translation[0]
    station = platform.act(np.array([xb, 0.0, 0.0]))
    lines = {
        "chain0": [np.zeros(3), jo("theta21"), jo("theta43"), station, jo("theta1615")],
        "gun": [jo("theta1615"), fo("tip")],
        "bracket": [],
    }
    for i, c in enumerate(robot.closures, start=1):
        lines[f"leg{i}"] = [np.array([0.0, jo(f"theta21_{i}")[1], 0.0]), jo(f"theta21_{i}"),
                            data.oMi[model.getJointId(f"theta21_{i}")].act(
                                np.array([0.0, 0.0, model.jointPlacements[
                                    model.getJointId(f"theta65_{i}")].translation[2]])),
                            jo(f"theta65_{i}"), fo(c.frame_a)]
        lines[f"bracket{i}"] = [station, fo(c.frame_b)]
    joints = {}
    for j in range(1, model.njoints):
        name = model.names[j]
        M = data.oMi[j]
        axis = M.rotation[:, "xyz".index(AXIS_NAMES[model.joints[j].shortname()])]
        joints[name] = (M.translation.copy(), axis)
    frames = {n: fo(n) for n in ["tip"] + [c.frame_a for c in robot.closures]}
    tool_x = data.oMf[model.getFrameId("tip")].rotation[:, 0]
    return lines, joints, frames, tool_x


def draw_home(robot, path: Path, dpi: int):
    lines, joints, frames, tool_x = skeleton(robot)
    colour = {"chain0": COLOURS["chain0"], "gun": "#333333", "leg1": COLOURS["leg1"],
              "leg2": COLOURS["leg2"], "bracket1": COLOURS["chain0"],
              "bracket2": COLOURS["chain0"]}
    fig = plt.figure(figsize=(16, 6.4))
    gs = fig.add_gridspec(1, 3, width_ratios=(1.25, 1.0, 1.0))
    ax3 = fig.add_subplot(gs[0], projection="3d")
    side = fig.add_subplot(gs[1])
    top = fig.add_subplot(gs[2])
    L = 0.045  # drawn length of a joint axis [m]
    for key, pts in lines.items():
        if not pts:
            continue
        P = np.array(pts)
        c = colour[key]
        lw = 1.6 if key.startswith("bracket") else 3.0
        ax3.plot(P[:, 0], P[:, 1], P[:, 2], color=c, lw=lw)
        side.plot(P[:, 0], P[:, 2], color=c, lw=lw)
        top.plot(P[:, 0], P[:, 1], color=c, lw=lw)
    for name, (o, a) in joints.items():
        act = name in robot.actuated
        c = ACTUATED_COLOUR if act else "black"
        seg = np.array([o - 0.5 * L * a, o + 0.5 * L * a])
        ax3.plot(seg[:, 0], seg[:, 1], seg[:, 2], color=c, lw=1.2)
        ax3.scatter(*o, color=c, s=18 if act else 10, depthshade=False)
        for view, (i, j) in ((side, (0, 2)), (top, (0, 1))):
            view.plot(seg[:, i], seg[:, j], color=c, lw=1.2)
            view.plot(o[i], o[j], "o", color=c, ms=4 if act else 3)
    tip = frames["tip"]
    spray = np.array([tip, tip + 0.06 * tool_x])
    balls = [frames[f"closure{i}_A"] for i in (1, 2)]

    def note(view, ij, text, point, at, c="black", ha="left"):
        view.annotate(text, np.asarray(point)[list(ij)], at, fontsize=7.8, color=c, ha=ha,
                      va="center", arrowprops=dict(arrowstyle="-", color="#aaaaaa", lw=0.6))

    def jp(n):
        return joints[n][0]

    red = ACTUATED_COLOUR
    xz, xy = (0, 2), (0, 1)
    note(side, xz, "theta21", jp("theta21"), (0.035, 0.075), red)
    note(side, xz, "theta21_1, theta21_2", jp("theta21_1"), (0.035, 0.015), red)
    note(side, xz, "theta43, theta54 (U joint)", jp("theta43"), (0.1, 0.385))
    note(side, xz, "theta65_i, theta76_i\n(U joints, both legs)", jp("theta65_1"), (0.2, 0.1))
    note(side, xz, "closure1, closure2\n(cut ball joints)", balls[0], (0.41, 0.07), CUT_COLOUR)
    note(side, xz, "wrist centre:\ntheta1615, theta1716,\ntheta1817", jp("theta1615"),
         (0.42, 0.28), red)
    note(side, xz, "tip", tip, (0.585, 0.115), "#c000c0")
    note(top, xy, "theta21", jp("theta21"), (0.02, 0.03), red)
    note(top, xy, "theta43, theta54", jp("theta43"), (0.09, -0.035))
    note(top, xy, "theta21_1", jp("theta21_1"), (0.03, -0.12), red)
    note(top, xy, "theta21_2", jp("theta21_2"), (0.03, 0.12), red)
    note(top, xy, "theta65_1, theta76_1", jp("theta65_1"), (0.32, -0.245))
    note(top, xy, "theta65_2, theta76_2", jp("theta65_2"), (0.32, 0.245))
    note(top, xy, "closure1", balls[0], (0.36, -0.06), CUT_COLOUR, "right")
    note(top, xy, "closure2", balls[1], (0.36, 0.06), CUT_COLOUR, "right")
    note(top, xy, "wrist centre:\ntheta1615/1716/1817", jp("theta1615"), (0.43, 0.11), red)
    note(top, xy, "tip", tip, (0.575, -0.05), "#c000c0")
    for view, ij in ((side, xz), (top, xy)):
        view.annotate("", spray[1, list(ij)], spray[0, list(ij)],
                      arrowprops=dict(arrowstyle="->", color="#c000c0", lw=1.6))
        view.plot(*tip[list(ij)], "s", color="#c000c0", ms=5)
        for p in balls:
            view.plot(*p[list(ij)], "o", ms=9, mfc="none", mec=CUT_COLOUR, mew=1.5)
    # 3-D: link names at their segments, world axes, the spray axis.
    ax3.plot(spray[:, 0], spray[:, 1], spray[:, 2], color="#c000c0", lw=1.6)
    for p in balls:
        ax3.scatter(*p, s=60, facecolors="none", edgecolors=CUT_COLOUR, depthshade=False)

    def mid(key, k):
        return 0.5 * (lines[key][k] + lines[key][k + 1])

    for text, at, c in (("arm0", mid("chain0", 1), COLOURS["chain0"]),
                        ("platform", mid("chain0", 2), COLOURS["chain0"]),
                        ("arm_1", mid("leg1", 2), COLOURS["leg1"]),
                        ("link_1", mid("leg1", 3), COLOURS["leg1"]),
                        ("arm_2", mid("leg2", 2), COLOURS["leg2"]),
                        ("link_2", mid("leg2", 3), COLOURS["leg2"]),
                        ("gun → tip", tip, "#c000c0")):
        ax3.text(*at, " " + text, color=c, fontsize=8.5, fontweight="bold")
    for k, n in enumerate("xyz"):
        e = np.eye(3)[k] * 0.08
        ax3.plot([0, e[0]], [0, e[1]], [0, e[2]], color="#888888", lw=1)
        ax3.text(*(e * 1.2), n, color="#555555", fontsize=8)
    ax3.set_xlabel("x [m]")
    ax3.set_ylabel("y [m]")
    ax3.set_zlabel("z [m]")
    allp = np.array([p for pts in lines.values() for p in pts] + [spray[1]])
    c = 0.5 * (allp.max(0) + allp.min(0))
    r = 0.5 * (allp.max(0) - allp.min(0)).max() + 0.01
    ax3.set_xlim(c[0] - r, c[0] + r)
    ax3.set_ylim(c[1] - r, c[1] + r)
    ax3.set_zlim(c[2] - r, c[2] + r)
    ax3.set_box_aspect((1, 1, 1), zoom=1.05)
    ax3.view_init(elev=24, azim=-128)
    ax3.set_title("3-D view (base at the origin)", fontsize=10)
    side.set_title("side view (x–z plane; the two legs coincide)", fontsize=10)
    top.set_title("top view (x–y plane)", fontsize=10)
    for ax, (xl, yl) in ((side, ("x [m]", "z [m]")), (top, ("x [m]", "y [m]"))):
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_xlim(-0.03, 0.64)
    side.axhline(0.0, color="#888888", lw=0.8)
    handles = [plt.Line2D([], [], color=COLOURS["chain0"], lw=3, label="chain 0 + platform arm"),
               plt.Line2D([], [], color=COLOURS["leg1"], lw=3, label="leg 1 (s₁ = −1)"),
               plt.Line2D([], [], color=COLOURS["leg2"], lw=3, label="leg 2 (s₂ = +1)"),
               plt.Line2D([], [], color=ACTUATED_COLOUR, lw=1.2, marker="o",
                          label="actuated joint (axis drawn)"),
               plt.Line2D([], [], color="black", lw=1.2, marker="o", ms=3,
                          label="passive joint (axis drawn)"),
               plt.Line2D([], [], color=CUT_COLOUR, lw=0, marker="o", mfc="none", ms=9,
                          label="cut spherical joint"),
               plt.Line2D([], [], color="#c000c0", lw=1.6, marker="s", ms=5,
                          label="tool tip, spray axis (+x of tip)")]
    fig.legend(handles=handles, loc="lower center", ncol=7, fontsize=9, frameon=False)
    fig.suptitle("Pollard robot at the home configuration: tip at "
                 f"{_vec(np.round(frames['tip'], 4))} m, spraying along world +x", fontsize=12)
    fig.tight_layout(rect=(0.01, 0.08, 1, 0.97))
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "figures")
    ap.add_argument("--dpi", type=int, default=110)
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    robot = pp.load()
    for name, draw in (("kinematic_tree.png", draw_tree), ("home_pose.png", draw_home)):
        path = args.out / name
        draw(robot, path, args.dpi)
        print(f"wrote {path} ({path.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    main()
