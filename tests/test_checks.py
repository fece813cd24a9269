"""The shared value rule (pollard_pin/checks.py): bounds, equality, non-numbers, the caller's
error family."""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from pollard_pin.checks import (
    EXAMPLE_ADDRESS,
    address_problem,
    callback,
    file_path,
    float_array,
    instance,
    integer,
    is_integer,
    is_real,
    problem,
    real,
    scheduler_address,
    shorten,
)
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


@pytest.mark.parametrize("value, says", [
    (10**400, "must be a finite number"),  # beyond a float: not numpy's OverflowError
    (10**5000, "must be a finite number"),  # beyond repr's digit limit too
    ("x" * 1000, "is not a number"),
], ids=["1e400", "1e5000", "long string"])
def test_real_refuses_the_huge_in_one_short_line(value, says):
    with pytest.raises(InputError, match=f"^m = .*: {says}$") as got:
        real(value, "m")
    assert len(str(got.value)) < 100


def test_real_speaks_through_the_callers_family():
    class Mine(InputError):
        pass

    with pytest.raises(Mine, match=r"^w = -1: must be >= 0 \(a margin\)$"):
        real(-1, "w", 0.0, why=" (a margin)", error=Mine)
    assert real(3, "w", 0.0) == 3.0 and isinstance(real(3, "w"), float)


def test_instance_names_the_argument_and_the_type():
    assert instance(2, "n", int, "an int") == 2 and instance(None, "n", int, "", none=True) is None
    with pytest.raises(InputError) as exc:
        instance("x" * 500, "count", int, "a whole number")
    msg = str(exc.value)
    assert msg.startswith("count = 'xxx") and msg.endswith("expected a whole number, got str")
    assert len(msg) < 120  # the value shown short
    with pytest.raises(InputError, match="n = None: expected an int, got NoneType"):
        instance(None, "n", int, "an int")


class Refused(Exception):
    pass


@pytest.mark.parametrize("value, says", [
    (None, "got NoneType"), (3, "got int"), (float("nan"), "got float"), (b"x", "got bytes"),
    ("", "an empty path"), ("a\0b", "a NUL character"), ([1], "got list")])
def test_file_path_refuses_what_names_no_file(value, says):
    with pytest.raises(Refused) as exc:
        file_path(value, "path", error=Refused)
    assert str(exc.value).startswith("path = ") and says in str(exc.value)


def test_file_path_takes_a_str_or_a_path():
    assert file_path("a/b.toml", "p") == Path("a/b.toml") == file_path(Path("a/b.toml"), "p")


@pytest.mark.parametrize("value, says", [
    ("abc", "got <U3 values"),
    ([[1.0, 2.0], [3.0]], "expected an array of real numbers"),  # ragged
    ([10**400, 0.0], "expected an array of real numbers"),  # beyond a float
    ([object()], "expected an array of real numbers"),
    ([1 + 2j], "got complex128 values"),
    ([True, False], "got bool values"),
])
def test_float_array_refuses_what_is_not_real_numbers(value, says):
    with pytest.raises(InputError, match="^poses = .*" + re.escape(says)) as got:
        float_array(value, "poses")
    assert "\n" not in str(got.value) and len(str(got.value)) <= 250


def test_float_array_takes_numbers_as_floats():
    np = pytest.importorskip("numpy")
    out = float_array([[1, 2], [3, 4.5]], "x")
    assert out.dtype == np.float64 and out.tolist() == [[1.0, 2.0], [3.0, 4.5]]
    assert float_array(np.array([7], dtype=object), "x").tolist() == [7.0]


def test_is_real_says_what_real_would_refuse_without_raising():
    assert is_real(0.5, 0.0, 1.0) and is_real(3, 0.0, above=True)
    assert is_real(0.0, 0.0) and not is_real(0.0, 0.0, above=True)
    for value in ("0.5", True, None, 1j, math.nan, math.inf, 10**400, -(10**400), [1.0]):
        assert not is_real(value), value  # 10**400: math.isfinite would raise OverflowError


@pytest.mark.parametrize("value, low, high, says", [
    (2, 2, None, None), (1, 2, None, "must be >= 2"),       # at and beside the low bound
    (16, 1, 16, None), (17, 1, 16, "must be at most 16"),   # ... and the high one
    (2.0, 1, None, "is not an integer"), (True, 0, None, "is not an integer"),
    ("3", 1, None, "is not an integer"), (None, 1, None, "is not an integer"),
])
def test_integer_at_and_beside_its_bounds(value, low, high, says):
    """The count rule PlannerPolicy, DesignOptions, the TOML readers and the CLI's counts
    share: is_integer agrees with integer, which names the value and the bound."""
    assert is_integer(value, low, high) == (says is None)
    if says is None:
        assert integer(value, "n", low, high) == value and type(integer(value, "n", low)) is int
    else:
        with pytest.raises(InputError, match=f"^n = {re.escape(repr(value))}: {says}$"):
            integer(value, "n", low, high)


def test_integer_takes_numpys_as_ints():
    np = pytest.importorskip("numpy")
    assert type(integer(np.int64(5), "n", 1)) is int
    assert is_integer(np.uint32(7), 0, 7) and not is_integer(np.float64(7.0), 0)


def test_callback_takes_a_function_or_none_only():
    assert callback(None, "progress") is None and callback(print, "progress") is print
    with pytest.raises(InputError, match=r"^progress = 'x': expected a function or None, got str$"):
        callback("x", "progress")


def test_every_refusal_shows_its_value_by_shorten():
    """One rule for a value shown short (it was two: a repr cut to 60 here, shorten in the
    model): a huge integer as its leading digits and its length, a long text cut with '…'."""
    with pytest.raises(InputError, match=r"^flag = 1e\+400 \(a 401-digit integer\): expected "
                                         r"True or False, got int$"):
        instance(10**400, "flag", bool, "True or False")
    with pytest.raises(InputError) as got:
        real("x" * 1000, "m")
    assert str(got.value) == f"m = {shorten('x' * 1000)}: is not a number"
    assert shorten("x" * 1000) == "'" + "x" * 57 + "…'"


@pytest.mark.parametrize("text, says", [
    ("", "an empty scheduler address"), (" \t", "an empty scheduler address"),
    ("localhost", "not a scheduler address: 'localhost' (missing port number"),
    ("tcp://127.0.0.1:99999", "not a scheduler address: 'tcp://127.0.0.1:99999' (port 99999 "
                              "is not in 1..65535)"),
])
def test_address_problem_is_the_one_rule_of_a_scheduler_address(text, says):
    if text.strip():
        pytest.importorskip("distributed")
    assert address_problem(text).startswith(says)


def test_scheduler_address_takes_what_dask_takes_and_names_the_rest():
    pytest.importorskip("distributed")
    for value in (None, "tcp://127.0.0.1:8786", " localhost:8786 ", "inproc://x"):
        assert scheduler_address(value, "dask") == value  # as given: the connection strips
    assert address_problem(EXAMPLE_ADDRESS) is None
    with pytest.raises(Refused, match=r"^dask: an empty scheduler address; e\.g\. "
                                      r"tcp://127\.0\.0\.1:8786, or None to run locally$"):
        scheduler_address(" ", "dask", error=Refused)
    with pytest.raises(Refused, match=r"^dask = b'x': expected a scheduler address \(str\), a "
                                      r"distributed\.Client or None, got bytes$"):
        scheduler_address(b"x", "dask", error=Refused)
