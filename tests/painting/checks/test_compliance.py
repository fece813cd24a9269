"""Compliance along a paint program (docs/model.md §27.7): the standoff error against
stiffness_at's deflection projected by hand, the recoil's bad values one line each; what it does
to the paint: the film error against a brute-force film of the deflected program (its own
deflection, rotation and integration), the film's thinning against the spot displacement's
divergence, every kind filmed as its planner does, and an actuators file without stiffness
reported, not refused."""
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import pollard_pin as pp
from pollard_pin.analytic.taskspace import rotation
from pollard_pin.dynamics.drives.stiffness import StiffnessOptions, stiffness_at
from pollard_pin.errors import PollardError
from pollard_pin.painting.checks.compliance import compliance_entry, program_deflection
from pollard_pin.painting.errors import JobError
from pollard_pin.painting.film.grid import plan_film
from pollard_pin.painting.job import job_from_dict
from pollard_pin.painting.plan.panel import plan_paint
from pollard_pin.painting.spray.deposition import gun_of, pair_rate

SMALL = {"panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.06,
                   "height": 0.04},
         "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7, "recoil": 5.0},
         "job": {"thickness": 25e-6}}


def test_standoff_error_is_the_projected_deflection(robot, plan, act):
    """examples/paint.toml with a 3 N recoil: at a few samples (both sides of a CHUNK), the
    deflection of stiffness_at under the weight and the recoil's wrench −3 a, projected by
    hand on the spray axis and across it (achieved 7e-20 m on ~1e-4 m: round-off)."""
    k = act.stiffness()
    d = program_deflection(robot, plan.trajectory, k, plan.spray, recoil=3.0)
    idx = [0, 1234, 4095, 4096, len(plan.trajectory) - 1]
    q = pp.inverse_kinematics(robot, plan.trajectory.poses[idx]).q
    for j, i in enumerate(idx):
        a = rotation(plan.trajectory.poses[i])[:, 0]
        w = StiffnessOptions(wrench=(*(-3.0 * a), 0.0, 0.0, 0.0))
        ref = stiffness_at(robot, q[j:j + 1], k, w).deflection[0]
        along = ref[:3] @ a
        assert d.standoff[i] == pytest.approx(along, abs=1e-17)
        assert d.lateral[i] == pytest.approx(np.linalg.norm(ref[:3] - along * a), abs=1e-17)
        assert d.tilt[i] == pytest.approx(np.linalg.norm(ref[3:] - (ref[3:] @ a) * a),
                                          abs=1e-17)
    # the weight alone sags the tip by tens of µm, the recoil pushes it back along the axis
    weight = program_deflection(robot, plan.trajectory, k)
    assert 1e-6 < np.abs(weight.deflection[:, :3]).max() < 1e-3
    assert np.all(d.standoff < weight.standoff)


@pytest.mark.parametrize("value, rule", [
    (-0.5, ">= 0"), (math.nan, "finite"), (1e6, "at most 100 N"), ("0.5", "a number"),
    (True, "a number")])
def test_bad_recoil_is_one_line(value, rule):
    d = {**SMALL, "gun": {**SMALL["gun"], "recoil": value}}
    with pytest.raises(JobError) as exc:
        job_from_dict(d, "bad.toml")
    msg = str(exc.value)
    assert isinstance(exc.value, PollardError) and "\n" not in msg
    assert "bad.toml" in msg and "gun.recoil" in msg and rule in msg, msg


def test_recoil_round_trips():
    job = job_from_dict(SMALL, "small.toml")
    assert job.recoil == 5.0 and job.to_dict()["gun"]["recoil"] == 5.0
    assert job_from_dict({**SMALL, "gun": {"standoff": 0.15, "sigma": 0.01, "flow": 1e-7}}
                         ).recoil is None


