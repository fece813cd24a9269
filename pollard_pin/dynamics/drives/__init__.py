"""The drives as springs (docs/model.md §27, §28): the static stiffness, deflection and modes
of compliant drives on rigid links, and the flexible-joint simulation's drives and plant."""
from .flexible import FlexibleDrives
from .stiffness import (
           StiffnessError,
           StiffnessOptions,
           StiffnessResult,
           check_linear,
           deflection_at,
           loaded_deflection,
           stiffness_at,
)

__all__ = ["stiffness_at", "deflection_at", "loaded_deflection", "check_linear",
           "StiffnessOptions", "StiffnessResult",
           "StiffnessError", "FlexibleDrives"]
