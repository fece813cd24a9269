"""The model layer: parameters (TOML), the URDF/SRDF generator and the Pinocchio model with its
two cut spherical joints (docs/model.md §3–§5). The modules: ``params``, ``urdf``,
``build``; the names users call, below."""
from .build import (
    ACTUATED,
    PASSIVE,
    ModelFileError,
    Robot,
    constraint_jacobian,
    constraint_residual,
    load,
)
from .params import ParameterError, Params, load_params

__all__ = ["load", "Robot", "ACTUATED", "PASSIVE", "constraint_residual", "constraint_jacobian",
           "ModelFileError", "load_params", "Params", "ParameterError"]
