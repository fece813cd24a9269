"""The front, the chosen design and the gains (synthesis/front.py), against brute force; the
reported front's ε-boxes (FrontResolution, epsilon_front) against a brute-force ε-box
dominance written here from its definition, and on a stored study's front."""
import csv
import itertools
import math
import random
from pathlib import Path

import pytest

from pollard_pin.errors import InputError
from pollard_pin.synthesis.front import (
    EXACT,
    MOTOR_USE_LIMIT,
    SENSES,
    FrontResolution,
    choose,
    dominates,
    epsilon_front,
    gains,
    non_dominated,
    rank_key,
)
from pollard_pin.synthesis.study import DesignOptions


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


# --- the ε-front ------------------------------------------------------------------------
NAMES = ("parts_per_hour", "robots", "motor_use", "kmin", "moving_mass")
SIGN = {"parts_per_hour": 1, "robots": -1, "motor_use": -1, "kmin": 1, "moving_mass": -1}
RELATIVE = {"parts_per_hour", "kmin", "moving_mass"}
FRONT_200 = Path(__file__).parents[1] / "data" / "design" / "front_200.csv"


def _stored_front():
    """The 46 exact front designs of a 200-evaluation study of examples/design, in its
    report's order (the chosen design, trial 1, first)."""
    with FRONT_200.open() as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return [{n: float(r[n]) for n in NAMES} | {"trial": int(r["trial"])} for r in rows]


def _box(o, eps):
    """Each objective's box: the figure itself at 0, else floor(x / ε) (absolute) or
    floor(ln x / ln(1 + ε)) (relative)."""
    return tuple(o[n] if not eps[n] else math.floor(
        math.log(o[n]) / math.log1p(eps[n]) if n in RELATIVE else o[n] / eps[n]) for n in NAMES)


def _better_or_equal(a, b):  # a no worse than b in every objective (a, b: boxes or figures)
    return all(SIGN[n] * x >= SIGN[n] * y for n, x, y in zip(NAMES, a, b))


def _rule(o):  # choose's rule, written out: the motor margin, robots, parts/h, mass
    return (o["motor_use"] > 0.9, o["robots"], -o["parts_per_hour"], o["moving_mass"])


def brute_force(rows, eps):
    """The ε-front by its definition: the Pareto set (the first of equal rows); every box of
    any row that no box of any row dominates keeps the Pareto row of it the rule puts first;
    and the rule's first Pareto row is kept whatever its box."""
    figs = [tuple(r[n] for n in NAMES) for r in rows]
    pareto = [i for i, a in enumerate(figs)
              if not any(_better_or_equal(b, a) and b != a for b in figs)
              and a not in figs[:i]]
    boxes = [_box(r, eps) for r in rows]
    free = {b for b in boxes if not any(_better_or_equal(c, b) and c != b for c in boxes)}
    kept = {min((i for i in pareto if boxes[i] == b), key=lambda i: (_rule(rows[i]), i))
            for b in free}
    kept.add(min(pareto, key=lambda i: (_rule(rows[i]), i)))
    return sorted(kept)


def _random_rows(rng, n):
    """Designs in tight clusters like a study's: parts/h near two levels, the motor use about
    the margin, kmin and mass over a few boxes (so that boxes hold several front rows)."""
    return [{"parts_per_hour": rng.choice([50.8, 106.0]) * rng.uniform(0.995, 1.01),
             "robots": rng.choice([2, 3]), "motor_use": rng.uniform(0.89, 0.92),
             "kmin": rng.uniform(1e4, 1.5e4), "moving_mass": rng.uniform(3.0, 3.15)}
            for _ in range(n)]


def test_resolution_is_checked_and_defaults_to_the_documented_values():
    r = FrontResolution()
    assert (r.parts_per_hour, r.motor_use, r.kmin, r.moving_mass) == (0.01, 0.01, 0.1, 0.02)
    assert DesignOptions().front == r
    for bad in (-0.01, 1.5, float("nan"), "0.01", True):
        with pytest.raises(InputError, match=r"FrontResolution.kmin = .*"):
            FrontResolution(kmin=bad)
    with pytest.raises(InputError, match="DesignOptions.front = .*expected FrontResolution"):
        DesignOptions(front={"kmin": 0.1})
    with pytest.raises(AttributeError):  # frozen
        r.kmin = 0.2


