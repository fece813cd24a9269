"""A still panel's raster before the motors (paint/plan/layout.py, docs/model.md §21): the
film per coat is the target's share, the passes are the spacing apart and cover the panel, a
spacing too wide names the job entry it came from, and the budgets stop a job before its path
is built."""
import math
from dataclasses import replace

import numpy as np
import pytest

from pollard_pin.painting.errors import BudgetError, PlanError
from pollard_pin.painting.film.grid import film_grid
from pollard_pin.painting.passes.raster import SPOT_RADIUS
from pollard_pin.painting.plan.layout import panel_layout, spot_too_fine
from pollard_pin.painting.plan.panel import plan_paint
from pollard_pin.painting.policy import PlannerPolicy
from pollard_pin.painting.spray.deposition import film, gun_of
from pollard_pin.painting.spray.spots import BetaSpot, EllipticGaussian


@pytest.mark.parametrize("coats", [1, 3])
def test_the_layout_splits_the_film_over_its_coats(job, coats):
    """Film per coat = flow/(speed·spacing) (docs/model.md §21), coats of it make the target
    (to 1e-15 relative: it achieves 2e-16); the passes are centred, ``spacing`` apart and
    reach the panel's edges; the passes run the panel's length plus the spot radius."""
    j = replace(job, coats=coats)
    lay = panel_layout(j)
    assert lay.coats == coats
    film = j.flow / (lay.speed * lay.spacing) * coats
    assert film == pytest.approx(j.thickness, rel=1e-13)
    gaps = lay.offsets[1:] - lay.offsets[:-1]
    assert gaps == pytest.approx(lay.spacing, rel=1e-13)
    assert lay.offsets.sum() == pytest.approx(0.0, abs=1e-15)
    length, extent = (j.width, j.height) if j.direction == "horizontal" else (j.height, j.width)
    assert lay.offsets[-1] - lay.offsets[0] >= extent - 2 * lay.spacing
    assert lay.half_length == pytest.approx(length / 2 + SPOT_RADIUS * j.sigma, rel=1e-15)


def test_too_wide_a_spacing(robot, job, act):
    with pytest.raises(PlanError, match=r"job\.spacing: spacing 0\.04 m is too wide"):
        plan_paint(robot, replace(job, spacing=0.04), act)
    # A speed that implies too wide a spacing names the speed (flow/(thickness·speed) = 0.2 m).
    with pytest.raises(PlanError, match=r"job\.speed: spacing 0\.2 m is too wide"):
        plan_paint(robot, replace(job, speed=job.flow / (job.thickness * 0.2)), act)


@pytest.mark.parametrize("change, says", [
    ({"thickness": 0.1}, "the path needs 1.57e+07 samples"),  # 7.6 GB of samples, then more
    ({"flow": 1e-300}, "samples"),  # overflowed the sample count
    ({"flow": 5e-324}, "the path needs inf samples"),  # a speed that underflows
    ({"thickness": 0.1, "speed": 0.001, "coats": 3}, "fewer coats or a faster gun"),
    ({"spacing": 1e-5}, "passes"),
    ({"coats": 10**9}, "passes"),
])
def test_budgets_are_checked_before_the_path_is_built(robot, act, job, change, says):
    with pytest.raises(BudgetError) as err:  # the budget's words: refused before building
        plan_paint(robot, replace(job, **change), act)
    msg = str(err.value)
    assert says in msg and "budget" in msg and "\n" not in msg and len(msg) < 250, msg


def _needs(msg: str) -> float:
    return float(msg.split("needs ")[1].split(" samples")[0])


def test_the_budget_advises_what_takes_fewer_samples(robot, act, job):
    """Where the step is step_sigma·σ of gun travel the gun's speed cancels out (samples ≈ path
    length / (step_sigma·σ)): four times the flow (a gun 4× faster) leaves the count within
    1.5× (the turnarounds aside), so the refusal says a wider spray, not more flow; where the
    step is max_step, four times the flow takes about 4× fewer and it says so."""
    fine = PlannerPolicy(step_sigma=1e-4, max_path_samples=1000)
    counts = []
    for flow in (job.flow, 4 * job.flow):
        with pytest.raises(BudgetError) as err:
            plan_paint(robot, replace(job, flow=flow), act, fine)
        msg = str(err.value)
        assert "a wider spray (gun.sigma)" in msg and "flow" not in msg, msg
        assert "policy.max_path_samples" in msg and len(msg) <= 250, msg
        counts.append(_needs(msg))
    assert counts[0] / counts[1] < 1.5, counts
    coarse = PlannerPolicy(max_path_samples=1000)
    counts = []
    for flow in (job.flow, 4 * job.flow):
        with pytest.raises(BudgetError) as err:
            plan_paint(robot, replace(job, flow=flow, thickness=0.1), act, coarse)
        msg = str(err.value)
        assert "a thinner film, more flow" in msg and "gun.sigma" not in msg, msg
        counts.append(_needs(msg))
    assert counts[0] / counts[1] > 3.0, counts


SPOTS = {"gaussian": None, "elliptic": EllipticGaussian(0.014, 0.006),
         "beta": BetaSpot(0.025, 2.5)}


@pytest.mark.parametrize("name, direction", [
    ("gaussian", "horizontal"), ("elliptic", "horizontal"), ("elliptic", "vertical"),
    ("beta", "horizontal")])
