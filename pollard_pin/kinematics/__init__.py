"""The kinematics layer (docs/model.md §7, §11, §12).

``closed_form`` (the thesis' IK with exact jet derivatives, numpy only; ``jet``, ``taskspace``)
· ``closure`` (loop closure by Newton, forward kinematics) · ``pipeline`` (constrained IK
along a trajectory, batched) · ``singularity`` (conditioning and margins) · ``errors``.
Kept import-free so that ``closed_form`` never pulls in Pinocchio."""
