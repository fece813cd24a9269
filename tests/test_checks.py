"""The shared value rule (pollard_pin/checks.py): bounds, equality, non-numbers, the caller's
error family."""
from __future__ import annotations

import math

import pytest

from pollard_pin.checks import problem, real
from pollard_pin.errors import InputError


@pytest.mark.parametrize("x, low, high, above, expected", [
    (0.0, 0.0, math.inf, False, None),             # equality with a closed bound passes
    (0.0, 0.0, math.inf, True, "must be > 0"),     # ... and fails an open one
    (math.nextafter(0.0, -1), 0.0, math.inf, False, "must be >= 0"),
    (1.0, 0.0, 1.0, False, None),
    (math.nextafter(1.0, 2), 0.0, 1.0, False, "must be at most 1"),
    (math.nan, -math.inf, math.inf, False, "must be a finite number"),
    (math.inf, -math.inf, math.inf, False, "must be a finite number"),
])
def test_problem_at_and_beside_the_bounds(x, low, high, above, expected):
    assert problem(x, low, high, above) == expected


@pytest.mark.parametrize("value", ["0.5", b"1", True, None, [1.0], object()])
def test_real_refuses_what_is_not_a_number(value):
    with pytest.raises(InputError, match=r"^m = .*: is not a number$"):
        real(value, "m")


def test_real_speaks_through_the_callers_family():
    class Mine(InputError):
        pass

    with pytest.raises(Mine, match=r"^w = -1: must be >= 0 \(a margin\)$"):
        real(-1, "w", 0.0, why=" (a margin)", error=Mine)
    assert real(3, "w", 0.0) == 3.0 and isinstance(real(3, "w"), float)
