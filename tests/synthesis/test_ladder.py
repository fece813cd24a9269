"""The study's first generation (synthesis/ladder.py, docs/model.md §31.5): the screened ladder
finds the thin slab of one-robot designs that NSGA-II's random first generation misses, and a
resumed study does not enqueue it again."""
import hashlib
import json
from dataclasses import dataclass
from types import SimpleNamespace

import optuna
import pytest
import synthesis_stub as stub

from pollard_pin.synthesis import baseline_values, load_space
from pollard_pin.synthesis.api import design
from pollard_pin.synthesis.ladder import BACK_LEVELS, LEVELS, ladder, seeds
from pollard_pin.synthesis.study import DesignOptions

MOTORS = ("S20", "S40", "S100", "S200", "W5", "W10")


@dataclass(frozen=True)
class SlabSpace:
    """The example's variables: two length factors in [1, 1.8], two motor groups of six
    motors, a base ratio of three, the place in [0, 0.4] m, one to three robots."""

    def variables(self):
        return [stub.Variable("scale.arms", 1.0, 1.8, "float"),
                stub.Variable("scale.links", 1.0, 1.8, "float"),
                stub.Variable("motor.base", 0, 5, "categorical", MOTORS),
                stub.Variable("ratio.base", 0, 2, "categorical", (50.0, 100.0, 160.0)),
                stub.Variable("motor.wrist", 0, 5, "categorical", MOTORS),
                stub.Variable("place.back", 0.0, 0.4, "float"),
                stub.Variable("robots", 1, 3, "int")]

    def fingerprint(self):
        return hashlib.sha256(json.dumps("slab").encode()).hexdigest()[:16]


BASE = {"scale.arms": 1.0, "scale.links": 1.0, "motor.base": 0, "ratio.base": 1,
        "motor.wrist": 4, "place.back": 0.0, "robots": 2}


def _in_slab(v) -> bool:
    """One robot paints the part alone only here (as the door: both factors near 1.7, the
    S100 base motor, about 0.3 m back): a share of about 8e-5 of the space."""
    return (abs(v["scale.arms"] - 1.7) < 0.03 and abs(v["scale.links"] - 1.7) < 0.03
            and v["motor.base"] == 2 and abs(v["place.back"] - 0.3) < 0.05)


def _evaluate(values, ctx, level="screen"):
    ctx["calls"].append(level)
    n = values["robots"]
    reach = -0.1 if n >= 2 or _in_slab(values) else 0.1  # two robots always reach
    mass = n * (1.0 + values["scale.arms"] + values["scale.links"])
    objectives = {"parts_per_hour": 50.0, "robots": float(n), "motor_use": 0.5, "kmin": 7e3,
                  "moving_mass": mass}
    return stub.Evaluation(level, reach <= 0, objectives, {"reach": reach},
                           None if reach <= 0 else "reach", {"robots_needed": 1 if reach <= 0
                                                             else 2})


def _evaluator(calls):
    return SimpleNamespace(OBJECTIVES=stub.OBJECTIVES, evaluate=_evaluate,
                           prepare=lambda job, space, search=None: {"calls": calls},
                           baseline_values=lambda space, ctx=None: dict(BASE))


def _run(ladder_on, trials=16, calls=None, **options):
    calls = [] if calls is None else calls
    return design(stub.StubJob(), SlabSpace(),
                  DesignOptions(trials=trials, workers=1, population=8, ladder=ladder_on,
                                **options), evaluator=_evaluator(calls)), calls


def test_the_ladder_walks_the_length_factors_together():
    designs = ladder(SlabSpace().variables(), BASE)
    assert len(designs) == LEVELS * BACK_LEVELS * (1 + 5 + 5)  # thesis motors, then one group
    assert all(d["scale.arms"] == d["scale.links"] and d["robots"] == 1 for d in designs)
    assert sum(map(_in_slab, designs)) == 1  # ×1.7, S100, 0.3 m back: one rung of it
    assert len({json.dumps(d, sort_keys=True) for d in designs}) == len(designs)


def test_the_examples_ladder_holds_the_one_robot_design():
    """The door's hand-picked design (every length ×1.7, the S100 base motors, 0.3 m back) is
    a rung of the example's ladder."""
    space = load_space("examples/design/space.toml")
    designs = ladder(space.variables(), baseline_values(space))
    s100 = space.catalogue.names.index("S100")
    assert [d for d in designs if d["scale.arms"] == d["scale.links"] == pytest.approx(1.7)
            and d["motor.base"] == s100 and d["place.back"] == pytest.approx(0.3)]


def test_seeds_take_the_fewest_robots_and_spread_over_the_motors():
    def ev(robots, mass):
        return SimpleNamespace(objectives={"robots": robots, "moving_mass": mass,
                                           "motor_use": 0.5})
    a, b = {"motor.base": 0}, {"motor.base": 1}
    passed = [({**a, "x": 1}, ev(2, 1.0)), ({**a, "x": 2}, ev(1, 3.0)),
              ({**a, "x": 3}, ev(1, 2.0)), ({**b, "x": 4}, ev(1, 2.5)), ({**b, "x": 5}, ev(2, 0.5))]
    assert [v["x"] for v in seeds(passed, 5)] == [3, 4, 2, 5, 1]
    assert [v["x"] for v in seeds(passed, 2)] == [3, 4]


def test_the_ladder_finds_the_one_robot_design_the_random_start_misses():
    """16 evaluations: the ladder's first generation holds the slab's design; NSGA-II from a
    random start (~8e-5 of the space: some 12,000 evaluations on average) finds only two
    robots."""
    plain, _ = _run(False)
    assert min(d["objectives"]["robots"] for d in plain.front) == 2
    laddered, calls = _run(True)
    best = laddered.front[laddered.chosen]
    assert best["objectives"]["robots"] == 1 and _in_slab(best["values"])
    assert best["trial"] < 8  # the first generation: the thesis robot, then the seeds
    assert laddered.baseline["values"] == BASE  # the thesis robot stays the first design
    # the ladder's thesis robot (every factor 1, at the origin: two robots) is not a seed: the
    # first generation's designs are distinct
    first = [tuple(r[k] for k in BASE) for r in laddered.trials if r["trial"] < 8]
    assert len(first) == 8 == len(set(first))


def test_a_resumed_study_does_not_enqueue_the_ladder_again(tmp_path):
    path = tmp_path / "study.db"

    def stop(done, total, feasible, best):
        if done >= 3:
            raise KeyboardInterrupt

    calls: list = []
    with pytest.raises(KeyboardInterrupt):
        design(stub.StubJob(), SlabSpace(),
               DesignOptions(trials=12, workers=1, population=8, study=path),
               evaluator=_evaluator(calls), progress=stop)
    screened = calls.count("screen")
    assert screened >= len(ladder(SlabSpace().variables(), BASE))
    result, again = _run(True, trials=12, study=path, resume=True)
    assert again.count("screen") == 0  # no ladder screened again
    study = optuna.load_study(study_name="pollard-pin design", storage=f"sqlite:///{path}")
    first = [t for t in study.get_trials() if "fixed_params" in t.system_attrs]
    assert len(first) == 8  # the thesis robot and 7 seeds, enqueued once
    assert len(result.trials) == 12
    assert not [t for t in study.get_trials() if t.state == optuna.trial.TrialState.WAITING]
    assert not list(tmp_path.glob("study.db-*"))  # closed: no -wal or -shm beside it
