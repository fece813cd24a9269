"""Design the robot for a paint job (docs/model.md §31): the design space (lengths, joint
ranges, motors from a catalogue, the number of robots), one design made concrete under the
mass model, and its evaluation: a cheap screen, then the full paint plan."""
from .catalogue import Catalogue, CatalogueError, Motor, load_catalogue
from .concrete import Design, build
from .evaluation import (
    CONSTRAINTS,
    OBJECTIVES,
    SENSES,
    DesignContext,
    Evaluation,
    baseline_values,
    design_files,
    evaluate,
    prepare,
)
from .space import DesignSpace, ScaleGroup, SpaceError, Variable, load_space, space_from_dict

__all__ = ["CONSTRAINTS", "Catalogue", "CatalogueError", "Design", "DesignContext",
           "DesignSpace", "Evaluation", "Motor", "OBJECTIVES", "SENSES", "ScaleGroup",
           "SpaceError", "Variable", "baseline_values", "build", "design_files", "evaluate",
           "load_catalogue", "load_space", "prepare", "space_from_dict"]

# The study (docs/model.md §31.5): ``pollard_pin.design(job, space, options)``.
from .api import design  # noqa: E402
from .fidelity import SearchFidelity  # noqa: E402
from .front import FrontResolution  # noqa: E402
from .result import DesignResult  # noqa: E402
from .study import DesignOptions  # noqa: E402

__all__ += ["DesignOptions", "DesignResult", "FrontResolution", "SearchFidelity", "design"]
