"""The closed-loop model as MJCF (docs/model.md §3, §4, §6): the URDF read without Pinocchio,
MuJoCo's spec of it with the two cut spherical joints as ``connect`` equalities, and
:func:`export_mjcf`, which writes it as a standalone file. MuJoCo is imported lazily (an
optional dependency); the MuJoCo peer (:mod:`pollard_pin.crosscheck.mujoco`) builds on this.

Modelling notes:
- MuJoCo rejects massless moving bodies, so each massless U-joint cross (docs/model.md §5) is
  removed and its hinge moved into its child body ahead of the child's own hinge. MuJoCo
  composes the joints of one body in order, so the kinematics are unchanged: Ry(θ43) Rz(θ54)
  etc. (docs/model.md §3).
- ``inertiafromgeom`` is off, so masses and inertias are the URDF inertials.
- The exported file keeps the joint limits (the URDF's) and disables contacts.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from ..names import ACTUATED
from ..names import TREE_JOINTS as JOINTS
from .atomic import atomic_open

TIP = "tip"  # tool-tip frame of the URDF (docs/model.md §3: Tx(x1918) on gun)


# --- URDF reading (independent of Pinocchio and of MuJoCo's parser) ---------------------------
def _vec(el, attr, default="0 0 0") -> np.ndarray:
    return np.array([float(x) for x in (el.get(attr) if el is not None and el.get(attr)
                                        is not None else default).split()])


def _rpy(rpy) -> np.ndarray:
    """URDF fixed-axis roll-pitch-yaw: R = Rz(y) Ry(p) Rx(r)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def is_urdf_text(source) -> bool:
    return isinstance(source, str) and source.lstrip().startswith("<")


def read_urdf(source) -> dict:
    """Links' inertials, joints and ``<loop_closure>`` pairs of the URDF (a path or its text)."""
    root = ET.fromstring(source) if is_urdf_text(source) else ET.parse(str(source)).getroot()
    inertials = {}
    for link in root.iter("link"):
        el = link.find("inertial")
        if el is None:
            continue
        o, i = el.find("origin"), el.find("inertia")
        I = np.array([[float(i.get(k, 0)) for k in row] for row in
                      (("ixx", "ixy", "ixz"), ("ixy", "iyy", "iyz"), ("ixz", "iyz", "izz"))])
        R = _rpy(_vec(o, "rpy"))
        inertials[link.get("name")] = dict(mass=float(el.find("mass").get("value")),
                                           com=_vec(o, "xyz"), inertia=R @ I @ R.T)
    joints = {}
    for j in root.iter("joint"):
        o = j.find("origin")
        lim = j.find("limit")
        joints[j.get("name")] = dict(type=j.get("type"), parent=j.find("parent").get("link"),
                                     child=j.find("child").get("link"), xyz=_vec(o, "xyz"),
                                     rpy=_vec(o, "rpy"), limit=None if lim is None else {
                                         k: float(lim.get(k, 0)) for k in
                                         ("lower", "upper", "effort", "velocity")})
    closures = [(c.get("name"), c.get("frame_a"), c.get("frame_b"))
                for c in root.iter("loop_closure")]
    return dict(inertials=inertials, joints=joints, closures=closures)


def frame_on_moving_link(urdf: dict, frame: str) -> tuple[str, np.ndarray, np.ndarray]:
    """(moving link, position, rotation of ``frame`` in it), walking up fixed joints."""
    by_child = {j["child"]: j for j in urdf["joints"].values()}
    p, R, link = np.zeros(3), np.eye(3), frame
    while link in by_child and by_child[link]["type"] == "fixed":
        j = by_child[link]
        Rj = _rpy(j["rpy"])
        p, R = j["xyz"] + Rj @ p, Rj @ R
        link = j["parent"]
    return link, p, R


def point_on_moving_link(urdf: dict, frame: str) -> tuple[str, np.ndarray]:
    """(moving link, position of ``frame``'s origin in it), walking up fixed joints."""
    by_child = {j["child"]: j for j in urdf["joints"].values()}
    p = np.zeros(3)
    link = frame
    while link in by_child and by_child[link]["type"] == "fixed":
        j = by_child[link]
        p = j["xyz"] + _rpy(j["rpy"]) @ p
        link = j["parent"]
    return link, p


# --- model construction -----------------------------------------------------------------------
def require_mujoco():
    """The ``mujoco`` module, or one clear line on what to install (an optional dependency)."""
    try:
        import mujoco
    except ImportError:
        raise ImportError("the MuJoCo peer needs MuJoCo, which is not installed: "
                          "pip install 'pollard-pin[mujoco]'") from None
    return mujoco


