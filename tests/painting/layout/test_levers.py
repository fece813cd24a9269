"""--robots auto's levers (painting/layout/levers.py, docs/model.md §26.5): tried only once
the plain proposal is refused, each left at its default set by its rule, said in the report."""
from dataclasses import dataclass, replace

import pytest
from cell_split_jobs import plate_part, tall_panel

from pollard_pin.painting.cell.bands import job_strokes
from pollard_pin.painting.errors import CellError, LayoutSearchError, PlanError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.layout import auto, seat
from pollard_pin.painting.layout.auto import fewest_robots
from pollard_pin.painting.layout.cell import LayoutOptions
from pollard_pin.painting.layout.levers import END_PITCH, Levers, levers_for
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.passes.surface import pass_spacing
from pollard_pin.painting.policy import PlannerPolicy

pytestmark = pytest.mark.usefixtures("bands_remembered")  # one band per robot, once

@pytest.fixture(scope="module")
def plate(tmp_path_factory):
    """A flat plate part (cheap strokes) and its strokes along the cell's axis."""
    from pollard_pin.painting.spray.occlusion import load_painted_part

    job = load_job(plate_part(tmp_path_factory.mktemp("plate")))
    return job, job_strokes(job, load_painted_part(job))


def test_the_levers_rules(plate):
    """Each lever at its default set by its rule, against the job's own numbers: the run
    past a seam one 5 mm grid step, the averaging ±3σ, the room the first ramp's run
    v·τ₀/2 = 2v²/a (v = flow/(thickness·spacing)) up to the mm, the top robot −5°; one set
    is kept."""
    job, strokes = plate
    policy = PlannerPolicy()
    v = job.flow / (job.thickness * pass_spacing(job))
    found = levers_for(job, strokes, policy, LayoutOptions())
    assert found == Levers(0.005, pytest.approx(6 * job.sigma, abs=1e-12),
                           pytest.approx(2 * v * v / policy.first_deceleration, abs=1e-3),
                           END_PITCH)
    assert 0 <= found.edge_room - 2 * v * v / policy.first_deceleration < 1e-3
    assert round(found.edge_room * 1e3, 9) % 1 == 0  # whole mm
    assert 0.1 < v < 1.0 and found.edge_room > 0.005  # a spray pass's speed, a ramp's run
    mine = levers_for(job, strokes, PlannerPolicy(seam_run=0.01, smoothing=0.05),
                      LayoutOptions(end_pitch=3.0))
    assert mine == Levers(edge_room=found.edge_room)
    assert mine.flags() == f"--edge-room {found.edge_room:.4g}"
    assert levers_for(job, strokes, PlannerPolicy(seam_run=0.0, smoothing=0.05),
                      LayoutOptions(edge_room=0.01, end_pitch=3.0)) is None  # all given
    panel = tall_panel()
    assert levers_for(panel, job_strokes(panel), policy, LayoutOptions()) is None  # flat
    slip = replace(job, flow=job.flow * 1e6)  # a pass at hundreds of km/s: refused plain
    assert levers_for(slip, strokes, policy, LayoutOptions()) is None


@dataclass(frozen=True)
class Report:
    data: dict


@dataclass(frozen=True)
class Painted:
    report: Report
    options: object


RAMP = "no place on the line keeps its first ramp in reach (its passes each fit)"
TURNS = "no place on the line keeps 23 of its 46 turnarounds in reach (its passes each fit)"


def refusing(tried, plain=RAMP, levered=TURNS, paints=()):
    """paint_job refusing the plain proposal (``plain``) and the levered one (``levered``)
    at every count but ``paints``, each try noted (count, seam run, top robot's rotation)."""
    def paint_job(robot, job, actuators=None, options=None):
        n, p = len(job.robots), options.policy
        tried.append((n, p.seam_run, job.robots[-1].rotation))
        if p.seam_run is None or n not in paints:
            raise PlanError(f"robot 'robot{n}': " + (plain if p.seam_run is None else levered))
        return Painted(Report({"cycle_time": 1.0}), options)
    return paint_job


