"""The closed-loop state from measured actuator angles and rates, once per control tick of a
simulation (docs/model.md §18): the passive angles by forward kinematics (docs/model.md §4),
the constraint Jacobian Jc, the velocity map N (§12), the rates v = N θ̇ and the tree
acceleration a₀ at θ̈ = 0 on the loops (§11, for the computed torque), in one compiled call
(:class:`~.kernels.ClosedState`) instead of some thirty Pinocchio and LAPACK calls.

The compiled path repeats :func:`~.closure.close_loops`' Newton step for step on the kernels'
tree passes (the same kinematics as Pinocchio's to round-off). Wherever it does not find a
clearly regular state — no convergence, input not finite, σ_min(Jc_p) < GRAM_TRUSTED σ_max —
the reference path (Pinocchio) runs instead and raises what it raises, with its messages.
"""
from __future__ import annotations

import numpy as np

from ..model.build import Robot
from .closure import CLOSURE_TOL, MAX_ITER, close_loops, closure_drift
from .ik_batch import layout
from .kernels import ClosedState
from .singularity import GRAM_TRUSTED, actuator_velocity_map, solve_small

# λ_min/λ_max of Jc_pᵀJc_p above which the compiled Gram value is trusted (σ ratio above
# GRAM_TRUSTED, far above the floor SIGMA_FLOOR; docs/model.md §12)
_TRUSTED = GRAM_TRUSTED ** 2


def reference_state(robot: Robot, theta, dtheta, q_guess=None):
    """(q, v, Jc, N, a₀) by Pinocchio: :func:`~.closure.close_loops` (its checks and errors),
    N = :func:`~.singularity.actuator_velocity_map`, v = N·θ̇ and a₀ from the closures' drift
    (a₀[passive] = −Jc_p⁻¹ J̇c v, 0 on the actuators)."""
    q, Jc = close_loops(robot, theta, q_guess)
    ia, ip = robot.actuated_v, robot.passive_v
    N = actuator_velocity_map(Jc, ia, ip)
    v = N @ dtheta
    a0 = np.zeros(robot.model.nv)
    a0[ip] = -solve_small(Jc[:, ip], closure_drift(robot, q, v))
    return q, v, Jc, N, a0


class LoopSensor:
    """``sensor(theta, dtheta, q_guess) → (q, v, Jc, N, a0)`` of ``robot``: as
    :func:`reference_state`, compiled where the model's joints allow (revolute, nq = nv)."""

    def __init__(self, robot: Robot):
        self.robot = robot
        self._kernel = None
        model = robot.model
        if model.nq == model.nv:
            try:
                tree = layout(robot).tree
            except NotImplementedError:  # a joint the kernels do not model: Pinocchio only
                tree = None
            if tree is not None:
                self._kernel = ClosedState(tree, robot.actuated_v, robot.passive_v, model.nq,
                                           model.nv)

    @property
    def compiled(self) -> bool:
        return self._kernel is not None

    def __call__(self, theta, dtheta, q_guess=None):
        if self._kernel is not None:
            guess = self.robot.q_reference if q_guess is None else q_guess
            try:
                steps, q, v, Jc, N, a0, (lo, hi) = self._kernel(theta, dtheta, guess,
                                                                CLOSURE_TOL, MAX_ITER)
            except (ValueError, TypeError):  # wrong sizes: the reference path says which
                steps = -1
            if steps >= 0 and lo > _TRUSTED * hi:  # (NaN fails)
                return q, v, Jc, N, a0
        return reference_state(self.robot, theta, dtheta, q_guess)
