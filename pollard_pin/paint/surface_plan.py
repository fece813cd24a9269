"""Plan a paint job over a part's mesh (docs/model.md §23): the passes of :mod:`.surface`
timed into one C² rest-to-rest program the robot and its motors can run, and its film.

Pieces, each a polynomial in time or a polynomial of one, so positions, rates and
accelerations are exact at any time (the trajectory's ``curve``):

- pass: the gun pose (tip, angles) as a quintic interpolating B-spline P(s) of the surface arc
  s through the pass samples, run at ṡ = ±v: rate P'(s)·ṡ, acceleration P''(s)·v²;
- turnaround, ramp: the quintic in time matching pose, rate and acceleration at both ends
  (from rest, or to rest: a ramp starts v·τ/2 before its pass, as the panel's); the
  turnarounds lie off the part (the passes run EXTENSION σ past its edges) with the gun
  closed (``spray`` 0), the passes open (1).

Each turnaround and ramp is the shortest whose motors stay within UTILISATION of peak torque
and speed (:func:`.motion.fastest`); then the whole path is checked like ``run`` (reach,
margins, joint limits) and against the motors' peak torque, speed and continuous (RMS)
rating at CHECK_REFINE× its sampling.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import make_interp_spline

from ..analytic.taskspace import angles_from_rotation, rotation
from ..dynamics.averages import time_rms
from ..dynamics.motors import Actuators
from ..paths.trajectory import Trajectory
from .deposition import BLOCK_ELEMENTS, gun_of
from .errors import BudgetError, PlanError, ReachError
from .film import film_spacing
from .film_points import surface_points
from .mesh import Part, load_part
from .mesh_film import MeshFilm, mesh_film
from .motion import fastest, motion
from .policy import (
    CHECK_REFINE,
    MAX_PATH_SAMPLES,
    MAX_STEP,
    STEP_SIGMA,
    TURN_SAMPLES,
    UTILISATION,
    first_guess,
)
from .surface import SMOOTHING, SurfaceLayout, pass_spacing, pass_speed, surface_layout


def load_job_part(job) -> Part:
    """The job's part, read and placed (:func:`.mesh.load_part`)."""
    from .mesh import MAX_ANGLE

    return load_part(job.mesh, job.units, job.position, job.rotation, job.facing,
                     MAX_ANGLE if job.max_angle is None else job.max_angle)


def gun_frame(axis: np.ndarray) -> np.ndarray:
    """Tool rotations (K, 3, 3) spraying along unit ``axis`` (K, 3): R = [a, c × a, c], c the
    world z projected off a (the panel's [−n, u, v] for a = −n)."""
    ez = np.array([0.0, 0.0, 1.0])
    c = ez - (axis @ ez)[:, None] * axis
    c /= np.linalg.norm(c, axis=1, keepdims=True)
    return np.stack([axis, np.cross(c, axis), c], axis=-1)


class PassPiece:
    """A pass run at surface speed ``v``, forwards (s from 0) or backwards."""

    kind = "pass"

    def __init__(self, s, poses, v: float, forward: bool, index: int):
        self.spline = make_interp_spline(s, poses, k=5)
        self.d1, self.d2 = self.spline.derivative(1), self.spline.derivative(2)
        self.length, self.v, self.forward, self.index = float(s[-1]), v, forward, index
        self.duration = self.length / v

    def evaluate(self, tau):
        rate = self.v if self.forward else -self.v
        s = tau * self.v if self.forward else self.length - tau * self.v
        s = np.clip(s, 0.0, self.length)
        return self.spline(s), self.d1(s) * rate, self.d2(s) * self.v ** 2

    def state(self, end: bool):
        return tuple(x[0] for x in self.evaluate(np.array([self.duration if end else 0.0])))