def test_each_count_is_tried_with_the_levers_before_the_next(robot, plate, monkeypatch):
    """A count refused plain is tried with the levers before the next count (its levers
    painting it: fewer robots than a larger plain cell); the plan found says them and the
    plain refusal of the counts tried in its report; refused both ways at every count, the
    line says each count's plain cause and the levers' beside it."""
    import pollard_pin.painting.api as api

    job, strokes = plate
    tried = []
    monkeypatch.setattr(api, "paint_job", refusing(tried, paints=(3,)))
    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))
    monkeypatch.setattr(auto, "AUTO_MORE", 1)  # counts 2 and 3: cheap
    robots, painted = fewest_robots(robot, job)
    flat, turned = (0.0, 0.0, 0.0), (0.0, END_PITCH, 0.0)
    assert tried == [(2, None, flat), (2, 0.005, turned), (3, None, flat), (3, 0.005, turned)]
    levers = levers_for(job, strokes, PlannerPolicy(), LayoutOptions())
    said = painted.report.data["levers"]
    assert said == {**levers.as_dict(), "plain": "no cell of 1–3 robots paints the part at "
                    "0.012 m/s: 1 band 70 mm short; 2 first ramp out of reach; 3 first ramp "
                    "out of reach"}, said
    assert painted.report.data["cycle_time"] == 1.0 and len(robots) == 3
    assert painted.options.policy == PlannerPolicy(seam_run=0.005, smoothing=levers.smoothing)
    # refused both ways: each count's plain cause, the levers' beside it
    tried.clear()
    monkeypatch.setattr(api, "paint_job", refusing(tried))
    with pytest.raises(LayoutSearchError) as err:
        fewest_robots(robot, replace(job, source="j.toml"))
    assert str(err.value) == (  # each count's causes in fewer words: the line's room
        "j.toml: no cell of 1–3 robots paints the part at 0.012 m/s (its levers too): "
        "1 band 70 mm short; 2 ramp out of reach (levers: turnarounds out of reach); 3 ramp "
        "out of reach (levers: turnarounds out of reach)")
    assert sorted(err.value.levered) == [2, 3] and len(tried) == 4
    assert err.value.levered[2].said == "23 of 46 turnarounds out of reach"
    assert err.value.causes[3].said == "first ramp out of reach"
    # a user's lever kept, the others set by rule
    policies = []
    monkeypatch.setattr(api, "paint_job", lambda robot, job, actuators=None, options=None: (
        policies.append(options.policy), refusing(tried)(robot, job, actuators, replace(
            options, policy=replace(options.policy, seam_run=None))))[1])
    with pytest.raises(LayoutSearchError):
        fewest_robots(robot, job, options=PaintOptions(policy=PlannerPolicy(seam_run=0.01)))
    kept = PlannerPolicy(seam_run=0.01, smoothing=levers.smoothing)
    assert policies == [PlannerPolicy(seam_run=0.01), kept] * 2


@pytest.mark.parametrize("high, levered", [(0.0059, False), (0.0061, True)])
def test_a_count_far_too_fast_for_the_line_is_not_tried_with_the_levers(
        robot, plate, monkeypatch, high, levered):
    """A count whose plan paints only at speeds the job's 0.012 m/s is over twice the top of
    (SPEED_PAST) is not planned again with the levers; just under twice, it is."""
    import pollard_pin.painting.api as api

    job, _ = plate
    assert job.line.speed == 0.012 and auto.SPEED_PAST == 2.0
    tried = []
    fast = (f"at line speed 0.012 m/s the program drifts out of reach; it paints at "
            f"0.0015–{high} m/s (--max-line-speed)")
    monkeypatch.setattr(api, "paint_job", refusing(tried, plain=fast))
    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))
    monkeypatch.setattr(auto, "AUTO_MORE", 0)
    with pytest.raises(LayoutSearchError) as err:
        fewest_robots(robot, job)
    assert [t[1] for t in tried] == [None, 0.005] if levered else [None]
    assert err.value.causes[2].speeds == (0.0015, high)
    assert ("(its levers too)" in str(err.value)) == levered


def test_a_given_count_is_tried_with_the_levers_too(robot, plate, monkeypatch):
    """--robots N: N planned plain, then with the levers (the plan found says them and the
    plain refusal); refused both ways, the plain refusal with the levers' cause; N robots'
    bands too narrow for the zones: the proposal's refusal, nothing planned."""
    import pollard_pin.painting.api as api

    job, _ = plate
    tried = []
    monkeypatch.setattr(api, "paint_job", refusing(tried, paints=(2,)))
    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))
    robots, painted = fewest_robots(robot, job, count=2)
    assert [t[:2] for t in tried] == [(2, None), (2, 0.005)] and len(robots) == 2
    assert painted.report.data["levers"]["plain"] == f"robot 'robot2': {RAMP}"
    tried.clear()
    monkeypatch.setattr(api, "paint_job", refusing(tried, paints=()))
    with pytest.raises(PlanError) as err:
        fewest_robots(robot, job, count=3)
    assert str(err.value).startswith(f"robot 'robot3': {RAMP}; with its levers (--seam-run "
                                     "0.005 ")
    assert str(err.value).endswith("): 23 of 46 turnarounds out of reach")
    assert [t[:2] for t in tried] == [(3, None), (3, 0.005)]
    tried.clear()
    with pytest.raises(CellError, match="each zone needs"):
        fewest_robots(robot, job, count=1)
    assert tried == []
