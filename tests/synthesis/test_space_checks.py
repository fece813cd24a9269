"""The design space's checks across entries (synthesis/space_checks.py; docs/model.md §31.2),
each called alone on hand-made entries. Through a space file (a bound's ends, joint limits at
the box's corners, the home pose): test_space.py."""
from types import SimpleNamespace

import pytest

from pollard_pin.synthesis.space_checks import SpaceError, given_once, lengths_nonnegative


def scale(*keys):
    return SimpleNamespace(keys=keys)


@pytest.mark.parametrize("bounds, scales, says", [
    ({"leg1.x87": (0.3, 0.4)}, [scale("leg1.x87")],
     "S.toml: 'leg1.x87' is varied in [bounds] and in [[scale]] 1; give each key one entry"),
    ({}, [scale("chain0.x32"), scale("leg1.x43", "chain0.x32")],
     "S.toml: 'chain0.x32' is varied in [[scale]] 1 and in [[scale]] 2; give each key one "
     "entry"),
    ({}, [scale("chain0.x32", "chain0.x32")],
     "S.toml: 'chain0.x32' is varied twice in [[scale]] 1; give each key one entry"),
])
def test_a_key_varied_twice_is_named_with_both_entries(bounds, scales, says):
    with pytest.raises(SpaceError) as e:
        given_once(bounds, scales, "S.toml")
    assert str(e.value) == says
    given_once({"leg1.x87": (0.3, 0.4)}, [scale("chain0.x32", "leg1.x43")], "S.toml")  # once each


def test_only_a_length_is_refused_below_zero():
    with pytest.raises(SpaceError, match=r"^S.toml \[bounds\]: leg1.x87 = \[-0.1, …\]: a bound "
                                         r"below zero \(a length\)$"):
        lengths_nonnegative("leg1.x87", -0.1, "S.toml [bounds]")
    lengths_nonnegative("leg1.x87", 0.0, "S.toml [bounds]")  # zero is a length
    lengths_nonnegative("home.tip.z", -0.1, "S.toml [bounds]")  # a place, not a length
    lengths_nonnegative("limits.theta21.lower", -106.0, "S.toml [bounds]")  # an angle
