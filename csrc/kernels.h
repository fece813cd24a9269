/* The compiled kernels behind pollard_pin.kinematics.kernels (C, built when the package is
 * installed; setup.py): the loops over samples, with the GIL released. kernels.py is the typed
 * front: it makes every array C-contiguous float64 / int64, allocates the outputs and documents
 * the mathematics (docs/model.md §11–§12); this code checks sizes and indices, then computes.
 *
 * module.c: the module (its argument checks: checks.c); linalg.c: Gram extremes and the block
 * inverse; tree.c: placements, point Jacobians and drifts; sense.c: a control tick's
 * closed-loop state; rk4.c: a simulation's RK4 step around a Python callable. Every function
 * takes buffers (read-only "y*", written "w*") and their dimensions. */
#ifndef POLLARD_KERNELS_H
#define POLLARD_KERNELS_H
#include "checks.h"
#include <math.h>

/* Partial pivoting's row: the r in [c, rows) with the largest |A[r][c]| (the first on ties,
 * as LAPACK's idamax) of a row-major A with row stride w; that |value| in *best. */
static inline idx pk_pivot(const double *A, idx w, idx c, idx rows, double *best)
{
    idx p = c;
    *best = fabs(A[c * w + c]);
    for (idx r = c + 1; r < rows; r++)
        if (fabs(A[r * w + c]) > *best)
            p = r, *best = fabs(A[r * w + c]);
    return p;
}

/* the kernels (linalg.c, tree.c) */
PyObject *pk_gram_extremes(PyObject *self, PyObject *args);
PyObject *pk_block_inverse(PyObject *self, PyObject *args);
PyObject *pk_tree_placements(PyObject *self, PyObject *args);
PyObject *pk_point_jacobians(PyObject *self, PyObject *args);
PyObject *pk_point_drifts(PyObject *self, PyObject *args);
PyObject *pk_closed_state(PyObject *self, PyObject *args);
PyObject *pk_rk4_step(PyObject *self, PyObject *args);

/* the loops behind them, for one another (one sample: n = 1) */
void gram_extremes_loop(const double *A, idx n, idx m, idx k, double *lo, double *hi,
                        double *work);
void tree_placements_loop(const double *C, const double *S, idx n, idx nq,
                          const int64_t *parent, const int64_t *axis, const int64_t *idx_q,
                          const double *M_rot, const double *M_trans, idx J, double *R,
                          double *o);
void point_jacobians_loop(const double *R, const double *o, idx S, idx n, const int64_t *axis,
                          const int64_t *col, const int64_t *pt_slot, const double *pt_local,
                          const int64_t *pt_support, idx depth, const int64_t *pt_row,
                          const double *pt_sign, idx P, idx ang_point, idx ang_row, idx nv,
                          double *K, double *pos);
void point_drifts_loop(const double *R, const double *o, idx S, idx n, const int64_t *parent,
                       const int64_t *axis, const int64_t *col, const double *V, idx nv,
                       const int64_t *pt_slot, const int64_t *pt_row, const double *pt_sign,
                       const double *pos, idx P, idx ang_point, idx ang_row, double *drift,
                       double *omega, double *work);

#endif
