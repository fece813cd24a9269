"""--robots auto and --robots N (painting/layout/auto.py, docs/model.md §26.5): each count
planned plain, then with the levers, before the next; the refusal names each count's cause."""

from dataclasses import replace

import pytest
from cell_split_jobs import tall_panel
from refusals import WRONG, refused

from pollard_pin.painting.errors import CellError, LayoutSearchError, LineSpeedError, PlanError
from pollard_pin.painting.layout import auto
from pollard_pin.painting.layout.auto import fewest_robots

pytestmark = pytest.mark.usefixtures("bands_remembered")


def no_seating(monkeypatch):
    """No robot planned alone before a mocked paint_job (the seating: test_seat.py)."""
    from pollard_pin.painting.layout import seat

    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))


# each count's refusal as the planner words it (the three cabinet doors' case), and
# what the search's line says of it
DOOR_REFUSALS = {
    2: (CellError, "<python>: no robot reaches z -0.015…0.025 m (the part's edge 0.015 m and "
        "its run-on; the lowest band starts at 0.025 m, robot 'robot1')",
        "band", "bottom band 40 mm short of the run-on"),
    3: (PlanError, "robot 'robot1': no place on the line keeps 23 of its 46 turnarounds and "
        "its first ramp in reach (its passes each fit): move the robot or the part", "reach",
        "23 of 46 turnarounds and first ramp out of reach"),
    4: (PlanError, "<python>: no line speed paints the part: too slow at 0.03394 m/s (a motor "
        "at 126 % of its rating), too fast at 0.03413 m/s (a motor at 126 % of its rating); "
        "binding: slow (motors), fast (motors)", "motors", "motor 126 % at any speed"),
}

def test_the_search_stops_at_the_first_layout_that_paints(robot, monkeypatch):
    tried = []

    def paint_job(robot, job, actuators=None, options=None):
        tried.append(len(job.robots))
        if len(job.robots) < 3:
            raise LineSpeedError("too fast for the motors", too_fast=True)
        return "painted"

    import pollard_pin.painting.api as api

    monkeypatch.setattr(api, "paint_job", paint_job)
    no_seating(monkeypatch)
    robots, result = fewest_robots(robot, tall_panel())
    assert (tried, len(robots), result) == ([2, 3], 3, "painted")
    tried.clear()
    monkeypatch.setattr(auto, "AUTO_MORE", 0)
    with pytest.raises(LayoutSearchError, match=r"no cell of 1–2 robots paints the part at "
                                                r"0.012 m/s: 1 band \d+ mm short; 2 too fast"):
        fewest_robots(robot, tall_panel())
    assert tried == [2]


def test_the_search_refusal_says_each_counts_first_cause_in_one_line(robot, monkeypatch):
    from pollard_pin.errors import MESSAGE_ROOM

    def paint_job(robot, job, actuators=None, options=None):
        n = len(job.robots)
        raise LineSpeedError(f"cause {n}: the motors of {n} robots (figures " + "x " * 60
                             + f"); what to change {n}" + " y" * 60, too_fast=True)

    import pollard_pin.painting.api as api

    monkeypatch.setattr(api, "paint_job", paint_job)
    no_seating(monkeypatch)
    monkeypatch.setattr(auto, "AUTO_MORE", 2)
    with pytest.raises(LayoutSearchError) as err:
        fewest_robots(robot, tall_panel())
    said = str(err.value)
    assert len(said) <= MESSAGE_ROOM, said
    assert said.endswith("no cell of 1–4 robots paints the part at 0.012 m/s: 1 band 80 mm "
                         "short; 2 cause 2: the motors of 2 robots; 3 cause 3: the motors of 3 "
                         "robots; 4 cause 4: the motors of 4 robots"), said  # no figures, no fix


@pytest.fixture
def as_doors(monkeypatch):
    """paint_job refusing each count (2–4 robots tried on the tall panel) as a door's was."""
    import pollard_pin.painting.api as api

    def paint_job(robot, job, actuators=None, options=None):
        kind, said = DOOR_REFUSALS[len(job.robots)][:2]
        raise kind(said)

    monkeypatch.setattr(api, "paint_job", paint_job)
    no_seating(monkeypatch)
    monkeypatch.setattr(auto, "AUTO_MORE", 2)


def search_refused(robot, job=None) -> LayoutSearchError:
    with pytest.raises(LayoutSearchError) as err:
        fewest_robots(robot, job or tall_panel())
    return err.value


