"""A paint program's time-optimal cycle that keeps its film (dynamics/passes.py).

The program: the shipped example's (examples/paint.toml, planned by ``paint``), with the gun
switched off in its turnarounds (where the tip is 2σ beyond the panel's edges), so that it has
gun-off stretches to retime; the spray column is the program's trigger, as ``paint`` writes it.
The kept stretches are compared row by row with the source file; the retimed ones are replayed
between their rows by the definition the file's metadata states (tests/retime_replay.py),
along the source path rebuilt by scipy's Bernstein polynomials through its rows (not the
package's spline), with the pipeline's inverse dynamics."""
import contextlib
import io
from dataclasses import replace

import numpy as np
import pytest
from cli_run import check_refusal
from motor_model import EXAMPLE
from retime_replay import read_retimed, replay
from scipy.interpolate import BPoly

from pollard_pin.cli import main
from pollard_pin.dynamics import passes, sizing
from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.dynamics.passes import spray_stretches, time_optimal_program
from pollard_pin.io.retime import retimed_trajectory
from pollard_pin.io.trajectory import from_csv, to_csv
from pollard_pin.paths.trajectory import Trajectory

EDGE = 0.13 + 2 * 0.010  # m: the example panel's half width (y) and 2σ


@pytest.fixture(scope="module")
def planned_csv(panel_painted):
    """path.csv of `paint --job examples/paint.toml`, painted once per session
    (tests/examples_planned.py)."""
    return panel_painted / "path.csv"


@pytest.fixture(scope="module")
def turns_off(planned_csv, tmp_path_factory):
    src = from_csv(planned_csv)  # with its d_*, dd_* columns: no spline, no warning
    path = tmp_path_factory.mktemp("turns") / "turns_off.csv"
    to_csv(replace(src, spray=np.where(np.abs(src.poses[:, 1]) > EDGE, 0.0, 1.0)), path)
    return path


@pytest.fixture(scope="module")
def size_retime(turns_off, tmp_path_factory):
    """``size --retime`` of the program, run once per module: (exit code, stderr, the retimed
    file, the report, and the :class:`~pollard_pin.dynamics.sizing.Sizing` the command
    computed, recorded on its way: the library's ``time_optimal_program`` of the program)."""
    folder = tmp_path_factory.mktemp("size")
    out, report, seen = folder / "rt.csv", folder / "r.md", []
    real = sizing.actuator_sizing

    def recorded(*args, **kwargs):
        seen.append(real(*args, **kwargs))
        return seen[-1]

    stdout, stderr = io.StringIO(), io.StringIO()
    with pytest.MonkeyPatch.context() as mp, contextlib.redirect_stdout(stdout), \
            contextlib.redirect_stderr(stderr):
        mp.setattr(sizing, "actuator_sizing", recorded)
        code = main([str(a) for a in ("size", "--trajectory", turns_off, "--quiet",
                                      "--actuators", EXAMPLE, "--retime", out, "--out",
                                      report)])
    check_refusal(stderr.getvalue())
    return code, stderr.getvalue(), out, report, seen


@pytest.fixture(scope="module")
def solved(turns_off, size_retime):
    """The program, and its ``time_optimal_program`` (timing, film summary): what ``size``
    computed of it (the same call: actuator_sizing of a spraying trajectory)."""
    sized = size_retime[-1]
    assert len(sized) == 1 and sized[0].timing is not None
    return from_csv(turns_off), sized[0].timing, sized[0].report["time_optimal_film"]


def _tiny(spray, poses=None):
    n = len(spray)
    t = 0.01 * np.arange(n)
    poses = np.column_stack([t, *np.zeros((5, n))]) if poses is None else poses
    d = np.gradient(poses, t, axis=0)
    return Trajectory(t, poses, d, np.gradient(d, t, axis=0), spray=np.asarray(spray, float))


def test_stretches_split_where_the_gun_switches():
    # intervals (0,0) (0,1) (1,1) (1,0) (0,0) (0,0) (0,.5) (.5,0): off, on×3, off×2, on×2
    got = spray_stretches(_tiny([0, 0, 1, 1, 0, 0, 0, 0.5, 0]))
    assert got == [(0, 2, False), (1, 5, True), (4, 7, False), (6, 9, True)]
    assert spray_stretches(_tiny([1] * 5)) == [(0, 5, True)]
    assert spray_stretches(_tiny([0] * 5)) == [(0, 5, False)]


