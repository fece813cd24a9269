"""Independent formulations that check the Pinocchio pipeline: ``euler_lagrange`` (the thesis'
task-space Euler–Lagrange torques, numpy only, docs/model.md §8) and ``mujoco`` (MuJoCo peer)."""