def test_each_spot_paints_the_panel_within_the_band(job, name, direction):
    """The example panel with each spray model, its passes at the spacing rule's spacing
    (the spot's own ripple, across its strokes: an elliptic spot's long axis lies across
    horizontal passes, along vertical ones), the gun on straight passes at the layout's
    speed over the layout's length (the turnarounds, beyond the spot's 4σ, left out): the
    film on the panel's grid (σ/2) is the target within the layout's 1 % cross profile plus
    the passes' ends (achieved 0.50–0.81 %, the β spot's time integral adding ~3e-4),
    asserted 1.1 %: far inside the acceptance band (99 % of the area within ±10 %). The
    elliptic spot's vertical passes are 0.78 σ_long = 1.815 σ_short apart."""
    spot = SPOTS[name]
    j = replace(job, direction=direction, spot=spot,
                sigma=job.sigma if spot is None else spot.width)
    lay = panel_layout(j)
    horizontal = direction == "horizontal"
    ep, es = (lay.frame.u, lay.frame.v) if horizontal else (lay.frame.v, lay.frame.u)
    gun = gun_of(j)
    step = j.sigma / 4
    U = np.arange(-lay.half_length, lay.half_length + step / 2, step)
    t, p = [], []
    for k, off in enumerate(lay.offsets):
        u = U if k % 2 == 0 else U[::-1]
        t.append(k * 10.0 + (u - u[0]) * (1 if k % 2 == 0 else -1) / lay.speed)
        p.append(lay.frame.c + j.standoff * lay.frame.n + u[:, None] * ep + off * es)
    U_, V_, pts = film_grid(lay.frame, j, resolution=j.sigma / 2)
    total = np.zeros(pts.shape[0] * pts.shape[1])
    for tk, pk in zip(t, p):  # one pass at a time: the gun is off between them
        R = np.tile(lay.frame.rotation, (len(tk), 1, 1))
        total += film(gun, tk, pk, R, pts.reshape(-1, 3), lay.frame.n,
                      origin=lay.frame.c).thickness
    rel = total / j.thickness - 1
    assert np.abs(rel).max() < 0.011
    if name == "elliptic":
        short = direction == "vertical"
        assert lay.spacing == pytest.approx(1.8151 * (0.006 if short else 0.014), rel=1e-4)


def test_a_beta_spot_runs_on_no_further_than_its_footprint(job):
    """The β spot deposits nothing beyond R (docs/model.md §20), so its passes run on R past
    the panel's edges, not the Gaussian rule's 4σ (at β = 1.5, 4σ = 1.79 R: the calibrated
    gun's ramps once left the workspace 0.64 m past the edge); a Gaussian keeps 4σ."""
    spot = BetaSpot(0.06, 1.5)
    j = replace(job, width=0.19, height=0.09, standoff=0.2, flow=4.05e-7, spot=spot,
                sigma=spot.width)
    lay = panel_layout(j)
    assert SPOT_RADIUS * j.sigma > 1.7 * 0.06
    assert lay.half_length == pytest.approx(0.19 / 2 + 0.06, rel=1e-15)
    # β = 12: 4σ = 4R/√26 < R, the Gaussian-like rule binds
    wide = BetaSpot(0.06, 12.0)
    lay = panel_layout(replace(j, spot=wide, sigma=wide.width))
    assert lay.half_length == pytest.approx(0.19 / 2 + 4 * 0.06 / math.sqrt(26), rel=1e-12)


def test_a_gun_too_slow_for_a_steep_beta_spot_says_the_spot_is_why(job):
    """At β = 1.5 the ripple rule needs passes 9.2 mm apart (a 120 mm-wide spot; the
    Gaussian of its width: 48.7 mm), so the target's gun speed is 1.76 m/s: the refusal
    names the spot and the spacing the motors would allow with its ripple (brute force
    below); a Gaussian job is left to the general refusal."""
    spot = BetaSpot(0.06, 1.5)
    j = replace(job, width=0.19, height=0.09, standoff=0.2, flow=4.05e-7, spot=spot,
                sigma=spot.width)
    lay = panel_layout(j)
    assert lay.spacing == pytest.approx(9.195e-3, rel=1e-3)
    msg = spot_too_fine(j, lay.speed, lay.spacing, 1.701)
    assert msg.startswith("the beta spot (beta 1.5) needs passes 9.195 mm apart for ±0.5 %")
    assert len("pollard-pin paint: error: " + msg) <= 250
    wider = lay.spacing * lay.speed / 1.701
    assert f"job.spacing {wider * 1e3:.4g} mm" in msg
    y = np.linspace(0.0, wider, 401)[:, None] - wider * np.arange(-10, 11)[None, :]
    brute = np.abs(wider * ((1 - (y / 0.06) ** 2).clip(0) / (0.06 * 4 / 3)).sum(1) - 1).max()
    assert f"(ripple ±{brute * 100:.2g} %)" in msg
    # ramps out of reach at that speed: the spot is named as their cause too
    msg = spot_too_fine(j, lay.speed, lay.spacing)
    assert msg.startswith("the beta spot (beta 1.5) needs passes 9.195 mm apart")
    assert msg.endswith(f"so {lay.speed:.4g} m/s: a lower flow or job.spacing up to "
                        "13.24 mm (±1 %)")
    gauss = panel_layout(job)
    assert spot_too_fine(job, gauss.speed, gauss.spacing, 0.1) is None
    assert spot_too_fine(job, gauss.speed, gauss.spacing) is None
    oval = EllipticGaussian(0.03, 0.01)  # a Gaussian's stripe: its spacing is the rule's
    je = replace(j, spot=oval, sigma=oval.width)
    assert spot_too_fine(je, 1.0, panel_layout(je).spacing) is None
    four = BetaSpot(0.06, 4.0)  # 28.4 mm, finer than the Gaussian of its width (34.4 mm)
    j4 = replace(j, spot=four, sigma=four.width)
    assert "needs passes 28.42 mm apart" in spot_too_fine(j4, 1.0, panel_layout(j4).spacing)