@pytest.mark.parametrize("recoil", [-1.0, math.nan, 1e6, True])
def test_program_deflection_refuses_a_bad_recoil(robot, act, plan, recoil):
    with pytest.raises(PollardError, match="recoil") as exc:
        program_deflection(robot, plan.trajectory, act.stiffness(), recoil=recoil)
    assert "\n" not in str(exc.value)


@pytest.fixture(scope="module")
def small(robot, act):
    """A 60 × 40 mm panel, its plan and its film on a σ grid."""
    job = job_from_dict(SMALL, "small.toml")
    plan = plan_paint(robot, job, act)
    U, V, pts, f = plan_film(plan, job.sigma)
    return job, plan, pts, f


def _brute_film(gun, t, tips, axes, pts, n):
    """∫ rate dt by the trapezoid rule, point by point over every sample (no culling)."""
    out = np.empty(len(pts))
    for j, s in enumerate(pts):
        rate = pair_rate(gun, tips, axes, np.broadcast_to(s, tips.shape),
                         np.broadcast_to(n, tips.shape))
        out[j] = np.trapezoid(rate, t)
    return out


def test_film_error_against_a_brute_force(robot, act, small):
    """The reported film error against the film of the deflected program computed apart:
    the deflection from stiffness_at with the recoil's constant wrench (the gun's axis is
    the panel's −n throughout), the pose turned by scipy's rotation vector, the film summed
    over every sample at every grid point (achieved 2.3e-13 relative: round-off of the
    films' difference)."""
    job, plan, pts, f = small
    entry = compliance_entry(robot, plan, pts, f.thickness, act)
    tr = plan.trajectory
    q = pp.inverse_kinematics(robot, tr.poses).q
    a = -np.asarray(job.normal)
    d = stiffness_at(robot, q, act.stiffness(),
                     StiffnessOptions(wrench=(*(-job.recoil * a), 0, 0, 0))).deflection
    R = Rotation.from_rotvec(d[:, 3:]).as_matrix() @ rotation(tr.poses)
    flat = pts.reshape(-1, 3)
    gun = gun_of(job)
    rigid = _brute_film(gun, tr.t, tr.poses[:, :3], rotation(tr.poses)[:, :, 0], flat,
                        plan.frame.n)
    moved = _brute_film(gun, tr.t, tr.poses[:, :3] + d[:, :3], R[:, :, 0], flat,
                        plan.frame.n)
    brute = np.abs(moved - rigid).max() / job.thickness
    assert entry["stiffness"] and entry["recoil_n"] == 5.0
    assert 1e-5 < brute < 0.1  # the recoil and the weight do move the film
    assert entry["film_error"] == pytest.approx(brute, rel=3e-11)
    assert entry["standoff_error_m"] == pytest.approx(np.abs(d[:, :3] @ a).max(), rel=1e-13)


def test_film_error_is_zero_without_deflection(robot, act, small):
    """The rigid poses give the plan's own film (equal: the same integration); near-rigid
    drives (1e9 N·m/rad) a film within 1e-6 of it."""
    from pollard_pin.painting.checks.compliance import program_film

    job, plan, pts, f = small
    assert np.array_equal(program_film(plan, pts, plan.trajectory.poses), f.thickness)
    stiff = replace(act, units=tuple(replace(u, stiffness=1e9) for u in act.units))
    entry = compliance_entry(robot, plan, pts, f.thickness, stiff)
    # achieved: film 7e-9 of the target, standoff 4.9e-10 m (the deflection scales as 1/k)
    assert entry["film_error"] < 1e-6 and entry["standoff_error_m"] < 5e-8


def test_without_stiffness_the_report_says_so(robot, act, small):
    """An actuators file without stiffness: one entry naming the missing key, no error."""
    job, plan, pts, f = small
    soft = replace(act, units=tuple(replace(u, stiffness=None) for u in act.units))
    entry = compliance_entry(robot, plan, pts, f.thickness, soft)
    assert entry["stiffness"] is False and "stiffness' is missing" in entry["note"]
    assert entry["recoil_n"] == 5.0


