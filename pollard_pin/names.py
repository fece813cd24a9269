"""The joint and body vocabulary of the Pollard robot, defined once (docs/model.md §2, §3, §6).

An import-free leaf under every layer: the numpy-only closed form, the model, the pipeline,
the peers and the writers all take their names and orders from here."""

# Tree joints in docs/model.md §3 order (IKResult.q columns, Robot.joint_names).
TREE_JOINTS = ("theta21", "theta43", "theta54", "theta1615", "theta1716", "theta1817",
               "theta21_1", "theta65_1", "theta76_1", "theta21_2", "theta65_2", "theta76_2")
# ZYZ angles of the two cut spherical joints (docs/model.md §4), leg 1 then leg 2.
SPHERICAL = ("theta98_1", "theta109_1", "theta1110_1", "theta98_2", "theta109_2", "theta1110_2")
JOINTS = TREE_JOINTS + SPHERICAL  # the closed form's 18 angles (docs/model.md §7)
ACTUATED = ("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716", "theta1817")  # §6
PASSIVE = ("theta43", "theta54", "theta65_1", "theta76_1", "theta65_2", "theta76_2")
CHAINS = ("chain 0", "leg 1", "leg 2")
# Joints drawn and reported together: base chain 0, wrist, legs (docs/model.md §3).
CHAIN_JOINTS = (("chain 0", TREE_JOINTS[0:3]), ("wrist", TREE_JOINTS[3:6]),
                ("leg 1", TREE_JOINTS[6:9]), ("leg 2", TREE_JOINTS[9:12]))
BODIES = ("arm0", "platform", "wrist1", "wrist2", "gun", "arm_1", "arm_2", "link_1", "link_2")

__all__ = ["TREE_JOINTS", "SPHERICAL", "JOINTS", "ACTUATED", "PASSIVE", "CHAINS", "CHAIN_JOINTS",
           "BODIES"]
