"""The model with every joint limit one full turn, for the workspace tests (package scope)."""
import pytest

import pollard_pin as pp
from pollard_pin.model.params import load_params
from pollard_pin.names import TREE_JOINTS


@pytest.fixture(scope="package")
def wide():
    """The shipped model with every joint limit one full turn: only reach and the margins
    bound the workspace (``run`` does not check joint limits)."""
    ov = {f"limits.{j}.{k}": v for j in TREE_JOINTS for k, v in (("lower", -180.0),
                                                                 ("upper", 180.0))}
    return pp.load(load_params(overrides=ov))
