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
    from toppra import exceptions
    from toppra.algorithm import ParameterizationReturnCode as codes
    from toppra.constants import MAX_TRIES, SMALL, TINY

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

        def compute_parameterization(self, sd_start, sd_end, return_data=False):
            # toppra 0.6.10's, its forward pass with Python floats (the same IEEE operations
            # in the same order); a failure as toppra's: None, None, None (and K)
            if sd_end < 0 or sd_start < 0:
                raise exceptions.BadInputVelocities(
                    f"Negative path velocities: path velocities must be positive: "
                    f"({sd_start}, {sd_end})")
            data = self._problem_data
            K = self.compute_controllable_sets(sd_end, sd_end)
            failed = (None, None, None, K) if return_data else (None, None, None)
            if np.isnan(K).any():
                data.return_code = codes.FailUncontrollable
                return failed
            data.K = K
            x_start = sd_start ** 2
            if x_start + SMALL < K[0, 0] or K[0, 1] + SMALL < x_start:
                data.return_code = codes.FailUncontrollable
                return failed
            solver, n = self.solver_wrapper, self._N
            stages = solver.get_no_stages()
            deltas = solver.get_deltas()
            xs, us = np.zeros(stages + 1), np.zeros(stages)
            xs[0] = x_start
            extra = solver.get_no_vars() - 2
            v_vec = np.zeros((stages, extra))
            low, high = K[:, 0].tolist(), K[:, 1].tolist()
            step = deltas.tolist() if hasattr(deltas, "tolist") else list(deltas)
            forward = self._forward_step
            tries, i, x = 0, 0, xs[0]
            solver.setup_solver()
            while i < n:
                res = forward(i, x, (low[i + 1], high[i + 1]))
                u = res[0]
                if u != u:  # NaN: toppra's retry, x a little lower
                    if tries < MAX_TRIES:
                        x = xs[i] = max(xs[i] - TINY, 0.999 * xs[i])
                        tries += 1
                        continue
                    xs[i + 1:] = np.nan
                    break
                tries = 0
                us[i] = u
                x_next = x + 2 * step[i] * u
                x_next = max(x_next - TINY, 0.9999 * x_next)
                x = xs[i + 1] = min(high[i + 1], max(low[i + 1], x_next))
                if extra:
                    v_vec[i] = res[2:]
                i += 1
            solver.close_solver()
            sd_vec, sdd_vec = np.sqrt(xs), np.copy(us)
            data.sd_vec, data.sdd_vec = sd_vec, sdd_vec
            data.return_code = codes.ErrUnknown if np.isnan(sd_vec).any() else codes.Ok
            if return_data:
                return sdd_vec, sd_vec, v_vec, K
            return sdd_vec, sd_vec, v_vec

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
