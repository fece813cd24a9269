/* The compiled loop behind pollard_pin.painting.spray.kernel (that module is its typed front):
 * the round Gaussian spot's deposition rate and each source's height over each point's tangent
 * plane, for a block of sources × points in one pass with no temporaries (docs/model.md §20).
 *
 * Pair by pair, as spray/deposition.py's pair_rate: d = s − p, h = d·a, |d|², d·n, then _rate's
 * operations in their order without FMA contraction (setup.py): σ² = (k h)²,
 * ρ² = max(|d|² − h², 0), rate = ((flow/2π) / σ²) · exp(−ρ²/2 / σ²) · max(−d·n, 0) / h, 0
 * unless h > 0 and the rate is finite. numpy's block formulation (Sources.numpy_rate_and_height)
 * expands |d|² = s·s + p·p − 2 s·p in matrix products instead, whose round-off grows with the
 * coordinates' size: ~eps (|s|² + |p|²) / σ² of the rate (docs/model.md §20). */
#include "checks.h"
#include <math.h>

#define CHUNK 64 /* points at a time: their exponents (in SIMD), exp, then their rates */

/* One block: rate and height (T × P, row-major). A pair with h ≤ 0 or d·n ≥ 0 (or NaN) gets
 * exp(0) and a rate of 0, as _rate's mask gives it. */
static void round_loop(const double *s, const double *n, int per_point, const double *p,
                       const double *a, idx T, idx P, double k, double coef, double *rate,
                       double *height)
{
    double x[CHUNK], q[CHUNK], hh[CHUNK], e[CHUNK];
    for (idx j = 0; j < T; j++) {
        const double *aj = a + 3 * j, *pj = p + 3 * j;
        double *rj = rate + j * P, *hj = height + j * P;
        for (idx i0 = 0; i0 < P; i0 += CHUNK) {
            const idx m = P - i0 < CHUNK ? P - i0 : CHUNK;
            for (idx c = 0; c < m; c++) {
                const idx i = i0 + c;
                const double *si = s + 3 * i, *ni = per_point ? n + 3 * i : n;
                const double d0 = si[0] - pj[0], d1 = si[1] - pj[1], d2_ = si[2] - pj[2];
                const double dn = d0 * ni[0] + d1 * ni[1] + d2_ * ni[2];
                const double h = d0 * aj[0] + d1 * aj[1] + d2_ * aj[2];
                const double d2 = d0 * d0 + d1 * d1 + d2_ * d2_;
                hj[i] = -dn;
                double sh2 = k * h;
                sh2 *= sh2;
                double rho2 = d2 - h * h;
                rho2 = rho2 < 0.0 ? 0.0 : rho2;
                rho2 *= -0.5;
                rho2 /= sh2;
                const int live = h > 0.0 && -dn > 0.0;
                x[c] = live ? rho2 : 0.0;
                q[c] = live ? coef / sh2 : 0.0;
                hh[c] = live ? h : 1.0;
            }
            for (idx c = 0; c < m; c++)
                e[c] = exp(x[c]);
            for (idx c = 0; c < m; c++) {
                const idx i = i0 + c;
                double r = q[c];
                r *= e[c];
                r *= hj[i];
                r /= hh[c];
                rj[i] = r > 0.0 && r < INFINITY ? r : 0.0;  /* NaN, ±inf, −0: 0 */
            }
        }
    }
}

/* round_rate(s, n, per_point, p, a, T, P, k, coef, rate, height) */
static PyObject *pd_round_rate(PyObject *self, PyObject *args)
{
    Py_buffer b[6] = {{0}};
    int per_point;
    idx T, P;
    double k, coef;
    if (!PyArg_ParseTuple(args, "y*y*py*y*nnddw*w*", &b[0], &b[1], &per_point, &b[2], &b[3], &T,
                          &P, &k, &coef, &b[4], &b[5]))
        return NULL;
    if (!(T >= 0 && P >= 0 && pk_check_len(&b[0], 3 * P, "s")
          && pk_check_len(&b[1], per_point ? 3 * P : 3, "n") && pk_check_len(&b[2], 3 * T, "p")
          && pk_check_len(&b[3], 3 * T, "a") && pk_check_len(&b[4], T * P, "rate")
          && pk_check_len(&b[5], T * P, "height"))) {
        pk_release(b, 6);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    round_loop(b[0].buf, b[1].buf, per_point, b[2].buf, b[3].buf, T, P, k, coef, b[4].buf,
               b[5].buf);
    Py_END_ALLOW_THREADS
    pk_release(b, 6);
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"round_rate", pd_round_rate, METH_VARARGS,
     "s, n, per_point, p, a, T, P, k, coef, rate, height"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_deposit",
    "The compiled loop behind pollard_pin.painting.spray.kernel (use that module).", -1,
    methods,
};

PyMODINIT_FUNC PyInit__deposit(void) { return PyModule_Create(&module); }
