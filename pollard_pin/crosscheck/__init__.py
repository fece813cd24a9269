"""Independent formulations that check the Pinocchio pipeline: ``euler_lagrange`` (the thesis'
task-space Euler–Lagrange torques, numpy only, docs/model.md §8) and ``mujoco`` (MuJoCo peer)."""
from .compare import agreement, cross_check_mujoco, cross_check_thesis

__all__ = ["cross_check_thesis", "cross_check_mujoco", "agreement"]