def test_a_path_that_waits_keeps_everything_up_to_its_last_pass():
    """A conveyor's wait times the passes to the part: the gun-off stretches before the last
    pass keep their timing; only what follows it may be retimed."""
    x = np.concatenate([np.zeros(4), 0.01 * np.arange(1, 9)])  # 4 samples standing, then on
    poses = np.column_stack([x, *np.zeros((5, len(x)))])
    traj = _tiny([0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, 0], poses)
    traj = replace(traj, d_poses=np.where(np.arange(12)[:, None] < 4, 0.0, traj.d_poses),
                   dd_poses=np.where(np.arange(12)[:, None] < 4, 0.0, traj.dd_poses))
    assert passes.waits(traj) and not passes.waits(_tiny([0] * 5))
    assert spray_stretches(traj) == [(0, 11, True), (10, 12, False)]


def test_the_passes_keep_their_rows_their_times_and_the_gun_speed(solved):
    """Every row with the gun on, and every row next to one, is the source's own (poses,
    rates, accelerations, spray: exact) at the same time from the stretch's start (seen
    5.6e-17 s), so the film the program paints is the planned one; the cycle is shorter."""
    traj, timing, summary = solved
    out = retimed_trajectory(traj, timing)
    stretches = spray_stretches(traj)
    assert [p.planned is not None for p in timing.parts] == [on for _, _, on in stretches]
    assert summary["gun_off_retimed"] == summary["gun_off_stretches"] == 10
    row, worst = 0, 0.0
    for (a, b, on), part in zip(stretches, timing.parts):
        n = b - a if on else len(part.t)
        if on:
            for key in ("poses", "d_poses", "dd_poses", "spray"):
                assert np.array_equal(getattr(out, key)[row:row + n], getattr(traj, key)[a:b])
            worst = max(worst, np.abs((out.t[row:row + n] - out.t[row])
                                      - (traj.t[a:b] - traj.t[a])).max())
            speed = np.linalg.norm(out.d_poses[row:row + n, :3], axis=1)
            assert np.array_equal(speed, np.linalg.norm(traj.d_poses[a:b, :3], axis=1))
        else:
            assert not np.any(out.spray[row:row + n])
        row += n - 1
    assert row == len(out.t) - 1 and worst < 1e-12
    # the gun-on rows, all of them, once each
    assert np.count_nonzero(out.spray) == np.count_nonzero(traj.spray)
    planned = traj.t[-1] - traj.t[0]
    assert timing.duration == pytest.approx(out.t[-1] - out.t[0], abs=1e-12)
    assert timing.duration < planned - 0.3  # seen 9.498 s against 10.014 s


def test_the_gun_off_stretches_join_the_passes_c1(solved):
    """Each retimed stretch starts and ends at the source's rows with the source's rates
    there (TOPP-RA between those path rates): seen 5.6e-17 m/s between passes, 4e-10 where
    the path ends at rest (the chord spline's rates there)."""
    traj, timing, _ = solved
    for (a, b, on), part in zip(spray_stretches(traj), timing.parts):
        if on:
            continue
        piece = retimed_trajectory(traj.window(a, b), part)
        assert np.abs(piece.poses[[0, -1]] - traj.poses[[a, b - 1]]).max() < 1e-13
        assert np.abs(piece.d_poses[[0, -1]] - traj.d_poses[[a, b - 1]]).max() < 1e-7
        assert part.duration < traj.t[b - 1] - traj.t[a]  # seen 0.146 s against 0.204 s


def _source_curve(traj):
    """The source path between its rows: the quintic through each row's pose, rate and
    acceleration (scipy's Bernstein form, independent of the package's spline)."""
    poly = BPoly.from_derivatives(traj.t, np.stack([traj.poses, traj.d_poses, traj.dd_poses],
                                                   axis=1))
    d1, d2 = poly.derivative(1), poly.derivative(2)
    return lambda u: (poly(u), d1(u), d2(u))


