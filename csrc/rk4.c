/* One classical RK4 step of q̈ = f(q, q̇) (docs/model.md §18), the stages' small-vector
 * arithmetic in C around three calls of the Python callable f (kernels.h): in numpy the
 * arithmetic is some thirty calls of fixed cost, more than the dynamics' own. Each operation
 * is the one numpy's expression would do, in the same order (no FMA: setup.py), so the result
 * is the same to the bit. */
#include "kernels.h"

#include <string.h>

/* f(qs, vs) into a (n values): 0 with an exception set if f raised or returned no n floats. */
static int stage(PyObject *f, PyObject *qs, PyObject *vs, idx n, double *a)
{
    PyObject *out = PyObject_CallFunctionObjArgs(f, qs, vs, NULL);
    if (out == NULL)
        return 0;
    Py_buffer b;
    int ok = PyObject_GetBuffer(out, &b, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) == 0;
    if (ok) {
        ok = b.len == n * 8 && b.itemsize == 8 && b.format != NULL
             && (strcmp(b.format, "d") == 0 || strcmp(b.format, "<d") == 0
                 || strcmp(b.format, "=d") == 0);
        if (ok)
            memcpy(a, b.buf, sizeof(double) * n);
        else
            PyErr_Format(PyExc_ValueError, "kernels: the RK4 stage function returned no %zd "
                         "float64 values", n);
        PyBuffer_Release(&b);
    }
    Py_DECREF(out);
    return ok;
}

PyObject *pk_rk4_step(PyObject *self, PyObject *args)
{
    PyObject *f, *qs_obj, *vs_obj;
    Py_buffer b[7] = {{0}};
    double h;
    idx n;
    if (!PyArg_ParseTuple(args, "Oy*y*y*dnOOw*w*", &f, &b[0], &b[1], &b[2], &h, &n, &qs_obj,
                          &vs_obj, &b[3], &b[4]))
        return NULL;
    int ok = PyObject_GetBuffer(qs_obj, &b[5], PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) == 0
             && PyObject_GetBuffer(vs_obj, &b[6], PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) == 0;
    ok = ok && n >= 1 && pk_check_len(&b[0], n, "q") && pk_check_len(&b[1], n, "v")
         && pk_check_len(&b[2], n, "a1") && pk_check_len(&b[3], n, "q_out")
         && pk_check_len(&b[4], n, "v_out") && pk_check_len(&b[5], n, "stage q")
         && pk_check_len(&b[6], n, "stage v");
    double *work = ok ? PyMem_Malloc(sizeof(double) * 5 * n) : NULL;
    if (ok && work == NULL) {
        PyErr_NoMemory();
        ok = 0;
    }
    if (ok) {
        const double *q = b[0].buf, *v = b[1].buf, *a1 = b[2].buf;
        double *q_out = b[3].buf, *v_out = b[4].buf, *qs = b[5].buf, *vs = b[6].buf;
        double *v2 = work, *v3 = v2 + n, *a2 = v3 + n, *a3 = a2 + n, *a4 = a3 + n;
        double half = 0.5 * h, sixth = h / 6.0;
        for (idx i = 0; i < n; i++) {
            v2[i] = v[i] + half * a1[i];
            vs[i] = v2[i];
            qs[i] = q[i] + half * v[i];
        }
        ok = stage(f, qs_obj, vs_obj, n, a2);
        for (idx i = 0; ok && i < n; i++) {
            v3[i] = v[i] + half * a2[i];
            vs[i] = v3[i];
            qs[i] = q[i] + half * v2[i];
        }
        ok = ok && stage(f, qs_obj, vs_obj, n, a3);
        for (idx i = 0; ok && i < n; i++) {
            vs[i] = v[i] + h * a3[i]; /* v4 */
            qs[i] = q[i] + h * v3[i];
        }
        ok = ok && stage(f, qs_obj, vs_obj, n, a4);
        for (idx i = 0; ok && i < n; i++) {
            q_out[i] = q[i] + sixth * (((v[i] + (v2[i] + v2[i])) + (v3[i] + v3[i])) + vs[i]);
            v_out[i] = v[i] + sixth * (((a1[i] + (a2[i] + a2[i])) + (a3[i] + a3[i])) + a4[i]);
        }
    }
    PyMem_Free(work);
    pk_release(b, 7);
    if (!ok)
        return NULL;
    Py_RETURN_NONE;
}
