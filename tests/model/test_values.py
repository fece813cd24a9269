"""The one home for reading input: regular files only, TOML within limits, numbers checked,
values shown short."""
from __future__ import annotations

import math
import os
import time

import pytest

from pollard_pin.errors import InputError
from pollard_pin.model.values import (
    MAX_DEPTH,
    float_text_problem,
    integer,
    loads_toml,
    number,
    open_regular,
    parse_float,
    parse_int,
    read_toml,
    shorten,
)


class Bad(InputError):
    pass


@pytest.mark.parametrize("value, shown", [
    (0.25, "0.25"), (-3, "-3"), (True, "True"), ("abc", "'abc'"),
    (10**20, "1e+20"), (-(10**20), "-1e+20"),
    (10**399, "1e+399 (a 400-digit integer)"), (-(10**399), "-1e+399 (a 400-digit integer)"),
    (int("9" * 400), "9.999e+399 (a 400-digit integer)"),
    ("x" * 100, "'" + "x" * 57 + "…'"),
    ([10**399], "[" + "1" + "0" * 56 + "…]"),
])
def test_shorten_never_echoes_a_huge_value(value, shown):
    assert shorten(value) == shown and len(shown) <= 60


def test_shorten_survives_what_repr_refuses():
    deep: list = []
    node = deep
    for _ in range(100_000):  # repr() of this raises RecursionError
        node.append([])
        node = node[0]
    assert shorten(deep) == "<list>"


def test_a_fifo_is_refused_at_once(tmp_path):
    # open() of a FIFO with no writer blocked forever
    fifo = tmp_path / "f.toml"
    os.mkfifo(fifo)
    t0 = time.perf_counter()
    with pytest.raises(OSError, match=r"not a regular file \(a FIFO\)"):
        open_regular(fifo)
    with pytest.raises(Bad, match=r"^grid file '.*f\.toml' cannot be read: not a regular file "
                                  r"\(a FIFO\)$"):
        read_toml(fifo, "grid file", Bad)
    assert time.perf_counter() - t0 < 1.0


def test_a_nul_in_a_name_is_an_oserror(tmp_path):
    with pytest.raises(OSError, match="a path with a NUL character"):
        open_regular(str(tmp_path / "a\0b"))


def test_a_nul_is_said_in_the_words_of_checks_file_path(tmp_path):
    """One rule, one wording: the reader's OSError and the path check say the same."""
    from pollard_pin.checks import file_path

    with pytest.raises(OSError) as opened:
        open_regular(str(tmp_path / "a\0b"))
    with pytest.raises(Bad) as checked:
        file_path("a\0b", "path", error=Bad)
    assert opened.value.strerror and str(checked.value).endswith(": " + opened.value.strerror)
    with pytest.raises(Bad, match=r"^grid file '.*a\\x00b' cannot be read: a path with a NUL "
                                  r"character$"):
        read_toml(str(tmp_path / "a\0b"), "grid file", Bad)


def test_shorten_is_the_checks_one():
    """shorten and clip have one home, pollard_pin.checks (below the model): model.values
    uses that one, and no module takes them from model.values (no second door)."""
    import ast
    from pathlib import Path

    from pollard_pin import checks
    from pollard_pin.model import values

    assert values.shorten is checks.shorten
    assert not {"shorten", "clip"} & set(values.__all__)
    root = Path(checks.__file__).parent
    through = [f"{p.relative_to(root)}:{node.lineno}" for p in sorted(root.rglob("*.py"))
               for node in ast.walk(ast.parse(p.read_text()))
               if isinstance(node, ast.ImportFrom) and (node.module or "").endswith("values")
               and {a.name for a in node.names} & {"shorten", "clip"}]
    assert not through, through


def test_fail_says_the_key_and_sets_it_on_the_error():
    with pytest.raises(Bad, match=r"^parameter 'a\.b\[2\]' = 1e\+400 \(a 401-digit integer\): "
                                  r"must be within the float range") as e:
        number(10**400, "a.b[2]", Bad, "parameter ")
    assert e.value.key == "a.b[2]"


def test_a_folder_and_a_missing_file(tmp_path):
    with pytest.raises(Bad, match="cannot be read: Is a directory"):
        read_toml(tmp_path, "job", Bad)
    with pytest.raises(Bad, match="does not exist"):
        read_toml(tmp_path / "nope.toml", "job", Bad)


def test_an_over_large_toml_file_is_refused(tmp_path):
    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * (1 << 20) + "\n")
    with pytest.raises(Bad) as err:
        read_toml(big, "parameter file", Bad)
    assert str(err.value) == f"parameter file '{big}' is over 1 MiB, the limit"


