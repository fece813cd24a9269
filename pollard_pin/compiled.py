"""The one way the package loads its compiled loops (``csrc/``, built into extension modules
when the package is installed: :mod:`.kinematics.kernels`, :mod:`.painting.spray.kernel`)
and the one array form their C side reads. Nothing compiles at run time; a source tree used
without installing it gets one line saying so."""
from __future__ import annotations

import importlib

import numpy as np


def extension(name: str):
    """The compiled module ``name`` (e.g. ``"pollard_pin.kinematics._kernels"``), or an
    ImportError saying in one line how to build it."""
    try:
        return importlib.import_module(name)
    except ImportError as exc:  # a source tree used without installing it
        raise ImportError(f"pollard_pin's compiled kernels are missing ({exc}); install the "
                          "package (`pip install .` or `pip install -e .`, which needs a C "
                          "compiler) instead of importing it from the source tree") from None


def f64(x) -> np.ndarray:
    """``x`` as a C-contiguous float64 array (what the C side's buffers are; no copy when it
    already is one)."""
    return np.ascontiguousarray(x, dtype=np.float64)


__all__ = ["extension", "f64"]