def test_the_retimed_file_keeps_the_film_and_replays_within_the_ratings(
        robot, turns_off, size_retime):
    """``size --retime``: the file's spray column equals the source's on the kept stretches,
    and its gun-off stretches, replayed densely between their rows by the stated definition,
    use at most the ratings (seen 1.00013)."""
    code, err, out, report_path, _ = size_retime
    assert code == 0, err
    cols, meta = read_retimed(out)
    src = from_csv(turns_off)
    curve = _source_curve(src)
    worst, kinds = 0.0, []
    for seg in meta["segments"]:
        a, b = seg["rows"]
        kinds.append(seg["path_parameter"])
        if seg["path_parameter"] == "planned":
            i, j = np.searchsorted(src.t, [seg["source_start"], seg["source_end"]])
            assert np.array_equal(cols["spray"][a:b + 1], src.spray[i:j + 1])
            assert np.array_equal(cols["x"][a:b + 1], src.poses[i:j + 1, 0])
            continue
        use = replay(robot, {k: v[a:b + 1] for k, v in cols.items()}, seg, curve, 20001)
        worst = max(worst, use.max())
    assert kinds == ["arc_length", "planned"] * 9 + ["arc_length"]
    assert 0.99 <= worst <= 1.002, worst
    report = report_path.read_text()
    assert "the passes (gun on) as planned" in report
    assert "it changes the painting speed, so the film" in report  # the uniform scaling


def test_a_stretch_whose_ends_cannot_be_held_is_kept_as_planned(robot, turns_off, tmp_path):
    """Motors with 22 % of the example's peak torque cannot take the gun from rest to the
    first pass's speed over the approach: that stretch keeps its planned timing (and breaks
    the ratings, seen 4.4×, which the cycle's worst use says), the summary says so once, the
    other nine are retimed."""
    text = EXAMPLE.read_text().replace("peak_torque = 0.05", "peak_torque = 0.011")
    (tmp_path / "weak.toml").write_text(text.replace("continuous_torque = 0.02",
                                                     "continuous_torque = 0.0099"))
    traj = from_csv(turns_off)
    timing, summary = time_optimal_program(robot, load_actuators(tmp_path / "weak.toml"), traj)
    assert summary["gun_off_as_planned"] == 1 and summary["gun_off_retimed"] == 9
    assert summary["as_planned_because"].startswith("t = 0…0.082 s")
    assert summary["summary"].count("kept as planned") == 1
    (_, _, on), (_, b, _) = spray_stretches(traj)[:2]
    kept = timing.parts[0]  # the approach and the first pass: one part, as planned
    assert not on and kept.planned is not None
    assert kept.duration == pytest.approx(traj.t[b - 1] - traj.t[0], abs=1e-12)
    assert timing.between > 2.0
    out = retimed_trajectory(traj, timing)
    assert np.array_equal(out.poses[:b], traj.poses[:b])
    assert np.count_nonzero(out.spray) == np.count_nonzero(traj.spray)


def test_short_gun_off_stretches_and_those_beyond_the_longest_keep_their_plan(
        robot, turns_off, monkeypatch):
    """A gap of 5 samples in a pass is too short to retime; with room for the 2 longest
    gun-off stretches only, the others keep their plan, joined with the passes around them
    into one part each, every row the source's, and the saving is exactly those two's."""
    traj = from_csv(turns_off)
    spray = traj.spray.copy()
    spray[300:305] = 0.0  # inside the first pass
    traj = replace(traj, spray=spray)
    monkeypatch.setattr(passes, "MAX_RETIMED", 2)
    timing, summary = time_optimal_program(robot, load_actuators(EXAMPLE), traj)
    stretches = spray_stretches(traj)
    off = [(a, b) for a, b, on in stretches if not on]
    assert len(off) == 11 and (300, 305) in off  # samples 300…304: 4 intervals
    assert summary["gun_off_retimed"] == 2 and summary["gun_off_as_planned"] == 9
    assert "9 kept as planned: shorter than 16 samples or beyond the 2 longest" in \
        summary["summary"]
    longest = sorted(off, key=lambda ab: traj.t[ab[1] - 1] - traj.t[ab[0]])[-2:]
    retimed = [p for p in timing.parts if p.planned is None]
    assert len(retimed) == 2 and len(timing.parts) == 5
    saved = sum(traj.t[b - 1] - traj.t[a] for a, b in longest) - sum(p.duration
                                                                       for p in retimed)
    planned = traj.t[-1] - traj.t[0]
    assert timing.duration == pytest.approx(planned - saved, abs=1e-9)
    out = retimed_trajectory(traj, timing)
    a, b = longest[0] if longest[0][0] < longest[1][0] else longest[1]
    assert np.array_equal(out.poses[:a + 1], traj.poses[:a + 1])  # all kept up to the first
    assert np.array_equal(out.spray[:a + 1], traj.spray[:a + 1])
