"""The plant's perturbations against physics (docs/model.md §18), not only against its own
inverse dynamics: the payload's static torque is the virtual work of its weight at the tool
tip, a mass error scales every torque by exactly 1 + e; the closed-loop dynamics in actuator
coordinates and the closure drift against independent computations."""
import numpy as np
import pinocchio as pin
import pytest

from pollard_pin.dynamics.inverse import JointLosses, inverse_dynamics_sample, reduced_dynamics
from pollard_pin.dynamics.plant import ModelMismatch, Plant
from pollard_pin.kinematics.closure import closure_drift
from pollard_pin.kinematics.singularity import actuator_velocity_map
from pollard_pin.model.build import constraint_jacobian
from pollard_pin.paths.curves import thesis_trajectory


@pytest.fixture(scope="module")
def ik(robot):
    import pollard_pin as pp

    traj = thesis_trajectory(samples=201)
    return pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)


def _tip_map(robot, q):
    """J_tip N (3 × 6): actuator rates → tool-tip point velocity, world axes."""
    model, data = robot.model, robot.data
    Jc = constraint_jacobian(model, data, robot.constraint_models, robot.constraint_datas, q)
    N = actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    J = pin.getFrameJacobian(model, data, robot.tip_frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return J[:3] @ N


def test_payload_static_torque_is_the_weight_at_the_tip(robot, ik):
    """A point mass m at the tool tip adds τ = −(J_tip N)ᵀ m g to the static torque (virtual
    work of its weight; g = (0, 0, −9.81) m/s²): 5.2e-15 relative (asserted 5e-13)."""
    m = 0.05
    zero = np.zeros(robot.model.nv)
    loaded, bare = Plant(robot, ModelMismatch(payload=m)), Plant(robot)
    g = np.asarray(robot.model.gravity.linear)
    worst = 0.0
    for q in ik.q[::20]:
        extra = loaded.actuator_torque(q, zero, zero) - bare.actuator_torque(q, zero, zero)
        weight = -_tip_map(robot, q).T @ (m * g)
        worst = max(worst, np.abs(extra - weight).max() / np.abs(weight).max())
    assert worst <= 5e-13


@pytest.mark.parametrize("e", [0.1, -0.3])
def test_mass_error_scales_the_torque_by_one_plus_e(robot, ik, e):
    """Every link's mass and inertia × (1 + e) scale the inverse dynamics, linear in them, by
    exactly 1 + e along the moving thesis curve: 1.1e-15 relative (asserted 1e-13). A payload
    does not scale that way (the check can fail)."""
    scaled, bare = Plant(robot, ModelMismatch(mass_error=e)), Plant(robot)
    worst = 0.0
    for q, v, a in zip(ik.q[::20], ik.v[::20], ik.a[::20]):
        tau = bare.actuator_torque(q, v, a)
        worst = max(worst, np.abs(scaled.actuator_torque(q, v, a) - (1 + e) * tau).max()
                    / np.abs(tau).max())
    assert worst <= 1e-13
    q, v, a = ik.q[100], ik.v[100], ik.a[100]
    tau = bare.actuator_torque(q, v, a)
    payload = Plant(robot, ModelMismatch(payload=0.1 * robot.params.total_mass))
    assert np.abs(payload.actuator_torque(q, v, a) - 1.1 * tau).max() > 1e-3 * np.abs(tau).max()


def test_reduced_dynamics_is_the_inverse_dynamics(robot, ik):
    """M_red θ̈ + h_red equals the closed-loop inverse dynamics of §13 at the IK's consistent
    accelerations, with and without losses: 2.8e-15 relative (asserted 3e-13)."""
    ia = robot.actuated_v
    losses = JointLosses(viscous=0.01, coulomb=0.02, armature=np.linspace(1e-4, 1e-3, 12))
    worst = 0.0
    for q, v, a in zip(ik.q[::13], ik.v[::13], ik.a[::13]):
        for loss in (None, losses):
            M, h = reduced_dynamics(robot, q, v, loss)
            tau = inverse_dynamics_sample(robot, q, v, a, loss)[0]
            worst = max(worst, np.abs(M @ a[ia] + h - tau).max() / np.abs(tau).max())
    assert worst <= 3e-13


def test_closure_drift_matches_the_batched_ik(robot, ik):
    """γ_c = J̇c v from Pinocchio's classical accelerations: Jc a = −γ_c at the accelerations
    of the compiled batched IK (docs/model.md §11): 7.8e-15 relative (asserted 1e-12); and
    J̇c v by central differences of Jc along v (h = 1e-6): 2.9e-10 (asserted 3e-8)."""
    model, data = robot.model, robot.data

    def jac(q):
        return constraint_jacobian(model, data, robot.constraint_models,
                                   robot.constraint_datas, q)

    worst = fd = 0.0
    for q, v, a in zip(ik.q[::10], ik.v[::10], ik.a[::10]):
        gamma = closure_drift(robot, q, v)
        worst = max(worst, np.abs(jac(q) @ a + gamma).max() / np.abs(gamma).max())
        h = 1e-6
        central = (jac(q + h * v) - jac(q - h * v)) / (2 * h) @ v
        fd = max(fd, np.abs(central - gamma).max() / np.abs(gamma).max())
    assert worst <= 1e-12
    assert fd <= 3e-8


def test_last_closure_residual_is_the_residual_at_the_last_state(robot):
    """Read where constraintDynamics placed the closures, it is closure_residual at that q,
    bit for bit (the loop saves a kinematics pass per tick)."""
    plant = Plant(robot, ModelMismatch(payload=0.05, mass_error=0.1))
    rng = np.random.default_rng(2)
    for _ in range(5):
        q = robot.home() + rng.normal(0.0, 0.05, robot.model.nq)
        plant.acceleration(q, rng.normal(size=robot.model.nv), rng.normal(size=6))
        assert plant.last_closure_residual() == plant.closure_residual(q)


@pytest.mark.parametrize("losses", [None, JointLosses(viscous=0.01, coulomb=0.02)])
def test_held_torque_dynamics_are_the_acceleration_bit_for_bit(robot, losses):
    """plant.held(τ) — the tree torque of a control period built once for its RK4 stages —
    gives acceleration(q, v, τ) to the bit, friction or not, and keeps the τ it was given
    (a later tick's torque does not leak into it)."""
    plant = Plant(robot, ModelMismatch(payload=0.05, mass_error=0.1, losses=losses))
    rng = np.random.default_rng(3)
    tau = rng.normal(size=6)
    f = plant.held(tau)
    other = plant.held(rng.normal(size=6))
    for _ in range(5):
        q = robot.home() + rng.normal(0.0, 0.05, robot.model.nq)
        v = rng.normal(size=robot.model.nv)
        a = f(q, v)
        np.testing.assert_array_equal(a, plant.acceleration(q, v, tau))
        assert not np.array_equal(other(q, v), a)
        np.testing.assert_array_equal(f(q, v), a)  # a copy: the next call does not move it
