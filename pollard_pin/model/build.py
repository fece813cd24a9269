"""The Pinocchio model: open tree from the URDF plus the two cut spherical joints (docs/model.md
§4).

Closure i is the 3D point constraint ``closure{i}_A`` (on ``link_i``) == ``closure{i}_B`` (on
``platform``). Its residual is ``p_A − p_B`` in world axes; with the constraint Jacobian
``Jc = ∂(p_A − p_B)/∂q`` (LOCAL_WORLD_ALIGNED), a multiplier λ_i in ``τ = Sᵀτ_act + Jcᵀλ`` is
the force the platform exerts on ``link_i`` at the ball joint, in world axes.
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..checks import instance
from ..errors import InputError
from ..names import ACTUATED, PASSIVE, TREE_JOINTS
from .overrides import ParameterError
from .params import Params, load_params
from .paths import models_dir
from .urdf import generate_srdf, generate_urdf

TIP_FRAME = "tip"
DEFAULT_URDF = "pollard.urdf"
DEFAULT_SRDF = "pollard.srdf"


class ModelFileError(InputError):
    """The URDF/SRDF is malformed or does not describe the Pollard tree (one line: what is
    missing or wrong, and in which file)."""


@dataclass(frozen=True)
class Closure:
    """A cut spherical joint: frame ``frame_a`` (leg side) coincides with ``frame_b`` (platform)."""

    name: str
    frame_a: str
    frame_b: str


@dataclass(repr=False)
class Robot:
    """Pinocchio model, data, geometry and loop closures of the Pollard robot.

    Build it with :func:`pollard_pin.load`. The model is the open tree of docs/model.md §3
    (12 revolute joints, ``nq = nv = 12``); the two cut spherical joints are 3D point
    constraints (docs/model.md §4) in ``constraint_models``.

    Attributes
    ----------
    params : Params
        The numbers the model was built from (SI units).
    model, data : pinocchio.Model, pinocchio.Data
        Pinocchio's model of the open tree and its workspace.
    visual_model, collision_model : pinocchio.GeometryModel
        The link geometry (drawn by the viewer).
    closures : tuple of pollard_pin.model.build.Closure
        The two cut spherical joints: frame ``frame_a`` (leg side) meets ``frame_b``
        (platform).
    constraint_models, constraint_datas
        Pinocchio's ``RigidConstraintModel`` and ``RigidConstraintData`` of the closures
        (``CONTACT_3D``, ``LOCAL_WORLD_ALIGNED``).
    urdf : str
        The URDF text the model was built from.
    actuated, passive : tuple of str
        The six actuated and six passive joint names (docs/model.md §6 order).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> robot.model.nq, robot.actuated[:3]
    (12, ('theta21', 'theta21_1', 'theta21_2'))
    >>> q = robot.home()            # the home pose, loops closed to round-off
    >>> bool(robot.as_dict(q)["theta21"] == q[robot.idx_q("theta21")])
    True
    """

    params: Params
    model: pin.Model
    data: pin.Data
    visual_model: pin.GeometryModel
    collision_model: pin.GeometryModel
    closures: tuple[Closure, ...]
    constraint_models: list  # as pin.StdVec_RigidConstraintModel after __post_init__
    constraint_datas: list  # as pin.StdVec_RigidConstraintData
    urdf: str  # the URDF text the model was built from
    actuated: tuple[str, ...] = ACTUATED
    passive: tuple[str, ...] = PASSIVE
    visual_data: pin.GeometryData = field(init=False)
    collision_data: pin.GeometryData = field(init=False)

    def __post_init__(self):
        # Pinocchio's own vector types: a Python list is converted (copied) on every call that
        # takes the constraints, ≈ 7 µs each (getConstraintsJacobian 8 → 1 µs).
        self.constraint_models = _std_vector(pin.StdVec_RigidConstraintModel,
                                             self.constraint_models)
        self.constraint_datas = _std_vector(pin.StdVec_RigidConstraintData,
                                            self.constraint_datas)
        self.visual_data = self.visual_model.createData()
        self.collision_data = self.collision_model.createData()

    def __repr__(self) -> str:
        closures = ", ".join(c.name for c in self.closures)
        return (f"Robot(name={self.model.name!r}, nq={self.model.nq}, nv={self.model.nv}, "
                f"constraints={len(self.constraint_models)} × 3D point ({closures}), "
                f"mass={self.params.total_mass:.4g} kg, params={self.params.source!r})")

    # --- name ↔ index helpers -------------------------------------------------------------
    @property
    def joint_names(self) -> tuple[str, ...]:
        """The tree joints in configuration order (universe excluded)."""
        return tuple(self.model.names[1:])

    def joint_id(self, name: str) -> int:
        if not self.model.existJointName(name):
            raise KeyError(f"no joint named {name!r}; joints: {', '.join(self.joint_names)}")
        return int(self.model.getJointId(name))

    def idx_q(self, name: str) -> int:
        return int(self.model.joints[self.joint_id(name)].idx_q)

    def idx_v(self, name: str) -> int:
        return int(self.model.joints[self.joint_id(name)].idx_v)

    def frame_id(self, name: str) -> int:
        if not self.model.existFrame(name):
            raise KeyError(f"no frame named {name!r}")
        return int(self.model.getFrameId(name))

    # Cached (read-only): the joint structure never changes after loading, and these are
    # looked up on every control tick (≈ 8 µs each when rebuilt).
    @cached_property
    def constraint_pairs(self) -> tuple:
        """(model, data) of each constraint, elements of the Pinocchio vectors, fetched once
        (each fetch from a vector costs ≈ 1.5 µs)."""
        return tuple(zip(tuple(self.constraint_models), tuple(self.constraint_datas)))

    @cached_property
    def closure_frame_ids(self) -> tuple[tuple[int, int], ...]:
        """(frame_a, frame_b) ids of each closure, in :attr:`closures` order."""
        return tuple((self.frame_id(c.frame_a), self.frame_id(c.frame_b))
                     for c in self.closures)

    @cached_property
    def actuated_v(self) -> np.ndarray:
        return self._index_array(self.actuated)

    @cached_property
    def passive_v(self) -> np.ndarray:
        return self._index_array(self.passive)

    def _index_array(self, names: tuple[str, ...]) -> np.ndarray:
        out = np.array([self.idx_v(n) for n in names])
        out.setflags(write=False)
        return out

    @property
    def tip_frame(self) -> int:
        return self.frame_id(TIP_FRAME)

    @property
    def q_reference(self) -> np.ndarray:
        """The SRDF ``home`` posture (closed-form IK, as written in the file)."""
        return np.array(self.model.referenceConfigurations["home"])

    def home(self) -> np.ndarray:
        """The home configuration (docs/model.md §9) at full precision: the closed-form IK of
        the home pose, whose loops close to round-off (the SRDF keeps 12 digits)."""
        values = home_joint_values(self.params)
        return np.array([values[n] for n in self.joint_names])

    def as_dict(self, q: np.ndarray) -> dict[str, float]:
        return {n: float(q[self.idx_q(n)]) for n in self.joint_names}


def _std_vector(kind, items):
    """``items`` as the Pinocchio vector ``kind`` (itself if it is one already). The vector
    holds copies: use its elements, not the originals, afterwards."""
    if isinstance(items, kind):
        return items
    out = kind()
    for item in items:
        out.append(item)
    return out


def parse_closures(urdf: str) -> tuple[Closure, ...]:
    """The ``<loop_closure>`` elements of a Pollard URDF."""
    try:
        root = ET.fromstring(urdf)
    except ET.ParseError as exc:
        raise ModelFileError(f"URDF is not well-formed XML: {exc}") from None
    closures = []
    for el in root.iter("loop_closure"):
        try:
            c = Closure(el.attrib["name"], el.attrib["frame_a"], el.attrib["frame_b"])
        except KeyError as exc:
            raise ModelFileError(f"<loop_closure> {el.attrib} lacks attribute {exc}") from None
        if el.attrib.get("type", "spherical") != "spherical":
            raise ModelFileError(f"loop closure {c.name!r}: only type='spherical' is supported")
        closures.append(c)
    if len(closures) != 2:
        raise ModelFileError("expected 2 <loop_closure> elements (docs/model.md §4), "
                             f"found {len(closures)}")
    return tuple(closures)


def _constraint(model: pin.Model, c: Closure) -> pin.RigidConstraintModel:
    fa, fb = (model.frames[model.getFrameId(n)] for n in (c.frame_a, c.frame_b))
    cm = pin.RigidConstraintModel(pin.ContactType.CONTACT_3D, model, fa.parentJoint,
                                  fa.placement, fb.parentJoint, fb.placement,
                                  pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    cm.name = c.name
    return cm


def build(params: Params, urdf: str, srdf: str) -> Robot:
    """Assemble a :class:`Robot` from URDF and SRDF text."""
    try:
        model = pin.buildModelFromXML(urdf)
    except Exception as exc:  # Pinocchio raises RuntimeError/ValueError with its own text
        raise ModelFileError(f"Pinocchio cannot build the URDF: {exc}") from None
    missing = [n for n in ACTUATED + PASSIVE if not model.existJointName(n)]
    if missing or model.nq != 12 or model.nv != 12:
        raise ModelFileError("URDF is not the Pollard tree of docs/model.md §3: "
                             f"missing joints {missing},"
                             f" nq={model.nq}, nv={model.nv} (expected 12, 12)")
    closures = parse_closures(urdf)
    for c in closures:
        for f in (c.frame_a, c.frame_b):
            if not model.existFrame(f):
                raise ModelFileError(f"loop closure {c.name!r} names frame {f!r}, not in the URDF")
    pin.loadReferenceConfigurationsFromXML(model, srdf, False)
    if "home" not in model.referenceConfigurations:
        raise ModelFileError("SRDF has no group_state named 'home'")
    visual = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.VISUAL)
    collision = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.COLLISION)
    cmodels = [_constraint(model, c) for c in closures]
    return Robot(params=params, model=model, data=model.createData(), visual_model=visual,
                 collision_model=collision, closures=closures, constraint_models=cmodels,
                 constraint_datas=[cm.createData() for cm in cmodels], urdf=urdf)


def home_joint_values(params: Params) -> dict[str, float]:
    """Tree joint values at the home pose, by the closed-form IK of docs/model.md §7."""
    from ..analytic.closed_form import position_ik

    q = position_ik(params, np.asarray(params.home_pose)[None, :])[0]
    return {n: float(v) for n, v in zip(TREE_JOINTS, q[:12])}


def generate(params: Params) -> tuple[str, str]:
    """URDF and SRDF text for these parameters."""
    return generate_urdf(params), generate_srdf(params, home_joint_values(params))


def check_robot(robot, name: str = "robot") -> Robot:
    """``robot`` when it is a :class:`Robot`; else one :class:`~pollard_pin.errors.InputError`
    line naming the argument ``name`` (the public entry points' first check)."""
    return instance(robot, name, Robot, "a Robot (pollard_pin.load())")


def load(params: Params | str | Path | None = None) -> Robot:
    """Load the robot: the Pinocchio model of the Pollard mechanism with its loop closures.

    Parameters
    ----------
    params : Params or str or pathlib.Path or None, optional
        ``None`` (the default) loads the shipped ``models/pollard.urdf`` and ``pollard.srdf``
        with the shipped parameters (``models/pollard.toml``, docs/model.md §5). A
        :class:`~pollard_pin.Params` (from :func:`~pollard_pin.load_params`), or the path of
        a parameter TOML (which may list only the keys that differ from the shipped file),
        generates the description in memory from those parameters.

    Returns
    -------
    Robot
        The model, its data, geometry and closures.

    Raises
    ------
    ParameterError
        A parameter file or value breaks a rule (the message names the key and the rule).
    ModelFileError
        The shipped URDF/SRDF do not match the shipped parameters, or Pinocchio cannot build
        them.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> robot.joint_names[:3]
    ('theta21', 'theta43', 'theta54')
    >>> longer = pp.load(pp.load_params(overrides={"chain0.x32": 0.34}))
    >>> round(longer.params.x32, 3)
    0.34
    """
    if params is None:
        d = models_dir()
        params = load_params()
        urdf, srdf = (d / DEFAULT_URDF).read_text(), (d / DEFAULT_SRDF).read_text()
        if (urdf, srdf) != generate(params):  # someone edited the TOML (or the URDF) by hand
            raise ModelFileError(f"{d / DEFAULT_URDF} and {DEFAULT_SRDF} do not match "
                                 f"{d / 'pollard.toml'}: regenerate them from the parameters "
                                 "(generate(params), or `make urdf` in a checkout)")
        return build(params, urdf, srdf)
    instance(params, "params", (Params, str, os.PathLike),
             "a Params, a parameter file's path or None", error=ParameterError)
    if not isinstance(params, Params):
        params = load_params(params)
    return build(params, *generate(params))


# --- constraint residual and Jacobian ---------------------------------------------------------
def constraint_residual(model, data, cmodels, cdatas, q) -> np.ndarray:
    """The loop-closure residual: the stacked ``p_A − p_B`` [m] of the two closures.

    Parameters
    ----------
    model, data : pinocchio.Model, pinocchio.Data
        ``robot.model`` and ``robot.data`` (``data``'s kinematics are updated here).
    cmodels, cdatas
        ``robot.constraint_models`` and ``robot.constraint_datas``.
    q : ndarray
        A configuration (12,) [rad], :attr:`Robot.joint_names` order.

    Returns
    -------
    ndarray
        Shape (6,): ``p_A − p_B`` of closure 1 then closure 2 [m], world axes
        (docs/model.md §4); zero when the loops are closed.

    Examples
    --------
    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> from pollard_pin.model import constraint_residual
    >>> r = pp.load()
    >>> res = constraint_residual(r.model, r.data, r.constraint_models,
    ...                           r.constraint_datas, r.home())
    >>> bool(np.abs(res).max() < 1e-12)
    True
    """
    pin.forwardKinematics(model, data, q)
    out = []
    for cm, cd in zip(cmodels, cdatas):
        cm.calc(model, data, cd)
        out.append(cd.oMc1.translation - cd.oMc2.translation)
    return np.concatenate(out)


def constraint_residual_jacobian(robot: Robot, q) -> tuple[np.ndarray, np.ndarray]:
    """(:func:`constraint_residual`, :func:`constraint_jacobian`) of ``robot`` at ``q`` from one
    kinematics pass (the Jacobians' pass places the joints as forward kinematics does, same
    bits), with ``robot.data`` and its constraint data."""
    model, data = robot.model, robot.data
    pin.computeJointJacobians(model, data, q)
    out = []
    for cm, cd in robot.constraint_pairs:
        cm.calc(model, data, cd)
        out.append(cd.oMc1.translation - cd.oMc2.translation)
    return np.concatenate(out), pin.getConstraintsJacobian(
        model, data, robot.constraint_models, robot.constraint_datas)


def constraint_jacobian(model, data, cmodels, cdatas, q) -> np.ndarray:
    """The constraint Jacobian ``Jc = ∂(p_A − p_B)/∂q`` of the two closures.

    Parameters
    ----------
    model, data : pinocchio.Model, pinocchio.Data
        ``robot.model`` and ``robot.data`` (``data``'s Jacobians are updated here).
    cmodels, cdatas
        ``robot.constraint_models`` and ``robot.constraint_datas``.
    q : ndarray
        A configuration (12,) [rad].

    Returns
    -------
    ndarray
        Shape (6, 12) [m/rad], world axes (``LOCAL_WORLD_ALIGNED``, docs/model.md §4):
        the residual's rows, :func:`~pollard_pin.model.constraint_residual` order.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> from pollard_pin.model import constraint_jacobian
    >>> r = pp.load()
    >>> constraint_jacobian(r.model, r.data, r.constraint_models, r.constraint_datas,
    ...                     r.home()).shape
    (6, 12)
    """
    pin.computeJointJacobians(model, data, q)
    for cm, cd in zip(cmodels, cdatas):
        cm.calc(model, data, cd)  # refresh before reading the Jacobian (stale otherwise)
    return pin.getConstraintsJacobian(model, data, cmodels, cdatas)
