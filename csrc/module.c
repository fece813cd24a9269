/* The module table of the compiled kernels (kernels.h); their argument checks: checks.c. */
#include "kernels.h"

static PyMethodDef methods[] = {
    {"gram_extremes", pk_gram_extremes, METH_VARARGS, "A, n, m, k, lo, hi"},
    {"block_inverse", pk_block_inverse, METH_VARARGS,
     "K, n, size, top, bottom, first, second, h, out"},
    {"tree_placements", pk_tree_placements, METH_VARARGS,
     "C, S, n, nq, parent, axis, idx_q, M_rot, M_trans, J, R, o"},
    {"point_jacobians", pk_point_jacobians, METH_VARARGS,
     "R, o, S, n, axis, col, pt_slot, pt_local, pt_support, depth, pt_row, pt_sign, P, "
     "ang_point, ang_row, nv, K, pos"},
    {"point_drifts", pk_point_drifts, METH_VARARGS,
     "R, o, S, n, parent, axis, col, V, nv, pt_slot, pt_row, pt_sign, pos, P, ang_point, "
     "ang_row, drift, omega"},
    {"closed_state", pk_closed_state, METH_VARARGS,
     "parent, axis, idx_q, col, M_rot, M_trans, pt_slot, pt_local, pt_support, pt_row, "
     "pt_sign, ia, ip, S, P, depth, ang_point, ang_row, nq, nv, m, theta, dtheta, guess, tol, "
     "max_iter, q, v, Jc, N, a0, lohi -> Newton steps (>= 0) or -1 / -2 / -3"},
    {"rk4_step", pk_rk4_step, METH_VARARGS,
     "f, q, v, a1, h, n, stage_q, stage_v, q_out, v_out"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_kernels",
    "The compiled loops behind pollard_pin.kinematics.kernels (use that module).", -1, methods,
};

PyMODINIT_FUNC PyInit__kernels(void) { return PyModule_Create(&module); }
