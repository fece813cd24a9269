"""--robots auto's levers (painting/layout/levers.py, docs/model.md §26.5): tried only once
the plain proposal is refused, each left at its default set by its rule, said in the report."""
from dataclasses import dataclass, replace

import pytest
from cell_split_jobs import plate_part, tall_panel

from pollard_pin.painting.cell.bands import job_strokes
from pollard_pin.painting.errors import LayoutSearchError, PlanError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.layout import cell as cell_layout
from pollard_pin.painting.layout import seat
from pollard_pin.painting.layout.cell import LayoutOptions, fewest_robots
from pollard_pin.painting.layout.levers import END_PITCH, Levers, levers_for
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.passes.surface import pass_spacing
from pollard_pin.painting.policy import PlannerPolicy


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


def test_auto_tries_the_levers_only_once_refused_plain(robot, plate, monkeypatch):
    """A plain search refused at every count is tried again with the levers (the counts
    again, fewest first); the plan found says them and the plain refusal in its report; a
    search refused both ways says so, with the plain causes."""
    import pollard_pin.painting.api as api

    job, strokes = plate
    tried = []

    def paint_job(robot, job, actuators=None, options=None):
        p = options.policy
        tried.append((len(job.robots), p.seam_run, job.robots[-1].rotation))
        if p.seam_run is None:
            raise PlanError(f"robot 'robot{len(job.robots)}': no place on the line keeps its "
                            "first ramp in reach (its passes each fit)")
        return Painted(Report({"cycle_time": 1.0}), options)

    monkeypatch.setattr(api, "paint_job", paint_job)
    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))
    monkeypatch.setattr(cell_layout, "AUTO_MORE", 0)  # the fewest count only: cheap
    robots, painted = fewest_robots(robot, job)
    turned = (0.0, END_PITCH, 0.0)
    assert tried == [(2, None, (0.0, 0.0, 0.0)), (2, 0.005, turned)]
    levers = levers_for(job, strokes, PlannerPolicy(), LayoutOptions())
    said = painted.report.data["levers"]
    assert said == {**levers.as_dict(), "plain": "no cell of 1–2 robots paints the part at "
                    "0.012 m/s: 1 band 70 mm short; 2 first ramp out of reach"}, said
    assert painted.report.data["cycle_time"] == 1.0 and len(robots) == 2
    assert painted.options.policy == PlannerPolicy(seam_run=0.005, smoothing=levers.smoothing)
    # a user's lever kept; refused both ways: the plain causes, said tried with the levers
    tried.clear()
    monkeypatch.setattr(api, "paint_job", lambda robot, job, actuators=None, options=None: (
        tried.append(options.policy), paint_job(robot, job, actuators, replace(
            options, policy=replace(options.policy, seam_run=None))))[1])
    with pytest.raises(LayoutSearchError) as err:
        fewest_robots(robot, job, options=PaintOptions(policy=PlannerPolicy(seam_run=0.01)))
    assert str(err.value).endswith(said["plain"].replace(" m/s:", " m/s (its levers too):"))
    kept = PlannerPolicy(seam_run=0.01, smoothing=levers.smoothing)
    assert tried[::2] == [PlannerPolicy(seam_run=0.01), kept]
