"""JSON text for the package's files (io/json_text.py): finite numbers only, a non-finite one
refused in one line naming its key."""
import json

import numpy as np
import pytest

from pollard_pin.errors import PollardError
from pollard_pin.io.json_text import NonFiniteError, finite_json


def test_finite_values_are_json_dumps():
    value = {"a": [1.5, np.float64(2.0), {"b": None, "c": True}], "d": "x", "e": 1e308}
    assert finite_json(value, "f.json", indent=1) == json.dumps(value, indent=1)


@pytest.mark.parametrize("value, key, shown", [
    ({"a": float("inf")}, "a", "inf"),
    ({"a": [0.0, {"b": float("nan")}]}, "a[1].b", "nan"),
    ({"s": {"sag": {"max": np.float64(-np.inf)}}}, "s.sag.max", "-inf"),
    ([1.0, float("nan")], "[1]", "nan"),
    (float("inf"), "the value", "inf"),
])
def test_a_non_finite_number_is_one_line_naming_its_key(value, key, shown):
    with pytest.raises(NonFiniteError) as err:
        finite_json(value, "paint.json")
    msg = str(err.value)
    assert msg.startswith(f"paint.json: {key} = ") and shown in msg and "\n" not in msg
    assert isinstance(err.value, PollardError)
