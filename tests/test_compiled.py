"""pollard_pin/compiled.py: the compiled loops' one loader and array form."""
import numpy as np
import pytest

from pollard_pin.compiled import extension, f64


def test_a_built_extension_loads_and_a_missing_one_is_one_line():
    assert extension("pollard_pin.kinematics._kernels").__name__ == \
        "pollard_pin.kinematics._kernels"
    assert hasattr(extension("pollard_pin.painting.spray._deposit"), "round_rate")
    with pytest.raises(ImportError) as info:
        extension("pollard_pin.painting.spray._not_built")
    said = str(info.value)
    assert "\n" not in said and "compiled kernels are missing" in said
    assert "_not_built" in said and "pip install" in said
    assert info.value.__cause__ is None and info.value.__suppress_context__


def test_f64_is_the_c_side_layout_with_the_same_values():
    a = np.arange(12, dtype=np.int32).reshape(3, 4)[:, ::2]  # strided integers
    b = f64(a)
    assert b.dtype == np.float64 and b.flags.c_contiguous
    np.testing.assert_array_equal(b, a.astype(float))
    c = np.ones((2, 3))
    assert f64(c) is c  # already the layout: no copy
    assert f64([1, 2]).tolist() == [1.0, 2.0]
