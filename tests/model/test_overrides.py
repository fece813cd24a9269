"""Dotted-key overrides of the parameter dictionary (model/overrides.py): a key reaches one
value or one component, the rest of the dictionary is untouched, the new value keeps the old
one's shape, and a KEY=VALUE text reads as TOML; every slip is one ParameterError naming the
key."""
import copy

import numpy as np
import pytest

from pollard_pin.model.overrides import (
    ParameterError,
    apply_overrides,
    lookup,
    parse_assignment,
    plain_value,
)
from pollard_pin.model.params import load_params, read_params_dict


def test_an_override_changes_its_value_and_nothing_else():
    base = read_params_dict()
    kept = copy.deepcopy(base)
    out = apply_overrides(base, {"chain0.x32": 0.34, "home.tip[2]": 0.2,
                                 "bodies.gun.inertia[1][1]": np.float64(90.0)})
    assert base == kept  # a copy: the input is not touched
    expected = copy.deepcopy(base)  # the same edits written out by hand
    expected["chain0"]["x32"] = 0.34
    expected["home"]["tip"][2] = 0.2
    expected["bodies"]["gun"]["inertia"][1][1] = 90.0
    assert out == expected
    assert type(out["bodies"]["gun"]["inertia"][1][1]) is float  # numpy scalars made plain
    assert lookup(out, "home.tip[2]") == 0.2 and lookup(out, "bodies.gun.mass") == \
        base["bodies"]["gun"]["mass"]
    assert plain_value((np.int64(1), np.array([2.0]))) == [1, [2.0]]


@pytest.mark.parametrize("over, key, rule", [
    ({"chain0.foo": 1}, "chain0.foo", "override names no parameter (unknown key)"),
    ({"chain1.x32": 1}, "chain1.x32", "override names no parameter (unknown section)"),
    ({"bodies.gun.com": [0.03, 0]}, "bodies.gun.com", "must be a list of 3 numbers"),
    ({"bodies.gun.inertia": [[1, 0, 0], [0, 1, 0]]}, "bodies.gun.inertia",
     "must be a 3x3 matrix"),
    ({"chain0": 1}, "chain0", "names a section, not a parameter"),
    ({"home.tip[3]": 0.1}, "home.tip[3]", "index [3] is out of range"),
    ({"chain0.x32[0]": 0.1}, "chain0.x32[0]", "index [0] is out of range"),
])
def test_override_rules(over, key, rule):
    with pytest.raises(ParameterError) as ei:
        load_params(overrides=over)
    msg = str(ei.value)
    assert msg.startswith(f"parameter '{key}'"), msg
    assert rule in msg, msg
    assert "\n" not in msg


def test_an_assignment_reads_as_toml():
    assert parse_assignment(" chain0.x32 = 0.35") == ("chain0.x32", 0.35)
    assert parse_assignment("home.tip=[0.5, 0, 0.2]") == ("home.tip", [0.5, 0, 0.2])
    for text, words in [("chain0.x32", "expected KEY=VALUE"), ("=1", "expected KEY=VALUE"),
                        ("chain0.x32=1_000", "'_' digit separators"),
                        ("chain0.x32=0.3\nchain0.z10=1", "control character"),
                        ("chain0.x32=abc", "not a number or a list of numbers")]:
        with pytest.raises(ParameterError, match=words):
            parse_assignment(text)