def test_paint_reports_it(robot, act, small):
    """pollard_pin.paint: paint.json's ``compliance`` is compliance_entry's on its plan and
    film (equal); PaintOptions(compliance=False) leaves it out."""
    from pollard_pin.painting.options import PaintOptions

    job = small[0]
    r = pp.paint(robot, job, act, PaintOptions(resolution=job.sigma))
    direct = compliance_entry(robot, r.plan, r.film.points, r.film.thickness, act)
    assert r.report.data["compliance"] == direct
    assert "compliance" in r.report.timings
    with pytest.raises(PollardError, match="PaintOptions.compliance"):
        PaintOptions(compliance="yes")


def test_cli_without_stiffness_says_so(robot, tmp_path, capsys):
    """pollard-pin paint with an actuators file without stiffness: it paints, its summary
    line and paint.json say the compliance is not computed and which key is missing; with
    --no-compliance neither says anything of it."""
    import json
    import re
    from pathlib import Path

    from pollard_pin.cli import main

    root = Path(__file__).resolve().parents[3]
    text = (root / "examples" / "actuators.toml").read_text(encoding="utf-8")
    (tmp_path / "act.toml").write_text(re.sub(r"(?m)^stiffness\s*=.*$", "", text),
                                       encoding="utf-8")
    g, p = SMALL["gun"], SMALL["panel"]
    (tmp_path / "job.toml").write_text(
        f"[panel]\ncenter = {p['center']}\nnormal = {p['normal']}\nwidth = {p['width']}\n"
        f"height = {p['height']}\n[gun]\n" + "".join(f"{k} = {v}\n" for k, v in g.items())
        + "[job]\nthickness = 25e-6\n", encoding="utf-8")
    assert main(["paint", "--job", str(tmp_path / "job.toml"), "--actuators",
                 str(tmp_path / "act.toml"), "--out", str(tmp_path / "out"),
                 "--resolution", "0.01"]) == 0
    out = capsys.readouterr().out
    rep = json.loads((tmp_path / "out" / "paint.json").read_text(encoding="utf-8"))
    assert rep["compliance"]["stiffness"] is False and rep["compliance"]["recoil_n"] == 5.0
    line = [x for x in out.splitlines() if x.startswith("compliance")]
    assert len(line) == 1 and "not computed" in line[0] and "stiffness' is missing" in line[0]
    assert main(["paint", "--job", str(tmp_path / "job.toml"), "--out", str(tmp_path / "off"),
                 "--resolution", "0.01", "--no-compliance"]) == 0
    assert "compliance" not in capsys.readouterr().out
    assert "compliance" not in (tmp_path / "off" / "paint.json").read_text(encoding="utf-8")


def test_the_film_thins_by_the_spots_divergence(robot, job, plan, film, act):
    """Paint is conserved: where the deflection stretches the raster the film thins by the
    divergence of the spot's displacement δ on the panel, ΔT/T ≈ −div δ (docs/model.md
    §27.7). examples/paint.toml under the weight: the deflected program's film over the
    interior (2σ from the edges) against −div δ, δ from the deflected axes' intersections
    with the panel, gridded and differentiated apart (achieved 3.5e-3 relative on the mean:
    the ripple and the edges are not in −div δ)."""
    from scipy.interpolate import griddata

    from pollard_pin.painting.checks.compliance import deflected_poses, program_film

    U, V, pts, f = film
    tr, fr = plan.trajectory, plan.frame
    d = program_deflection(robot, tr, act.stiffness(), plan.spray)
    moved = deflected_poses(tr.poses, d.deflection)
    T = f.thickness.reshape(len(V), len(U))
    change = program_film(plan, pts, moved).reshape(T.shape) / T - 1

    def spot(poses):  # where each sample's axis meets the panel, (u, v)
        a = rotation(poses)[:, :, 0]
        s = poses[:, :3] + (((fr.c - poses[:, :3]) @ fr.n) / (a @ fr.n))[:, None] * a - fr.c
        return np.c_[s @ fr.u, s @ fr.v]

    s0 = spot(tr.poses)
    delta = spot(moved) - s0
    near = (np.abs(s0[:, 0]) < job.width / 2 + 0.02) & (np.abs(s0[:, 1]) < job.height / 2 + 0.02)
    UU, VV = np.meshgrid(U, V)
    grid = griddata(s0[near], delta[near], (UU, VV))  # one triangulation, both components
    du, dv = grid[..., 0], grid[..., 1]
    div = np.gradient(du, U, axis=1) + np.gradient(dv, V, axis=0)
    inner = ((np.abs(UU) <= job.width / 2 - 2 * job.sigma)
             & (np.abs(VV) <= job.height / 2 - 2 * job.sigma))
    assert change[inner].mean() < -5e-4  # the weight does thin the film
    assert change[inner].mean() == pytest.approx(-div[inner].mean(), rel=0.1)


