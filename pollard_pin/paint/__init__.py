"""Paint planning: the job file, the spray deposition model, the raster planner, the motion
checks and the film (docs/model.md §20–24).

The package is callable: ``pollard_pin.paint(robot, job, actuators, options)`` is
:func:`pollard_pin.paint.api.paint` (one name for the subpackage and its entry point, since
importing any ``pollard_pin.paint.*`` module binds ``pollard_pin.paint`` to this package).
"""
import sys
import types


class _CallablePackage(types.ModuleType):
    def __call__(self, robot, job, actuators=None, options=None):
        """Plan, film and report a paint job: :func:`pollard_pin.paint.api.paint`."""
        from .api import paint

        return paint(robot, job, actuators, options)


sys.modules[__name__].__class__ = _CallablePackage
