"""The thesis' Euler–Lagrange dynamics (crosscheck/euler_lagrange.py) against its own
definitions: the Coriolis term from finite differences of the mass matrix, a symmetric positive
definite mass matrix, the power balance d(K + U)/dt, static torques as the potential's
gradient, and the ill-posed three-actuator problem. (Against Pinocchio: tests/dynamics/
test_inverse.py.)"""
import numpy as np
import pytest
from thesis_curves import T_PROBE, TRAJECTORIES, painting_trajectory, sinusoid_trajectory

from pollard_pin.analytic.closed_form import actuation_jacobian
from pollard_pin.crosscheck.euler_lagrange import (
    energy,
    gravity_torques,
    inverse_dynamics,
    mass_matrix,
    three_actuator_analysis,
)
from pollard_pin.model.params import load_params


@pytest.fixture(scope="module")
def p():
    return load_params()


def test_coriolis_term_is_the_lagrangian_one(p):
    # V q̇ == Ḋ q̇ − ½ ∂(q̇ᵀ D q̇)/∂q, with D differentiated by central differences.
    _, x, xd, xdd = sinusoid_trajectory(p, t=T_PROBE[:4])
    Vqd = inverse_dynamics(p, x, xd, xdd)["Vqd"]
    h = 1e-6
    Ddot = (mass_matrix(p, x + h * xd) - mass_matrix(p, x - h * xd)) / (2 * h)
    grad = np.empty_like(xd)
    for k in range(6):
        e = np.zeros(6)
        e[k] = h
        dD = (mass_matrix(p, x + e) - mass_matrix(p, x - e)) / (2 * h)
        grad[:, k] = np.einsum("ni,nij,nj->n", xd, dD, xd)
    want = np.einsum("nij,nj->ni", Ddot, xd) - 0.5 * grad
    assert np.abs(Vqd - want).max() <= 2e-9 * (1 + np.abs(want).max())  # achieves 1.6e-11
    assert np.abs(want).max() > 1e-3  # the check is not vacuous


def test_mass_matrix_is_symmetric_positive_definite(p):
    D = mass_matrix(p, painting_trajectory(p, n=51)[1])
    assert np.abs(D - np.swapaxes(D, 1, 2)).max() < 1e-15
    assert np.linalg.eigvalsh(D).min() > 0


@pytest.mark.parametrize("traj", TRAJECTORIES)
def test_power_balance(p, traj):
    # τ · (actuator rates) = Q · q̇ = d(K + U)/dt; central-difference error must shrink as h².
    _, x, xd, xdd = traj(p, t=T_PROBE)
    r = inverse_dynamics(p, x, xd, xdd)
    power = np.einsum("ni,ni->n", r["tau"], r["qd_act"])
    # Achieves 4.4e-16 W.
    assert np.allclose(power, np.einsum("ni,ni->n", r["Q"], xd), rtol=1e-13, atol=1e-14)
    errs = []
    for h in (1e-2, 1e-3):
        Ep = sum(energy(p, *traj(p, t=T_PROBE + h)[1:3]))
        Em = sum(energy(p, *traj(p, t=T_PROBE - h)[1:3]))
        errs.append(np.abs((Ep - Em) / (2 * h) - power).max() / np.abs(power).max())
    # Second order: h ten times smaller, error 100 times smaller (achieves 99.994).
    assert errs[1] < 1e-5 and errs[0] / errs[1] == pytest.approx(100.0, rel=5e-3)


def test_static_torques_balance_potential_gradient(p):
    _, x, _, _ = sinusoid_trajectory(p, t=T_PROBE[:3])
    zero = np.zeros_like(x)
    tau = inverse_dynamics(p, x, zero, zero)["tau"]
    assert np.allclose(gravity_torques(p, x), tau, rtol=1e-12, atol=1e-14)
    h = 1e-6
    gradU = np.empty_like(x)
    for k in range(6):
        e = np.zeros(6)
        e[k] = h
        gradU[:, k] = (energy(p, x + e, zero)[1] - energy(p, x - e, zero)[1]) / (2 * h)
    want = np.linalg.solve(np.swapaxes(actuation_jacobian(p, x), 1, 2), gradU[..., None])[..., 0]
    assert np.abs(tau - want).max() <= 5e-8 * np.abs(want).max()  # achieves 2.4e-10 × peak
    # The base motor holds −0.5862 N·m here; the check above makes it the potential's gradient.
    assert tau[0, 0] == pytest.approx(-0.5862011555, abs=1e-9)


def test_three_actuator_problem_is_ill_posed(p):
    _, x, xd, xdd = painting_trajectory(p, n=101)
    a = three_actuator_analysis(p, x, xd, xdd)
    J3 = actuation_jacobian(p, x)[:, :3]
    # The residual is orthogonal to what base torques can produce, and is not zero.
    assert np.abs(np.einsum("nij,nj->ni", J3, a["residual"])).max() < 1e-12
    assert a["summary"]["rank_J3"] == 3
    assert a["summary"]["max_rel_residual"] > 1e-3