def test_the_search_refusal_names_each_count_and_its_cause(robot, as_doors):
    refusal = search_refused(robot)
    assert str(refusal) == (
        "<python>: no cell of 1–4 robots paints the part at 0.012 m/s: 1 band 80 mm short; 2 "
        "bottom band 40 mm short of the run-on; 3 23 of 46 turnarounds and first ramp out of "
        "reach; 4 motor 126 % at any speed"), str(refusal)
    # a valid job no cell paints: the solve family, a PlanError as a count's plan refusal
    # is (the CLI says it in one line, exit 2, as before)
    assert isinstance(refusal, PlanError) and not isinstance(refusal, CellError)


def test_the_search_refusal_carries_each_counts_cause(robot, as_doors):
    refusal = search_refused(robot)
    causes = refusal.causes
    assert sorted(causes) == [1, 2, 3, 4] and refusal.speed == 0.012
    assert (causes[1].binding, causes[1].said) == ("band", "band 80 mm short")
    assert "each zone needs 0.420 m along z" in causes[1].message  # the proposal's own refusal
    for n, (_, said, binding, words) in DOOR_REFUSALS.items():
        assert (causes[n].binding, causes[n].said) == (binding, words), n
        assert causes[n].message == said.removeprefix("<python>: "), n
    assert causes[3].robot == "robot1" and causes[2].robot is None


def test_the_search_refusal_says_less_to_fit_the_line(robot, as_doors):
    """A job's path long enough that the figures do not fit: each count's cause in fewer
    words, then its constraint alone (the longest first), as far as the room asks; every
    count still named."""
    from pollard_pin.errors import MESSAGE_ROOM

    for room, tail in ((160, "1 band 80 mm short; 2 bottom band 40 mm short; 3 turnarounds out "
                             "of reach; 4 motor 126 %"),
                       (100, "1 band; 2 band; 3 reach; 4 motor 126 %"),
                       (96, "1 band; 2 band; 3 reach; 4 motors")):
        job = replace(tall_panel(), source="/" + "d" * (MESSAGE_ROOM - room) + "/j.toml")
        said = str(search_refused(robot, job))
        assert said.endswith(tail) and len(said) <= MESSAGE_ROOM, (room, said)


@pytest.mark.parametrize("arg", ["actuators", "layout"])
@pytest.mark.parametrize("wrong", [v for v in WRONG if v is not None and not isinstance(v, str)],
                         ids=repr)
def test_fewest_robots_refuses_a_wrong_argument(robot, arg, wrong):
    """fewest_robots' actuators and layout (its robot, job and options: tests/outputs/
    test_result.py): one line naming the argument, before any planning."""
    kwargs = {arg: wrong}
    refused(lambda: fewest_robots(robot, tall_panel(), **kwargs), arg)


def test_the_search_shows_a_bar_only_when_asked_on_a_terminal(robot, monkeypatch, capsys):
    import sys

    import pollard_pin.painting.api as api
    from pollard_pin.painting.options import PaintOptions

    monkeypatch.setattr(api, "paint_job", lambda *args, **kwargs: "painted")
    no_seating(monkeypatch)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    fewest_robots(robot, tall_panel())  # a Python caller who did not ask: silent
    assert capsys.readouterr().err == ""
    fewest_robots(robot, tall_panel(), options=PaintOptions(progress=True))
    assert "layout search" in capsys.readouterr().err


@pytest.mark.parametrize("wrong", [0, 17, 2.5, True, float("nan"), "3", [1, 2], -1], ids=repr)
def test_a_wrong_count_is_refused_before_any_planning(robot, wrong, monkeypatch):
    """fewest_robots' count (--robots N from Python): a whole number 1..16 or None; else one
    line naming it, nothing planned."""
    import pollard_pin.painting.api as api

    monkeypatch.setattr(api, "paint_job", lambda *a, **k: pytest.fail("planned"))
    refused(lambda: fewest_robots(robot, tall_panel(), count=wrong), "count")


@pytest.mark.parametrize("count", [None, 2])
def test_a_job_with_robots_or_without_a_line_is_refused_before_any_planning(robot, count,
                                                                            monkeypatch):
    """A layout is for a job on a line without [[robot]] tables: one line saying which,
    before any count or lever is planned."""
    import pollard_pin.painting.api as api
    from pollard_pin.painting.cell.robots import CellRobot

    monkeypatch.setattr(api, "paint_job", lambda *a, **k: pytest.fail("planned"))
    placed = replace(tall_panel(), robots=(CellRobot("a"), CellRobot("b", (0.0, 1.0, 0.0))))
    with pytest.raises(CellError, match=r"already places its 2 robot\(s\)") as err:
        fewest_robots(robot, placed, count=count)
    assert "\n" not in str(err.value)
    with pytest.raises(CellError, match=r"needs the job's \[line\]"):
        fewest_robots(robot, replace(tall_panel(), line=None), count=count)