def default_urdf() -> Path:
    from ..model.paths import models_dir

    return models_dir() / "pollard.urdf"


def _merge_massless_crosses(spec) -> list[str]:
    """Move each massless jointed body's hinges into its only child (see module notes)."""
    mujoco = require_mujoco()

    merged = []
    for body in list(spec.bodies):
        if body.name == "world" or body.explicitinertial or body.mass != 0.0:
            continue
        joints, kids = list(body.joints), list(body.bodies)
        if not joints:
            continue  # static: fusestatic handles it
        if len(kids) != 1 or np.any(kids[0].pos != 0) or np.any(kids[0].quat != [1, 0, 0, 0]):
            raise ValueError(f"massless moving body {body.name!r} cannot be merged into a child")
        child = kids[0]
        specs = [dict(name=j.name, type=j.type, axis=np.array(j.axis), pos=np.array(j.pos),
                      ref=j.ref, limited=j.limited, range=np.array(j.range),
                      actfrclimited=j.actfrclimited, actfrcrange=np.array(j.actfrcrange))
                 for j in joints + list(child.joints)]
        for j in joints + list(child.joints):
            spec.delete(j)
        for s in specs:  # parent's hinge first: R = R_parent_joint · R_child_joint
            if s["type"] != mujoco.mjtJoint.mjJNT_HINGE:
                raise ValueError(f"joint {s['name']!r} is not a hinge")
            child.add_joint(**s)
        merged.append(body.name)
    return merged


def closed_loop_spec(urdf):
    """MjSpec of the URDF (a path or its text) with the loops closed (see module notes).

    Returns ``(spec, urdf_info, merged)``: ``urdf_info`` from :func:`read_urdf`, ``merged`` the
    crosses whose hinges moved into their child."""
    mujoco = require_mujoco()

    info = read_urdf(urdf)
    where = "URDF" if is_urdf_text(urdf) else str(urdf)
    if len(info["closures"]) != 2:
        raise ValueError(f"{where}: expected 2 <loop_closure> elements (docs/model.md §4)")
    spec = (mujoco.MjSpec.from_string(urdf) if is_urdf_text(urdf)
            else mujoco.MjSpec.from_file(str(urdf)))
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.compiler.balanceinertia = False
    spec.compiler.boundmass = spec.compiler.boundinertia = 0.0
    merged = _merge_massless_crosses(spec)
    for name, fa, fb in info["closures"]:
        for tag, frame in (("A", fa), ("B", fb)):
            link, pos = point_on_moving_link(info, frame)
            spec.body(link).add_site(name=f"{name}_{tag}_site", pos=pos)
        spec.add_equality(name=name, type=mujoco.mjtEq.mjEQ_CONNECT,
                          objtype=mujoco.mjtObj.mjOBJ_SITE, name1=f"{name}_A_site",
                          name2=f"{name}_B_site")
    if TIP in {j["child"] for j in info["joints"].values()}:  # docs/model.md §3: Tx(x1918)
        link, pos, R = frame_on_moving_link(info, TIP)
        quat = np.empty(4)
        mujoco.mju_mat2Quat(quat, R.reshape(-1))
        spec.body(link).add_site(name=f"{TIP}_site", pos=pos, quat=quat)
    return spec, info, merged


def check_mjcf(model, urdf: dict, path) -> None:
    """The MJCF's closure sites, connect equalities and tip site are where the URDF puts them."""
    mujoco = require_mujoco()

    def names(kind, n):
        return [mujoco.mj_id2name(model, kind, i) for i in range(n)]

    sites = names(mujoco.mjtObj.mjOBJ_SITE, model.nsite)
    frames = [(f"{c}_{tag}_site", f) for c, fa, fb in urdf["closures"]
              for tag, f in (("A", fa), ("B", fb))]
    if TIP in {j["child"] for j in urdf["joints"].values()}:
        frames.append((f"{TIP}_site", TIP))
    for site, frame in frames:
        link, pos = point_on_moving_link(urdf, frame)
        if site not in sites:
            raise ValueError(f"{path}: no site {site!r} (URDF frame {frame!r})")
        s = model.site(site)
        body = model.body(int(s.bodyid[0])).name
        if body != link or np.abs(s.pos - pos).max() > 1e-12:
            raise ValueError(f"{path}: site {site!r} is on {body!r} at {s.pos.tolist()}, the "
                             f"URDF puts frame {frame!r} on {link!r} at {pos.tolist()}")
    eqs = names(mujoco.mjtObj.mjOBJ_EQUALITY, model.neq)
    for c, _, _ in urdf["closures"]:
        e = model.equality(c) if c in eqs else None
        ok = (e is not None and e.type[0] == mujoco.mjtEq.mjEQ_CONNECT
              and model.eq_objtype[e.id] == mujoco.mjtObj.mjOBJ_SITE
              and [int(e.obj1id[0]), int(e.obj2id[0])]
              == [model.site(f"{c}_A_site").id, model.site(f"{c}_B_site").id])
        if not ok:
            raise ValueError(f"{path}: no connect equality {c!r} between sites {c}_A_site "
                             f"and {c}_B_site (docs/model.md §4)")


