"""The default singularity margins (docs/model.md §12), in a leaf with no imports: the CLI
shows them in ``--help`` without loading numpy or the compiled kernels."""

SINGULARITY_MARGIN = 1e-3  # default smallest singular value allowed (parallel and serial)
WRIST_MARGIN = 0.05  # default smallest |sin θ1716| allowed (≈ 2.9°)