class Quintic:
    """The quintic in time from (p0, v0, a0) to (p1, v1, a1) over ``duration``."""

    def __init__(self, kind: str, start, end, duration: float):
        (p0, v0, a0), (p1, v1, a1) = start, end
        T = duration
        dp = p1 - p0
        self.c = np.array([
            p0, v0, a0 / 2,
            (20 * dp - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T ** 2) / (2 * T ** 3),
            (-30 * dp + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T ** 2) / (2 * T ** 4),
            (12 * dp - 6 * (v1 + v0) * T - (a0 - a1) * T ** 2) / (2 * T ** 5)])
        self.kind, self.duration = kind, T

    def evaluate(self, tau):
        tau = np.clip(tau, 0.0, self.duration)[:, None]
        c = self.c
        p = c[0] + tau * (c[1] + tau * (c[2] + tau * (c[3] + tau * (c[4] + tau * c[5]))))
        d = c[1] + tau * (2 * c[2] + tau * (3 * c[3] + tau * (4 * c[4] + tau * 5 * c[5])))
        dd = 2 * c[2] + tau * (6 * c[3] + tau * (12 * c[4] + tau * 20 * c[5]))
        return p, d, dd


def ramp(kind: str, state, duration: float, into: bool) -> Quintic:
    """From rest to a pass's start ``state`` (``into``), or from its end to rest: the rest
    pose lies v·τ/2 back (or on) along the pass's rate, as the panel's ramps travel."""
    p, v, a = state
    z = np.zeros_like(p)
    if into:
        return Quintic(kind, (p - v * duration / 2, z, z), state, duration)
    return Quintic(kind, state, (p + v * duration / 2, z, z), duration)