@pytest.mark.parametrize("seed", range(6))
def test_epsilon_front_is_the_brute_force_definition(seed):
    rng = random.Random(seed)
    rows = _random_rows(rng, 70)
    # an equal row, and a box mate that trades parts per hour for kmin
    rows += [dict(rows[3]), dict(rows[5], parts_per_hour=rows[5]["parts_per_hour"] * 1.0001,
                                 kmin=rows[5]["kmin"] * 0.999)]
    eps = {"parts_per_hour": rng.choice([0.005, 0.01, 0.03]), "robots": 0.0,
           "motor_use": rng.choice([0.01, 0.02]), "kmin": rng.choice([0.1, 0.3]),
           "moving_mass": rng.choice([0.02, 0.1])}
    res = FrontResolution(eps["parts_per_hour"], eps["motor_use"], eps["kmin"],
                          eps["moving_mass"])
    kept = epsilon_front(rows, res)
    assert kept == brute_force(rows, eps)
    front = non_dominated(rows)
    assert len(kept) < len(front)  # the boxes merged some
    shared = [i for i in front if sum(_box(rows[i], eps) == _box(rows[j], eps)
                                      for j in front) > 1]
    assert shared  # boxes of more than one front row: the rule picks among them
    # every row is covered: a kept design's box is no worse in every objective
    boxes = [_box(r, eps) for r in rows]
    assert all(any(_better_or_equal(boxes[k], b) for k in kept) for b in boxes)
    assert epsilon_front(rows, EXACT) == non_dominated(rows)  # ε = 0: the exact front


def test_the_chosen_design_is_kept_even_when_its_box_is_dominated():
    # b beats a's box in kmin with a's parts/h box: a's box is dominated, but the rule
    # prefers a (more parts per hour within the box)
    a = {"parts_per_hour": 50.9, "robots": 2, "motor_use": 0.95, "kmin": 1e4,
         "moving_mass": 2.0}
    b = dict(a, parts_per_hour=50.85, kmin=3e4)
    rows = [b, a]
    eps = {"parts_per_hour": 0.01, "robots": 0, "motor_use": 0.01, "kmin": 0.1,
           "moving_mass": 0.02}
    assert epsilon_front(rows, FrontResolution()) == [0, 1] == brute_force(rows, eps)
    assert _box(a, eps)[0] == _box(b, eps)[0]  # one parts/h box (394: 50.42-50.93 parts/h)
    # the rule's choice is b (more parts per hour) when a has fewer: a alone is dropped
    assert epsilon_front([dict(a, parts_per_hour=50.8), b], FrontResolution()) == [1]


def test_the_stored_study_front_keeps_its_choice_and_shrinks():
    rows = _stored_front()
    assert len(rows) == 46 and len(non_dominated(rows)) == 46
    full = sorted(rows, key=rank_key)
    chosen = full[choose(full)]["trial"]
    assert chosen == 1  # the study's choice: one robot, 51.83 parts/h
    assert epsilon_front(rows, EXACT) == list(range(46))
    eps = {"parts_per_hour": 0.01, "robots": 0.0, "motor_use": 0.01, "kmin": 0.1,
           "moving_mass": 0.02}
    kept = epsilon_front(rows, FrontResolution())
    assert kept == brute_force(rows, eps)
    assert len(kept) == 18
    shown = sorted((rows[i] for i in kept), key=rank_key)
    assert shown[choose(shown)]["trial"] == chosen
    # the eleven three-robot designs at 50.79-50.89 parts/h: one or two remain
    slow3 = [i for i, r in enumerate(rows) if r["robots"] == 3 and r["parts_per_hour"] < 51]
    assert len(slow3) == 11 and 1 <= len(set(slow3) & set(kept)) <= 2
