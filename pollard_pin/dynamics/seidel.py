"""TOPP-RA itself (``toppra``, docs/model.md §19): its import, with the one-line hint when it
is missing, and its reachability algorithm with lean per-stage loops (:func:`lean_toppra`)."""
from __future__ import annotations

import numpy as np

_LEAN = []  # the TOPPRA subclass of lean_toppra, made once toppra is imported


def load_toppra():
    """The ``toppra`` package with its algorithm and constraint modules imported; missing, an
    ImportError saying how to install it."""
    try:
        import toppra
        import toppra.algorithm
        import toppra.constraint
    except ImportError as exc:
        raise ImportError(f"the time-optimal cycle needs TOPP-RA ({exc}): pip install "
                          "'toppra>=0.6.10,<0.7' (a core dependency of pollard-pin)") from None
    return toppra


def lean_toppra():
    """toppra's ``TOPPRA`` (0.6.x) with the Python overhead of its two per-stage loops cut:
    the controllable sets and the forward step call the Seidel solver in the same order with
    the very arguments toppra's own code passes, so the result is the same to the bit; what
    goes is a fresh array, a NaN test by ``.any()`` and a logging check per stage (a third of
    a solve on a grid of thousands of points). Its failure warnings are not logged."""
    if _LEAN:
        return _LEAN[0]
    toppra = load_toppra()

    class Lean(toppra.algorithm.TOPPRA):
        def compute_controllable_sets(self, sdmin, sdmax):
            assert sdmin <= sdmax and 0 <= sdmin
            n, solver = self._N, self.solver_wrapper
            K = np.zeros((n + 1, 2))
            K[n] = [sdmin ** 2, sdmax ** 2]
            solver.setup_solver()
            upper = np.zeros(solver.get_no_vars())
            upper[0], upper[1] = 1e-9, -1
            lower = -upper
            solve = solver.solve_stagewise_optim
            lo, hi = K[n, 0], K[n, 1]
            nan = np.nan
            for i in range(n - 1, -1, -1):
                x_up = solve(i, None, upper, nan, nan, lo, hi)[1]
                x_lo = solve(i, None, lower, nan, nan, lo, hi)[1]
                if x_lo < 0:
                    x_lo = 0.0
                K[i, 0], K[i, 1] = x_lo, x_up
                if x_lo != x_lo or x_up != x_up:  # NaN: toppra's own early return
                    return K
                lo, hi = K[i, 0], K[i, 1]
            solver.close_solver()
            return K

        def _forward_step(self, i, x, K_next):
            if x != x:
                return np.array([np.nan, np.nan])
            solver = self.solver_wrapper
            if getattr(self, "_lean_deltas", None) is None:
                self._lean_deltas = np.asarray(solver.get_deltas())
                self._lean_g = np.zeros(solver.get_no_vars())
                self._lean_g[1] = -1
            g = self._lean_g
            g[0] = -2 * self._lean_deltas[i]
            return solver.solve_stagewise_optim(i, None, g, x, x, K_next[0], K_next[1])

    _LEAN.append(Lean)
    return Lean