@pytest.mark.parametrize("text, says", [
    ("a = " + "[" * 3000 + "]" * 3000, f"nested more than {MAX_DEPTH} deep"),  # RecursionError
    ("a = " + "[" * 40 + "]" * 40, f"f.toml: 'a' nests arrays or tables more than {MAX_DEPTH} "
                                   "deep"),
    ("a = " + "1" * 5000, "an integer of more than 4300 digits"),  # ValueError in tomllib
    ("[t]\na = " + "9" * 400, "'t.a' = 9.999e+399 (a 400-digit integer): must be within the float"),
    ("a = [1, -" + "9" * 400 + "]", "'a[1]' = -9.999e+399 (a 400-digit integer)"),
    ("a = ", "is not valid TOML"),
    # a float beyond the range: tomllib reads 1e400 as inf and 1e-400 as 0, and the old
    # messages said "'a' = inf: must be a finite number" of a file that says 1e400
    ("[t]\na = 1e400", "f.toml: 't.a' = 1e400: must be within the float range (about ±1.8e308)"),
    ("a = [1.0, -2.5E+999]", "'a[1]' = -2.5E+999: must be within the float range"),
    ("a = 1e-400", "'a' = 1e-400: must be 0, or at least about 4.9e-324 in magnitude (it reads "
                   "as 0)"),
])
def test_toml_within_limits(text, says):
    with pytest.raises(Bad) as info:
        loads_toml(text, "f.toml", Bad)
    assert says in str(info.value) and len(str(info.value)) < 200, str(info.value)


def test_a_float_beyond_the_range_goes_on_shown_as_written_without_ints():
    # a --set value: the parameter's own check names the key, and shows what was typed
    v = loads_toml("v = 1e400", "override", Bad, ints=False)["v"]
    assert v == math.inf and shorten(v) == "1e400"
    assert shorten(loads_toml("v = -1e-400", "override", Bad, ints=False)["v"]) == "-1e-400"


def test_toml_limits_keep_what_a_file_needs():
    assert loads_toml("a = [[1, 2], [3, 4]]\nb = 1e300\nc = 123456789012345678901234567890",
                      "f", Bad) == {"a": [[1, 2], [3, 4]], "b": 1e300,
                                    "c": 123456789012345678901234567890}
    assert loads_toml("a = " + "9" * 400, "f", Bad, ints=False)["a"] == int("9" * 400)


@pytest.mark.parametrize("value, rules, says", [
    (True, {}, "'k' = True: must be a number"),
    ("1", {}, "'k' = '1': must be a number"),
    (math.nan, {}, "'k' = nan: must be a finite number"),
    (10**400, {}, "'k' = 1e+400 (a 401-digit integer): must be within the float range"),
    (0, {"positive": True}, "'k' = 0: must be > 0"),
    (-1e-300, {"nonnegative": True}, "'k' = -1e-300: must be >= 0"),
    (-11.0, {"limit": 10.0}, "'k' = -11.0: must be within ±10"),
    (11, {"limit": 10.0, "limit_rule": "too long"}, "'k' = 11: too long"),
])
def test_number_rules(value, rules, says):
    with pytest.raises(Bad, match="^where: " + says.replace("(", r"\(").replace(")", r"\)")
                       .replace("+", r"\+")):
        number(value, "k", Bad, "where: ", **rules)


def test_number_and_integer_pass_good_values():
    assert number(3, "k", Bad) == 3.0 and type(number(3, "k", Bad)) is float
    assert number(1e308, "k", Bad, limit=1e309) == 1e308
    assert integer(2, "k", Bad) == 2
    for bad in (0, 1.5, True, "2"):
        with pytest.raises(Bad, match="must be a whole number >= 1"):
            integer(bad, "k", Bad)


@pytest.mark.parametrize("text", ["0.5_5", "1_000", "０.５５", "１", "1e1_0", "٣"])
def test_parse_float_refuses_what_float_takes_but_no_user_means(text):
    float(text)  # Python takes it...
    with pytest.raises(ValueError):
        parse_float(text)  # ...the package does not
    assert float_text_problem(text)  # the same rule, read on a whole file's cells at once
    assert float_text_problem("1.0" + text + "2")


@pytest.mark.parametrize("text, value", [("0.55", 0.55), (" -1e-3 ", -1e-3), ("inf", math.inf),
                                         ("+.5", 0.5)])
def test_parse_float_takes_plain_numbers(text, value):
    assert parse_float(text) == value
    assert float_text_problem(text) is None


@pytest.mark.parametrize("text", ["1_1", "１１", "1" * 5000, "1.0", "", "-", "0x10"])
def test_parse_int_refuses(text):
    with pytest.raises(ValueError):
        parse_int(text)


def test_parse_int_takes_plain_integers():
    assert [parse_int(t) for t in ("11", "-3", "+2", " 7 ")] == [11, -3, 2, 7]
