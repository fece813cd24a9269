/* The compiled loops behind pollard_pin.painting.spray.kernel (that module is its typed front):
 * the round Gaussian spot's deposition rate and each source's height over each point's tangent
 * plane, for a block of sources × points in one pass with no temporaries, and the cull's cone
 * test point by point, alone or before the rate of the points it keeps (docs/model.md §20).
 *
 * Pair by pair, as spray/deposition.py's pair_rate: d = s − p, h = d·a, |d|², d·n, then _rate's
 * operations in their order without FMA contraction (setup.py): σ² = (k h)²,
 * ρ² = max(|d|² − h², 0), rate = ((flow/2π) / σ²) · exp(−ρ²/2 / σ²) · max(−d·n, 0) / h, 0
 * unless h > 0 and the rate is finite. numpy's block formulation (Sources.numpy_rate_and_height)
 * expands |d|² = s·s + p·p − 2 s·p in matrix products instead, whose round-off grows with the
 * coordinates' size: ~eps (|s|² + |p|²) / σ² of the rate (docs/model.md §20). */
#include "checks.h"
#include <math.h>
#include <stdlib.h>

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

/* Reach.keep's verdict on one point (spray/deposition.py, docs/model.md §20), its numpy
 * formula's operations in their order: d = s − p̄, r = |d|, angle = arccos(clip(d·ā / r)),
 * spread = arcsin(clip((δp + radius) / r)), kept where angle − δa − spread ≤ cone, or
 * r ≤ throw/4 + δp + radius (``base`` + radius), or the angle is not finite (r = 0, NaN).
 * The clips keep a NaN, as numpy's minimum and maximum do. The clauses are tried cheapest
 * first, and a cosine above ``inside`` (cos(cone + δa) + 1e-9, accept_above) is inside the
 * cone with neither arccos nor arcsin: its angle lies ≥ 1e-9 rad inside cone + δa, far past
 * their and the sums' round-off, and spread ≥ 0, so the formula's verdict is the same. */
static inline int cone_keeps(const double *si, const double *pm, const double *am, double dp,
                             double da, double cone, double base, double radius, double inside)
{
    const double d0 = si[0] - pm[0], d1 = si[1] - pm[1], d2 = si[2] - pm[2];
    const double r = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    if (r <= base + radius)
        return 1;
    double c = (d0 * am[0] + d1 * am[1] + d2 * am[2]) / r;
    if (isnan(c))  /* its angle is not finite */
        return 1;
    c = c < -1.0 ? -1.0 : c;
    c = c > 1.0 ? 1.0 : c;
    if (c > inside)
        return 1;
    const double angle = acos(c);
    double sp = (dp + radius) / r;
    sp = sp < 0.0 ? 0.0 : sp;
    sp = sp > 1.0 ? 1.0 : sp;
    const double spread = asin(sp);
    return angle - da - spread <= cone || !isfinite(angle);
}

/* The cosine above which a point lies inside the cone (cone_keeps): none where cone + δa
 * nears π (or is NaN). */
static double accept_above(double da, double cone)
{
    const double x = cone + da;
    return x >= 0.0 && x <= 3.0 ? cos(x) + 1e-9 : 2.0;
}

/* The cone's arguments: p̄ (3), ā (3), then δp, δa, cone, base. */
static int parse_cone(const Py_buffer *b, const double **pm, const double **am, double *dp,
                      double *da, double *cone, double *base)
{
    if (!pk_check_len(b, 10, "cone"))
        return 0;
    const double *c = b->buf;
    *pm = c, *am = c + 3, *dp = c[6], *da = c[7], *cone = c[8], *base = c[9];
    return 1;
}

static int check_bytes(const Py_buffer *b, idx count, const char *what)
{
    if (b->len != count) {
        PyErr_Format(PyExc_ValueError, "kernels: %s holds %zd bytes, expected %zd", what,
                     b->len, count);
        return 0;
    }
    return 1;
}

/* cone_keep(s, P, radius, per_point, cone, keep): keep (P bytes) = cone_keeps of each point,
 * radius (P,) or (1,). */
