"""The dynamics layer: ``inverse`` (RNEA + closure forces, docs/model.md §13) and ``forward``
(constrained forward dynamics, replay, docs/model.md §14), the joint loads, control and
the closed-loop simulation, actuators and the fastest cycle; the drives as springs in
:mod:`pollard_pin.dynamics.drives`."""
from .control import (
    ComputedTorque,
    FeedforwardPD,
    Gains,
    PDGravity,
    desired_trajectory,
)
from .cycle import time_optimal_path
from .forward import SimulationError, forward_dynamics, replay_open_loop
from .inverse import inverse_dynamics
from .loads import JointLoads, joint_loads
from .motors import ActuatorError, Actuators, load_actuators
from .plant import ModelMismatch, Plant, PlantError
from .sizing import actuator_sizing
from .timeopt import TimeOptimal
from .tracking import MeasurementNoise, TrackingOptions, simulate_tracking
from .tracking_result import TrackingResult

__all__ = ["inverse_dynamics", "forward_dynamics", "replay_open_loop", "SimulationError",
           "joint_loads", "JointLoads", "desired_trajectory", "ComputedTorque", "FeedforwardPD",
           "PDGravity", "Gains", "simulate_tracking", "TrackingOptions", "MeasurementNoise",
           "TrackingResult", "Plant", "ModelMismatch", "PlantError", "load_actuators", "Actuators",
           "ActuatorError", "actuator_sizing", "time_optimal_path", "TimeOptimal"]
