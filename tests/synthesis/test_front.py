"""The front, the chosen design and the gains (synthesis/front.py), against brute force."""
import itertools
import random

import pytest

from pollard_pin.errors import InputError
from pollard_pin.synthesis.front import (
    MOTOR_USE_LIMIT,
    SENSES,
    choose,
    dominates,
    gains,
    non_dominated,
    rank_key,
)


def _rows(n, seed=3):
    rng = random.Random(seed)
    return [{"parts_per_hour": rng.choice([50.0, 80.0, 120.0]), "robots": rng.choice([1, 2, 3]),
             "motor_use": rng.choice([0.5, 0.8, 0.95]), "kmin": rng.choice([1e4, 3e4]),
             "moving_mass": rng.choice([5.0, 7.0])} for _ in range(n)]


def test_dominance_by_each_sense():
    a = {"parts_per_hour": 100.0, "robots": 1, "motor_use": 0.5, "kmin": 2e4, "moving_mass": 5.0}
    assert not dominates(a, a)
    for name, sense in SENSES.items():
        better = dict(a, **{name: a[name] + sense})  # one step the right way
        assert dominates(better, a) and not dominates(a, better)


def test_non_dominated_is_the_brute_force_front():
    rows = _rows(120)
    front = non_dominated(rows)
    for i, a in enumerate(rows):  # by the definition, pair by pair
        beaten = any(all(SENSES[n] * b[n] >= SENSES[n] * a[n] for n in SENSES)
                     and any(SENSES[n] * b[n] > SENSES[n] * a[n] for n in SENSES) for b in rows)
        first_of_equals = all(rows[j] != a for j in range(i))
        assert (i in front) == (not beaten and first_of_equals), (i, a)
    assert not any(dominates(rows[i], rows[j]) for i, j in itertools.permutations(front, 2))


def test_choose_keeps_the_motor_margin_then_fewest_robots_then_most_parts():
    front = [{"parts_per_hour": 300.0, "robots": 1, "motor_use": 0.95, "kmin": 1.0,
              "moving_mass": 1.0},
             {"parts_per_hour": 100.0, "robots": 2, "motor_use": 0.5, "kmin": 1.0,
              "moving_mass": 1.0},
             {"parts_per_hour": 120.0, "robots": 2, "motor_use": 0.6, "kmin": 1.0,
              "moving_mass": 9.0},
             {"parts_per_hour": 90.0, "robots": 3, "motor_use": 0.1, "kmin": 1.0,
              "moving_mass": 0.5}]
    assert front[0]["motor_use"] > MOTOR_USE_LIMIT
    assert choose(front) == 2  # within 0.9: 2 robots, and 120 > 100 parts/h
    assert sorted(range(4), key=lambda i: rank_key(front[i])) == [2, 1, 3, 0]
    assert choose(front, pick=4) == 3
    over = [dict(r, motor_use=0.95) for r in front]  # none keeps the margin: the rule on all
    assert choose(over) == 0
    with pytest.raises(InputError, match="--pick 5: the front has 4 designs"):
        choose(front, pick=5)
    with pytest.raises(InputError, match="no feasible design"):
        choose([])


def test_gains_say_each_objective_against_the_baseline():
    base = {"parts_per_hour": 100.0, "robots": 2, "motor_use": 0.5, "kmin": 2e4,
            "moving_mass": 10.0}
    mine = {"parts_per_hour": 125.0, "robots": 1, "motor_use": 0.75, "kmin": 1e4,
            "moving_mass": 8.0}
    line = gains(mine, base)
    assert line == ("125 parts/h (+25 %), 1 robot (-1), motor use 0.75 (+0.25), "
                    "kmin 1e+04 N/m (-50 %), moving mass 8 kg (-20 %)")
    assert gains(mine, None) == ("125 parts/h, 1 robot, motor use 0.75, kmin 1e+04 N/m, "
                                 "moving mass 8 kg")