def _window(plan, n=400):
    """The plan cut to ``n`` sprayed samples from the first sprayed one (a cheap film)."""
    i = int(np.flatnonzero(plan.spray > 0)[0])
    tr = plan.trajectory
    return replace(plan, trajectory=tr.window(i, i + n), spray=plan.spray[i:i + n])


@pytest.mark.parametrize("kind", ["line panel", "part", "line part"])
def test_every_kind_films_as_its_planner(robot, act, line_plan, line_part_plan, ribbed_plan,
                                         kind):
    """A line panel, a still part (examples/parts/ribbed_plate.toml), a part on a line: the
    rigid poses give the kind's own film (equal), the deflected ones a small change."""

    from pollard_pin.painting.checks.compliance import deflected_poses, film_error, program_film
    from pollard_pin.painting.film.line import line_film
    from pollard_pin.painting.film.part import surface_film

    if kind == "part":  # examples/parts/ribbed_plate.toml
        plan = _window(ribbed_plan)
    else:
        plan = _window(line_plan if kind == "line panel" else line_part_plan)
    sigma = plan.job.sigma
    if kind == "line panel":
        pts, own = line_film(plan, sigma)[2:]
    else:
        pts, own = surface_film(plan.in_part_frame() if kind == "line part" else plan, sigma)[:2]
    assert np.array_equal(program_film(plan, pts, plan.trajectory.poses), own.thickness)
    d = program_deflection(robot, plan.trajectory, act.stiffness(), plan.spray, 5.0)
    moved = program_film(plan, pts, deflected_poses(plan.trajectory.poses, d.deflection))
    err, _ = film_error(own.thickness, moved, plan.job.thickness)
    assert 1e-6 < err < 0.05  # a 400-sample piece: its film's edges move with the gun


def test_drives_beyond_the_linear_model_are_flagged_not_refused(robot, act, small):
    """Drives so soft (1 N·m/rad) that the weight turns one beyond the linear model's bound
    (docs/model.md §27.2): the entry keeps ``stiffness`` true, gives no figures and a note
    naming the sample and the bound; the summary line prints the note; program_deflection
    alone refuses in one line."""
    from pollard_pin.dynamics.drives.stiffness import StiffnessError
    from pollard_pin.painting.summary import compliance_line

    job, plan, pts, f = small
    soft = replace(act, units=tuple(replace(u, stiffness=1.0) for u in act.units))
    entry = compliance_entry(robot, plan, pts, f.thickness, soft)
    assert entry["stiffness"] is True and entry["recoil_n"] == 5.0
    assert set(entry) == {"recoil_n", "stiffness", "note"}
    assert entry["note"].startswith("not computed: sample 0 (t = 0 s): a drive turns by ")
    assert "beyond the linear model's 0.003 rad" in entry["note"]
    assert compliance_line(entry) == f"compliance {entry['note']}"
    with pytest.raises(StiffnessError, match="beyond the linear model"):
        program_deflection(robot, plan.trajectory, soft.stiffness(), plan.spray, 5.0)
