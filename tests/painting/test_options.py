"""PaintOptions (painting/options.py): checked once, each refusal one line naming the field
and its value."""
import re

import pytest

from pollard_pin.errors import InputError
from pollard_pin.painting.options import PaintOptions


@pytest.mark.parametrize(("field", "value", "says"), [
    ("resolution", -1e-3, "-0.001"), ("resolution", float("nan"), "nan"),
    ("max_line_speed", 1, "True or False"), ("speed_resolution", 1.0, "(0, 1)"),
    ("speeds", "yes", "True or False"),
    # an integer beyond a float: the same line, its value shown short (not OverflowError)
    ("resolution", 10**400, "1e+400 (a 401-digit integer): expected a spacing"),
    ("speeds", 10**400, "1e+400 (a 401-digit integer): expected True or False"),
], ids=lambda v: v if isinstance(v, str) else None)
def test_options_are_checked_once(field, value, says):
    with pytest.raises(InputError, match=re.escape(f"PaintOptions.{field} = ")) as info:
        PaintOptions(**{field: value})
    assert says in str(info.value)
