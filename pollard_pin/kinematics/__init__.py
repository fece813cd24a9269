"""The kinematics layer (docs/model.md §7, §11, §12).

``tree`` (forward recursions over the model tree: placements, velocities, accelerations;
compiled back-end ``kernels``) · ``closure`` (loop closure by Newton, forward kinematics) ·
``ik`` (constrained IK along a trajectory: ``ik_batch`` stacked over samples, ``ik_newton``
sample by sample, ``ik_common`` their shared inputs and result) · ``singularity``
(conditioning and margins) · ``errors``. The closed form lives in :mod:`pollard_pin.analytic`."""
