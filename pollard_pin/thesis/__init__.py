"""The thesis' own analytic method (spec §7, §8), numpy only: closed-form IK with exact
jet derivatives and the Euler–Lagrange dynamics in task coordinates. Never imports pinocchio."""
from .ik import (ACTUATED, JOINTS, TREE_JOINTS, UnreachableError, WristSingularError,
                 actuation_jacobian, body_kinematics, closure_points, forward_frames,
                 forward_tool_pose, inverse_kinematics, position_ik)
from .lagrange import (energy, gravity_torques, inverse_dynamics, mass_matrix,
                       three_actuator_analysis)

__all__ = ["ACTUATED", "JOINTS", "TREE_JOINTS", "UnreachableError", "WristSingularError",
           "actuation_jacobian", "body_kinematics", "closure_points", "forward_frames",
           "forward_tool_pose", "inverse_kinematics", "position_ik", "energy", "gravity_torques",
           "inverse_dynamics", "mass_matrix", "three_actuator_analysis"]