@dataclass(frozen=True, eq=False)
class Program:
    """Pieces back to back from t = 0."""

    pieces: tuple

    @property
    def start(self) -> np.ndarray:
        d = np.array([p.duration for p in self.pieces])
        return np.concatenate([[0.0], np.cumsum(d)[:-1]])

    @property
    def total(self) -> float:
        return float(sum(p.duration for p in self.pieces))

    def piece_at(self, t) -> np.ndarray:
        return np.clip(np.searchsorted(self.start, t, side="right") - 1, 0,
                       len(self.pieces) - 1)

    def evaluate(self, t):
        """(poses, rates, accelerations) (N, 6) at times ``t``; exactly at rest at both
        ends."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        start, idx = self.start, self.piece_at(t)
        out = [np.empty((len(t), 6)) for _ in range(3)]
        for i in np.unique(idx):
            sel = idx == i
            for o, x in zip(out, self.pieces[i].evaluate(t[sel] - start[i])):
                o[sel] = x
        ends = (t <= 0.0) | (t >= self.total)
        out[1][ends], out[2][ends] = 0.0, 0.0
        return tuple(out)

    def spray(self, t) -> np.ndarray:
        """The trigger at times ``t``: 1 on the passes, 0 elsewhere."""
        kinds = np.array([p.kind == "pass" for p in self.pieces], dtype=float)
        return kinds[self.piece_at(np.atleast_1d(np.asarray(t, dtype=float)))]


@dataclass(frozen=True)
class SurfacePlan:
    job: object  # PartJob
    part: Part
    layout: SurfaceLayout
    program: Program
    trajectory: Trajectory
    spray: np.ndarray  # (N,) the trigger at the trajectory's samples
    speed: float  # surface speed of the spot on the passes [m/s]
    coats: int
    ratios: dict  # per motor: peak_torque, rms_torque, speed (each over its rating)
    timings: dict = field(default_factory=dict)

    @property
    def cycle_time(self) -> float:
        return self.program.total

    @property
    def passes(self) -> int:
        return len(self.layout.passes) * self.coats

    @property
    def lower_bound(self) -> float:
        """Painting-only lower bound [s]: painted area × target / flow."""
        return self.part.painted_area * self.job.thickness / self.job.flow


def _pass_poses(layout: SurfaceLayout):
    out = []
    ref = None
    for p in layout.passes:
        ang = np.unwrap(angles_from_rotation(gun_frame(p.axis)), axis=0)
        if ref is None:
            ref = ang[0]
        ang -= 2 * math.pi * np.round((ang[0] - ref) / (2 * math.pi))
        out.append(np.column_stack([p.tip, ang]))
    return out


def pass_pieces(layout: SurfaceLayout, v: float, coats: int) -> list:
    """The passes of every coat in serpentine order (a coat runs back over the last)."""
    poses = _pass_poses(layout)
    order = []
    for c in range(coats):
        order += list(range(len(poses)) if c % 2 == 0 else range(len(poses) - 1, -1, -1))
    return [PassPiece(layout.passes[k].s, poses[k], v, i % 2 == 0, k)
            for i, k in enumerate(order)]


def _pass_use(robot, act, layout: SurfaceLayout, pieces) -> float:
    """The motors' peak utilisation over one coat's passes (at their samples)."""
    ev = [p.evaluate(np.linspace(0, p.duration, len(layout.passes[p.index].s)))
          for p in pieces]
    poses, d, dd = (np.concatenate([e[i] for e in ev]) for i in range(3))
    try:
        m = motion(robot, act, poses, d, dd)
    except ReachError as exc:
        lengths = np.cumsum([len(layout.passes[p.index].s) for p in pieces])
        k = int(np.searchsorted(lengths, exc.sample, side="right"))
        p = layout.passes[pieces[k].index]
        tip = np.asarray(exc.pose[:3])
        j = int(np.argmin(np.linalg.norm(p.tip - tip, axis=1)))
        x = p.surface[j]
        raise ReachError(f"the path leaves the workspace on pass {pieces[k].index + 1} of "
                         f"{len(layout.passes)} at part point ({x[0]:.3f}, {x[1]:.3f}, "
                         f"{x[2]:.3f}) m, tip ({tip[0]:.3f}, {tip[1]:.3f}, "
                         f"{tip[2]:.3f}) m: {exc}; {_reachable(robot, layout, pieces, poses)}",
                         exc.sample, exc.pose) from None
    return float(m.utilisation.max())


def _reachable(robot, layout: SurfaceLayout, pieces, poses) -> str:
    """Which of the part the gun reaches on the passes: the share of the on-part pass
    samples whose pose passes ``run``'s rules (docs/model.md §22's workspace test) and the
    box of their surface points."""
    from ..workspace.reach import evaluate

    ok = evaluate(robot, poses)["reachable"] > 0
    on = np.concatenate([layout.passes[p.index].on_part for p in pieces])
    surf = np.concatenate([layout.passes[p.index].surface for p in pieces])
    good = ok & on
    if not good.any():
        return "no point of the painted faces is within reach with the gun normal to it"
    lo, hi = surf[good].min(axis=0), surf[good].max(axis=0)
    return (f"reachable: {100 * good.sum() / max(on.sum(), 1):.0f} % of the passes, "
            f"x {lo[0]:.3f}..{hi[0]:.3f}, y {lo[1]:.3f}..{hi[1]:.3f}, "
            f"z {lo[2]:.3f}..{hi[2]:.3f} m")


def build_program(passes, taus) -> Program:
    """Ramp, pass, turn, pass, ..., ramp with the given turn/ramp durations (P + 1,)."""
    pieces = [ramp("ramp", passes[0].state(False), taus[0], True)]
    for k, p in enumerate(passes):
        pieces.append(p)
        if k + 1 < len(passes):
            pieces.append(Quintic("turn", p.state(True), passes[k + 1].state(False),
                                  taus[k + 1]))
    pieces.append(ramp("ramp", passes[-1].state(True), taus[-1], False))
    return Program(tuple(pieces))


def time_step(job, pieces, v: float) -> float:
    """The path's time step [s]: STEP_SIGMA σ of the tip's travel, the tip moving up to
    tip_rate × the spot's speed ``v`` (a convex part's stretch); the passes alone within the
    sample budget."""
    tip_rate = max(1.0, max(float(np.linalg.norm(p.d1(p.spline.t[5:-5])[:, :3], axis=1).max())
                            for p in pieces if p.kind == "pass"))
    dt = min(MAX_STEP, STEP_SIGMA * job.sigma / (v * tip_rate))
    swept = sum(p.duration for p in pieces)
    if swept / dt > MAX_PATH_SAMPLES:
        raise BudgetError(f"{job.source}: the passes alone need {swept / dt:.3g} samples "
                          f"({swept:.4g} s at {v:.4g} m/s), budget {MAX_PATH_SAMPLES:.3g}: "
                          "a thinner film, more flow or fewer coats")
    return dt


def _where(program: Program, layout: SurfaceLayout, t: float, pose) -> str:
    piece = program.pieces[int(program.piece_at(np.array([t]))[0])]
    tip = np.asarray(pose[:3])
    where = f"tool tip ({tip[0]:.3f}, {tip[1]:.3f}, {tip[2]:.3f}) m"
    if piece.kind == "pass":
        p = layout.passes[piece.index]
        k = int(np.argmin(np.linalg.norm(p.tip - tip, axis=1)))
        x = p.surface[k]
        return (f"on pass {piece.index + 1} of {len(layout.passes)} (level "
                f"{p.level:.4g} m) over the part at ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m, "
                f"{where}")
    return f"in a {piece.kind}, {where}"


def plan_surface(robot, job, act: Actuators, part: Part | None = None) -> SurfacePlan:
    """The spray program over the job's part (read from ``job.mesh`` unless given): see the
    module notes. Raises :class:`PlanError` (or :class:`ReachError`) naming where it fails."""
    clock = [time.perf_counter()]
    part = load_job_part(job) if part is None else part
    v = pass_speed(job, pass_spacing(job))
    coats = job.coats or 1
    smoothing = 0.0
    while True:  # the least smoothing whose passes the motors follow at speed v
        layout = surface_layout(part, job, min_smoothing=smoothing)
        pieces = pass_pieces(layout, v, coats)
        use = _pass_use(robot, act, layout, pieces[:len(layout.passes)])
        if use <= UTILISATION:
            break
        wider = [w for w in SMOOTHING if w > layout.smoothing]
        if not wider:
            raise PlanError(f"{part.source}: the motors need {use:.3g}× their peak torque or "
                            f"speed on the passes at {v:.4g} m/s even with the gun's normal "
                            f"averaged over {layout.smoothing:g} m: a thinner coat (more "
                            "coats), a smaller standoff or a gentler part")
        smoothing = wider[0]
    dt = time_step(job, pieces, v)
    clock.append(time.perf_counter())

    def evaluate(taus):
        prog = build_program(pieces, taus)
        sel = [i for i, p in enumerate(prog.pieces) if p.kind != "pass"]
        start = prog.start
        x = np.linspace(0.0, 1.0 - 1e-12, TURN_SAMPLES)
        t = np.concatenate([start[i] + prog.pieces[i].duration * x for i in sel])
        try:
            m = motion(robot, act, *prog.evaluate(t))
        except ReachError as exc:
            k = exc.sample // TURN_SAMPLES
            raise ReachError(f"the path leaves the workspace "
                             f"{_where(prog, layout, t[exc.sample], exc.pose)} ({taus[k]:.3g} "
                             f"s): {exc}", exc.sample, exc.pose) from None
        return m.utilisation.reshape(len(sel), TURN_SAMPLES, -1).max(axis=(1, 2))

    taus = fastest(evaluate, np.full(len(pieces) + 1, first_guess(v)), UTILISATION)
    program = build_program(pieces, taus)
    clock.append(time.perf_counter())
    n = math.ceil(program.total / dt) + 1
    if n > MAX_PATH_SAMPLES:
        raise BudgetError(f"{job.source}: the path needs {n:.3g} samples ({program.total:.4g} "
                          f"s), budget {MAX_PATH_SAMPLES:.3g}: a thinner film or more flow")
    t = np.linspace(0.0, program.total, n)
    traj = Trajectory(t, *program.evaluate(t), name="paint", derivatives="analytic",
                      curve=program.evaluate)
    tf = np.linspace(0.0, program.total, CHECK_REFINE * (n - 1) + 1)
    try:
        fine = motion(robot, act, *program.evaluate(tf))
    except ReachError as exc:
        raise ReachError(f"the path leaves the workspace "
                         f"{_where(program, layout, tf[exc.sample], exc.pose)}: {exc}",
                         exc.sample, exc.pose) from None
    ratios = {"peak_torque": fine.torque_ratio.max(0),
              "rms_torque": time_rms(tf, fine.torque) / act.column("continuous_torque"),
              "speed": fine.speed_ratio.max(0)}
    for what, r in ratios.items():
        if r.max() > 1.0:
            k = int(np.argmax(r))
            raise PlanError(f"motor {act.names[k]} needs {r[k]:.3g}× its "
                            f"{what.replace('_', ' ')} rating on the passes at "
                            f"{v:.4g} m/s: more coats of a thinner film, or a wider "
                            "spacing")
    clock.append(time.perf_counter())
    return SurfacePlan(job, part, layout, program, traj, program.spray(t), v, coats, ratios,
                       {"layout": clock[1] - clock[0], "turnarounds": clock[2] - clock[1],
                        "check": clock[3] - clock[2]})


def part_resolution(job, resolution: float | None = None) -> float:
    """The film point spacing [m] on a part: the rule of :func:`.film.film_spacing`."""
    return film_spacing(job.sigma, resolution, "film point spacing")


def live_faces(part: Part, tips) -> np.ndarray:
    """Faces (F,) bool that some gun tip lies in front of: a point s on a face of normal n
    gets nothing from a tip p with (p − s)·n ≤ 0 (the rate's cos i, docs/model.md §20), and
    s·n is the same over a flat face, so a face with max_p p·n ≤ v₀·n gets exactly 0."""
    level = np.einsum("ij,ij->i", part.vertices[part.faces[:, 0]], part.normals)
    ahead = np.full(len(part.faces), -np.inf)
    block = max(1, BLOCK_ELEMENTS // len(part.faces))  # (block × F) products: ~8 MB each
    for start in range(0, len(tips), block):
        ahead = np.maximum(ahead, (tips[start:start + block] @ part.normals.T).max(axis=0))
    return ahead > level


def surface_film(plan: SurfacePlan, resolution: float | None = None):
    """(film points on the painted faces and on every face any tip lies in front of, their
    film :class:`.mesh_film.MeshFilm`, the painted mask over the points, the transfer
    efficiency): the film of the plan's path with shadows and the trigger. Faces behind every
    tip get exactly nothing (:func:`live_faces`), so the volume landed on the points is the
    volume landed on the part."""
    job = plan.job
    tr = plan.trajectory
    on = plan.spray > 0
    faces = live_faces(plan.part, tr.poses[on, :3]) | plan.part.painted
    pts = surface_points(plan.part, resolution, sigma=job.sigma, faces=faces)
    axes = rotation(tr.poses)[:, :, 0]
    film: MeshFilm = mesh_film(gun_of(job), tr.t, tr.poses[:, :3], axes, pts, plan.part,
                               plan.spray)
    efficiency = film.landed / film.sprayed if film.sprayed > 0 else float("nan")
    return pts, film, plan.part.painted[pts.faces], efficiency


__all__ = ["PassPiece", "Program", "Quintic", "SurfacePlan", "build_program",
           "gun_frame", "live_faces", "load_job_part", "part_resolution", "pass_pieces",
           "plan_surface", "surface_film", "time_step"]
