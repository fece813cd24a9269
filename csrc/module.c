/* The argument checks and the module table of the compiled kernels (kernels.h). */
#include "kernels.h"

/* --- argument checks (before the GIL is released) ---------------------------------------- */
int pk_check_len(const Py_buffer *b, idx count, const char *what)
{
    if (b->len != count * 8) {
        PyErr_Format(PyExc_ValueError, "kernels: %s holds %zd bytes, expected %zd (%zd values)",
                     what, b->len, count * 8, count);
        return 0;
    }
    return 1;
}

/* Every entry of an int64 array in [lo, hi). */
int pk_check_range(const Py_buffer *b, idx lo, idx hi, const char *what)
{
    const int64_t *x = (const int64_t *)b->buf;
    idx n = b->len / 8;
    for (idx i = 0; i < n; i++)
        if (x[i] < lo || x[i] >= hi) {
            PyErr_Format(PyExc_ValueError, "kernels: %s[%zd] = %lld is outside [%zd, %zd)",
                         what, i, (long long)x[i], lo, hi);
            return 0;
        }
    return 1;
}

void pk_release(Py_buffer *bufs, int count)
{
    for (int i = 0; i < count; i++)
        if (bufs[i].obj != NULL)
            PyBuffer_Release(&bufs[i]);
}

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