static PyObject *pd_cone_keep(PyObject *self, PyObject *args)
{
    Py_buffer b[4] = {{0}};
    idx P;
    int per_point;
    const double *pm, *am;
    double dp, da, cone, base;
    if (!PyArg_ParseTuple(args, "y*ny*py*w*", &b[0], &P, &b[1], &per_point, &b[2], &b[3]))
        return NULL;
    if (!(P >= 0 && pk_check_len(&b[0], 3 * P, "s")
          && pk_check_len(&b[1], per_point ? P : 1, "radius")
          && parse_cone(&b[2], &pm, &am, &dp, &da, &cone, &base)
          && check_bytes(&b[3], P, "keep"))) {
        pk_release(b, 4);
        return NULL;
    }
    const double *s = b[0].buf, *rad = b[1].buf;
    char *keep = b[3].buf;
    const double inside = accept_above(da, cone);
    Py_BEGIN_ALLOW_THREADS
    for (idx i = 0; i < P; i++)
        keep[i] = (char)cone_keeps(s + 3 * i, pm, am, dp, da, cone, base,
                                   rad[per_point ? i : 0], inside);
    Py_END_ALLOW_THREADS
    pk_release(b, 4);
    Py_RETURN_NONE;
}

/* round_near(s, n, per_point, group, held, P, G, cone or b"", p, a, T, k, coef, kept, rate,
 * height) -> K: the points i of s (P, 3) whose group's ball may hold a kept point
 * (held[group[i]]) and that the cone keeps (every such point without a cone), their indices
 * in kept[:K] (ascending), then round_loop on them: rate and height (T, K) at the start of
 * their buffers (T × P each). The kept points' positions and normals are gathered first. */
static PyObject *pd_round_near(PyObject *self, PyObject *args)
{
    Py_buffer b[10] = {{0}};
    int per_point;
    idx P, G, T;
    double k, coef;
    if (!PyArg_ParseTuple(args, "y*y*py*y*nny*y*y*nddw*w*w*", &b[0], &b[1], &per_point, &b[2],
                          &b[3], &P, &G, &b[4], &b[5], &b[6], &T, &k, &coef, &b[7], &b[8],
                          &b[9]))
        return NULL;
    const double *pm = NULL, *am = NULL;
    double dp = 0, da = 0, cone = 0, base = 0;
    const int all = b[4].len == 0;
    if (!(P >= 0 && G >= 0 && T >= 0 && pk_check_len(&b[0], 3 * P, "s")
          && pk_check_len(&b[1], per_point ? 3 * P : 3, "n") && pk_check_len(&b[2], P, "group")
          && pk_check_range(&b[2], 0, G, "group") && check_bytes(&b[3], G, "held")
          && (all || parse_cone(&b[4], &pm, &am, &dp, &da, &cone, &base))
          && pk_check_len(&b[5], 3 * T, "p") && pk_check_len(&b[6], 3 * T, "a")
          && pk_check_len(&b[7], P, "kept") && pk_check_len(&b[8], T * P, "rate")
          && pk_check_len(&b[9], T * P, "height"))) {
        pk_release(b, 10);
        return NULL;
    }
    const double *s = b[0].buf, *n = b[1].buf;
    const int64_t *group = b[2].buf;
    const char *held = b[3].buf;
    int64_t *kept = b[7].buf;
    idx K = 0;
    int failed = 0;
    const double inside = all ? 2.0 : accept_above(da, cone);
    Py_BEGIN_ALLOW_THREADS
    for (idx i = 0; i < P; i++)
        if (held[group[i]]
            && (all || cone_keeps(s + 3 * i, pm, am, dp, da, cone, base, 0.0, inside)))
            kept[K++] = i;
    if (K) {
        double *sk = malloc(sizeof(double) * 3 * K * (per_point ? 2 : 1));
        if (sk == NULL)
            failed = 1;
        else {
            double *nk = per_point ? sk + 3 * K : NULL;
            for (idx c = 0; c < K; c++)
                for (int e = 0; e < 3; e++) {
                    sk[3 * c + e] = s[3 * kept[c] + e];
                    if (per_point)
                        nk[3 * c + e] = n[3 * kept[c] + e];
                }
            round_loop(sk, per_point ? nk : n, per_point, b[5].buf, b[6].buf, T, K, k, coef,
                       b[8].buf, b[9].buf);
            free(sk);
        }
    }
    Py_END_ALLOW_THREADS
    pk_release(b, 10);
    if (failed)
        return PyErr_NoMemory();
    return PyLong_FromSsize_t(K);
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
    {"cone_keep", pd_cone_keep, METH_VARARGS, "s, P, radius, per_point, cone, keep"},
    {"round_near", pd_round_near, METH_VARARGS,
     "s, n, per_point, group, held, P, G, cone, p, a, T, k, coef, kept, rate, height"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_deposit",
    "The compiled loop behind pollard_pin.painting.spray.kernel (use that module).", -1,
    methods,
};

PyMODINIT_FUNC PyInit__deposit(void) { return PyModule_Create(&module); }