def home_configuration(srdf_path=None, urdf_path=None) -> np.ndarray:
    """The SRDF's ``group_state`` "home" (12,) in :data:`JOINTS` order (docs/model.md §9).

    Default file: the ``.srdf`` beside ``urdf_path`` if there is one, else models/pollard.srdf.
    """
    if srdf_path is None:
        side = Path(urdf_path).with_suffix(".srdf") if urdf_path is not None else None
        srdf_path = side if side is not None and side.is_file() else \
            default_urdf().with_suffix(".srdf")
    root = ET.parse(str(srdf_path)).getroot()
    for gs in root.iter("group_state"):
        if gs.get("name") == "home":
            values = {j.get("name"): float(j.get("value")) for j in gs.iter("joint")}
            missing = [n for n in JOINTS if n not in values]
            if missing:
                raise ValueError(f"{srdf_path}: group_state 'home' lacks joints {missing}")
            return np.array([values[n] for n in JOINTS])
    raise ValueError(f"{srdf_path}: no group_state named 'home'")


# --- MJCF export -------------------------------------------------------------------------------
def export_mjcf(path, urdf=None, home=None) -> Path:
    """Write the closed-loop model as a standalone MJCF file and return its path (``-``: stdout).

    ``urdf``: a URDF path or its text (default: the shipped one). The file holds what
    :func:`build_mujoco` builds: the open tree with the massless crosses merged, the same joint
    names, masses and inertias (full precision), sites at the closure frames and at the tool tip,
    and the two loop closures as ``connect`` equalities (docs/model.md §4). For simulation it
    also mirrors the URDF limits (joint ranges, enforced; force ranges), drives each actuated
    joint (docs/model.md §6) with a ``motor`` of the same name whose ``ctrlrange`` is ± its
    effort limit, and keeps the ideal-joint assumption of docs/model.md §13 otherwise (no
    damping, friction or contacts). ``home`` ((12,) in :data:`JOINTS` order or name → value)
    becomes the keyframe "home"; by default the SRDF beside a URDF path gives it. Geometry is
    primitive shapes only: the file refers to no other file.
    """
    mujoco = require_mujoco()

    source = urdf if urdf is not None else default_urdf()
    if not is_urdf_text(source):
        source = Path(source)
        side = source.with_suffix(".srdf")
        if home is None and side.is_file():
            home = home_configuration(side)
    spec, info, _ = closed_loop_spec(source)
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT  # ideal: no collisions
    for j in spec.joints:
        if j.name not in ACTUATED:  # URDF effort 0: no actuator, not "unlimited"
            j.actfrclimited = mujoco.mjtLimited.mjLIMITED_FALSE
    for n in ACTUATED:
        effort = info["joints"][n]["limit"]["effort"]
        act = spec.add_actuator(name=n, target=n, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_motor()
        act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
        act.ctrlrange = [-effort, effort]
    spec.compiler.savecompiled = False  # save the spec itself: 17 significant digits
    model = spec.compile()
    if home is not None:
        values = (np.array([home[n] for n in JOINTS]) if hasattr(home, "keys")
                  else np.asarray(home, dtype=float).reshape(12))
        qpos = np.zeros(model.nq)
        qpos[model.jnt_qposadr[[model.joint(n).id for n in JOINTS]]] = values
        spec.add_key(name="home", qpos=qpos)
    xml = spec.to_xml()
    mujoco.MjModel.from_xml_string(xml)  # stands alone: no file next to it is needed
    with atomic_open(path) as f:
        f.write(xml)
    return Path(path)


__all__ = ["read_urdf", "closed_loop_spec", "check_mjcf", "export_mjcf", "home_configuration",
           "require_mujoco", "TIP"]
