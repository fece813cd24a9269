"""One home for curves (as toppra's ``interpolator.py``): the :class:`~pollard_pin.Trajectory`
type and its curve, the quintic splines (``paths.splines``), the analytic curves (``paths.curves``:
the thesis painting curve, docs/model.md §9) and the constant-s̈ parametrisation of a path
(``paths.const_accel``, docs/model.md §19). numpy and scipy only; io reads and writes them."""
from .const_accel import RetimedCurve
from .curves import ThesisTrajectory, smooth_random_trajectory, thesis_curve, thesis_trajectory
from .splines import QuinticHermite
from .trajectory import Trajectory, TrajectoryError, trajectory_curve

__all__ = ["Trajectory", "TrajectoryError", "trajectory_curve", "thesis_trajectory",
           "thesis_curve", "ThesisTrajectory", "smooth_random_trajectory", "QuinticHermite",
           "RetimedCurve"]
