/* The compiled kernels of pollard_pin.kinematics.kernels (C, built when the package is
 * installed): the loops over samples, with the GIL released. kernels.py is the typed front:
 * it makes every array C-contiguous float64 / int64, allocates the outputs and documents the
 * mathematics (docs/model.md §11–§12); this file checks sizes and indices, then computes.
 *
 * Every function takes buffers (read-only "y*", written "w*") and their dimensions. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define EPS DBL_EPSILON
#define PSD_SLACK 1e-12 /* relative: round-off may push λ_min(T) of a singular Gram below 0 */
#define MAX_STEPS 100   /* Laguerre steps: a handful for a simple root, linear at a multiple one */

typedef Py_ssize_t idx;

/* --- argument checks (before the GIL is released) ---------------------------------------- */
static int check_len(const Py_buffer *b, idx count, const char *what)
{
    if (b->len != count * 8) {
        PyErr_Format(PyExc_ValueError, "kernels: %s holds %zd bytes, expected %zd (%zd values)",
                     what, b->len, count * 8, count);
        return 0;
    }
    return 1;
}

/* Every entry of an int64 array in [lo, hi). */
static int check_range(const Py_buffer *b, idx lo, idx hi, const char *what)
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

static void release(Py_buffer *bufs, int count)
{
    for (int i = 0; i < count; i++)
        if (bufs[i].obj != NULL)
            PyBuffer_Release(&bufs[i]);
}

/* --- Gram extremes (docs/model.md §12) --------------------------------------------------- */
/* G = AᵀA (k × k) of one matrix A (m × k). */
static void gram(const double *A, idx m, idx k, double *G)
{
    for (idx i = 0; i < k; i++)
        for (idx j = i; j < k; j++) {
            double acc = 0.0;
            for (idx r = 0; r < m; r++)
                acc += A[r * k + i] * A[r * k + j];
            G[i * k + j] = acc;
            G[j * k + i] = acc;
        }
}

/* Householder reduction of the symmetric G (overwritten) to diagonal d and off-diagonal e of a
 * tridiagonal matrix with the same eigenvalues. */
static void tridiagonalize(double *G, idx k, double *d, double *e, double *v, double *p)
{
    for (idx j = 0; j + 2 < k; j++) {
        double alpha = 0.0;
        for (idx i = j + 1; i < k; i++)
            alpha += G[i * k + j] * G[i * k + j];
        alpha = sqrt(alpha);
        if (G[(j + 1) * k + j] > 0.0)
            alpha = -alpha;
        e[j] = alpha;
        if (alpha == 0.0) /* column already reduced */
            continue;
        for (idx i = j + 1; i < k; i++)
            v[i] = G[i * k + j];
        v[j + 1] -= alpha;
        double norm2 = 0.0;
        for (idx i = j + 1; i < k; i++)
            norm2 += v[i] * v[i];
        double beta = 2.0 / norm2;
        /* G ← H G H with H = I − β v vᵀ: G −= v wᵀ + w vᵀ, w = β G v − (β² vᵀGv / 2) v */
        for (idx i = j + 1; i < k; i++) {
            double acc = 0.0;
            for (idx r = j + 1; r < k; r++)
                acc += G[i * k + r] * v[r];
            p[i] = beta * acc;
        }
        double half = 0.0;
        for (idx i = j + 1; i < k; i++)
            half += v[i] * p[i];
        half *= 0.5 * beta;
        for (idx i = j + 1; i < k; i++)
            p[i] -= half * v[i];
        for (idx i = j + 1; i < k; i++)
            for (idx r = j + 1; r < k; r++)
                G[i * k + r] -= v[i] * p[r] + p[i] * v[r];
    }
    for (idx j = 0; j < k; j++)
        d[j] = G[j * k + j];
    if (k > 1)
        e[k - 2] = G[(k - 1) * k + k - 2];
}

/* The eigenvalue of the tridiagonal (d, e² = e2) next to x, x outside the spectrum on the low
 * side (upward) or the high side. Pivots q_i(x) of T − xI, their x-derivatives and
 * Σ q_i'/q_i = p'/p (g), −(p'/p)' (h) give Laguerre's step n / (g ∓ √((n−1)(nh − g²))). */
static double laguerre(const double *d, const double *e2, idx k, double x, int upward,
                       double tol)
{
    for (int step_no = 0; step_no < MAX_STEPS; step_no++) {
        double q = d[0] - x;
        if (q == 0.0)
            q = EPS; /* x is an eigenvalue of a leading block: the usual Sturm shift */
        double iq = 1.0 / q; /* one division per row: they dominate the cost */
        double dq = -1.0, ddq = 0.0;
        double g = -iq;
        double h = g * g;
        for (idx i = 1; i < k; i++) {
            double r = e2[i - 1] * iq;
            double q1 = d[i] - x - r;
            double dq1 = -1.0 + r * dq * iq;
            double ddq1 = r * (ddq - 2.0 * dq * dq * iq) * iq;
            q = q1, dq = dq1, ddq = ddq1;
            if (q == 0.0)
                q = EPS;
            iq = 1.0 / q;
            double u = dq * iq;
            g += u;
            h += u * u - ddq * iq;
        }
        double disc = (double)(k - 1) * ((double)k * h - g * g);
        double root = disc > 0.0 ? sqrt(disc) : 0.0;
        double den = upward ? g - root : g + root;
        if (den == 0.0 || (upward ? g >= 0.0 : g <= 0.0))
            break; /* at (or, by round-off, past) the eigenvalue */
        double step = (double)k / den;
        double x_new = x - step;
        if (upward ? x_new <= x : x_new >= x)
            break; /* no more progress: converged to round-off */
        x = x_new;
        if (fabs(step) <= tol)
            break;
    }
    return x;
}

/* Sturm count: the number of eigenvalues of the tridiagonal (d, e2) below x. */
static idx below(const double *d, const double *e2, idx k, double x)
{
    idx count = 0;
    double q = 1.0;
    for (idx i = 0; i < k; i++) {
        q = d[i] - x - (i > 0 ? e2[i - 1] / q : 0.0);
        if (q == 0.0)
            q = -EPS;
        if (q < 0.0)
            count++;
    }
    return count;
}

static void gram_extremes_loop(const double *A, idx n, idx m, idx k, double *lo, double *hi,
                               double *work)
{
    idx k1 = k > 1 ? k - 1 : 1;
    double *G = work, *d = G + k * k, *e = d + k, *e2 = e + k1, *v = e2 + k1, *p = v + k;
    for (idx i = 0; i < k1; i++)
        e[i] = 0.0;
    for (idx s = 0; s < n; s++) {
        gram(A + s * m * k, m, k, G);
        double scale = 0.0;
        for (idx i = 0; i < k; i++)
            if (G[i * k + i] > scale)
                scale = G[i * k + i]; /* = max |G_ij|: work at unit scale, no overflow */
        if (scale == 0.0) {           /* the zero matrix */
            lo[s] = hi[s] = 0.0;
            continue;
        }
        double inv = 1.0 / scale;
        for (idx i = 0; i < k * k; i++)
            G[i] *= inv;
        tridiagonalize(G, k, d, e, v, p);
        double low = INFINITY, high = -INFINITY;
        for (idx i = 0; i < k; i++) {
            double radius = (i > 0 ? fabs(e[i - 1]) : 0.0) + (i < k - 1 ? fabs(e[i]) : 0.0);
            if (d[i] - radius < low)
                low = d[i] - radius;
            if (d[i] + radius > high)
                high = d[i] + radius;
        }
        for (idx i = 0; i + 1 < k; i++)
            e2[i] = e[i] * e[i];
        double tol = 4.0 * EPS * (fabs(high) > fabs(low) ? fabs(high) : fabs(low));
        /* AᵀA is positive semi-definite: start just below 0 when no eigenvalue of T is lower
         * (round-off), which is much nearer λ_min than Gershgorin's bound. */
        double start = low - tol > -PSD_SLACK ? low - tol : -PSD_SLACK;
        if (below(d, e2, k, start) > 0)
            start = low - tol;
        lo[s] = scale * laguerre(d, e2, k, start, 1, tol);
        hi[s] = scale * laguerre(d, e2, k, high + tol, 0, tol);
    }
}

static PyObject *gram_extremes(PyObject *self, PyObject *args)
{
    Py_buffer b[3] = {{0}};
    idx n, m, k;
    if (!PyArg_ParseTuple(args, "y*nnnw*w*", &b[0], &n, &m, &k, &b[1], &b[2]))
        return NULL;
    if (!(check_len(&b[0], n * m * k, "A") && check_len(&b[1], n, "lo")
          && check_len(&b[2], n, "hi"))) {
        release(b, 3);
        return NULL;
    }
    idx k1 = k > 1 ? k - 1 : 1;
    double *work = malloc(sizeof(double) * (k * k + 3 * k + 2 * k1 + 1));
    if (work == NULL) {
        release(b, 3);
        return PyErr_NoMemory();
    }
    Py_BEGIN_ALLOW_THREADS
    gram_extremes_loop(b[0].buf, n, m, k, b[1].buf, b[2].buf, work);
    Py_END_ALLOW_THREADS
    free(work);
    release(b, 3);
    Py_RETURN_NONE;
}

/* --- block-triangular inverse (docs/model.md §11) ---------------------------------------- */
/* out = M⁻¹ (k × k) by Gauss–Jordan with partial pivoting; 0 at an exactly zero pivot
 * (singular M), as LAPACK's LU. work is k × 2k. */
static int invert(const double *M, idx k, double *out, double *work)
{
    idx w = 2 * k;
    for (idx i = 0; i < k; i++)
        for (idx j = 0; j < k; j++) {
            work[i * w + j] = M[i * k + j];
            work[i * w + k + j] = i == j ? 1.0 : 0.0;
        }
    for (idx c = 0; c < k; c++) {
        idx pivot = c;
        double best = fabs(work[c * w + c]);
        for (idx r = c + 1; r < k; r++)
            if (fabs(work[r * w + c]) > best)
                pivot = r, best = fabs(work[r * w + c]);
        if (best == 0.0)
            return 0;
        if (pivot != c)
            for (idx j = c; j < w; j++) {
                double t = work[c * w + j];
                work[c * w + j] = work[pivot * w + j];
                work[pivot * w + j] = t;
            }
        double inv = 1.0 / work[c * w + c];
        for (idx j = c; j < w; j++)
            work[c * w + j] *= inv;
        for (idx r = 0; r < k; r++) {
            double f = work[r * w + c];
            if (r != c && f != 0.0)
                for (idx j = c; j < w; j++)
                    work[r * w + j] -= f * work[c * w + j];
        }
    }
    for (idx i = 0; i < k; i++)
        for (idx j = 0; j < k; j++)
            out[i * k + j] = work[i * w + k + j];
    return 1;
}

static void block_inverse_loop(const double *K, idx n, idx size, const int64_t *top,
                               const int64_t *bottom, const int64_t *first,
                               const int64_t *second, idx h, double *out, double *scratch)
{
    double *T = scratch, *X = T + h * h, *Ti = X + h * h, *Xi = Ti + h * h,
           *CTi = Xi + h * h, *work = CTi + h * h;
    idx ss = size * size;
    memset(out, 0, sizeof(double) * n * ss);
    for (idx s = 0; s < n; s++) {
        const double *Ks = K + s * ss;
        double *Os = out + s * ss;
        for (idx i = 0; i < h; i++)
            for (idx j = 0; j < h; j++) {
                T[i * h + j] = Ks[bottom[i] * size + first[j]];
                X[i * h + j] = Ks[top[i] * size + second[j]];
            }
        if (!(invert(T, h, Ti, work) && invert(X, h, Xi, work))) {
            for (idx i = 0; i < ss; i++)
                Os[i] = NAN;
            continue;
        }
        for (idx i = 0; i < h; i++) /* C T⁻¹ */
            for (idx j = 0; j < h; j++) {
                double acc = 0.0;
                for (idx r = 0; r < h; r++)
                    acc += Ks[top[i] * size + first[r]] * Ti[r * h + j];
                CTi[i * h + j] = acc;
            }
        for (idx i = 0; i < h; i++)
            for (idx j = 0; j < h; j++) {
                Os[first[i] * size + bottom[j]] = Ti[i * h + j];
                Os[second[i] * size + top[j]] = Xi[i * h + j];
                double acc = 0.0;
                for (idx r = 0; r < h; r++)
                    acc += Xi[i * h + r] * CTi[r * h + j];
                Os[second[i] * size + bottom[j]] = -acc;
            }
    }
}

static PyObject *block_inverse(PyObject *self, PyObject *args)
{
    Py_buffer b[6] = {{0}};
    idx n, size, h;
    if (!PyArg_ParseTuple(args, "y*nny*y*y*y*nw*", &b[0], &n, &size, &b[1], &b[2], &b[3],
                          &b[4], &h, &b[5]))
        return NULL;
    static const char *names[] = {"top", "bottom", "first", "second"};
    int ok = check_len(&b[0], n * size * size, "K") && check_len(&b[5], n * size * size, "out");
    for (int i = 0; ok && i < 4; i++)
        ok = check_len(&b[1 + i], h, names[i]) && check_range(&b[1 + i], 0, size, names[i]);
    if (!ok) {
        release(b, 6);
        return NULL;
    }
    double *scratch = malloc(sizeof(double) * (7 * h * h + 1));
    if (scratch == NULL) {
        release(b, 6);
        return PyErr_NoMemory();
    }
    Py_BEGIN_ALLOW_THREADS
    block_inverse_loop(b[0].buf, n, size, b[1].buf, b[2].buf, b[3].buf, b[4].buf, h, b[5].buf,
                       scratch);
    Py_END_ALLOW_THREADS
    free(scratch);
    release(b, 6);
    Py_RETURN_NONE;
}

/* --- tree placements (docs/model.md §11) ------------------------------------------------- */
static void tree_placements_loop(const double *C, const double *S, idx n, idx nq,
                                 const int64_t *parent, const int64_t *axis,
                                 const int64_t *idx_q, const double *M_rot,
                                 const double *M_trans, idx J, double *R, double *o)
{
    double B[9];
    for (idx s = 0; s < n; s++) {
        for (int a = 0; a < 3; a++) {
            o[s * 3 + a] = 0.0;
            for (int b = 0; b < 3; b++)
                R[s * 9 + a * 3 + b] = a == b ? 1.0 : 0.0;
        }
    }
    for (idx j = 0; j < J; j++) { /* joint by joint: each pass streams through its parent's */
        idx p = parent[j], ax = axis[j];
        idx i1 = (ax + 1) % 3, i2 = (ax + 2) % 3;
        const double *Mr = M_rot + j * 9, *Mt = M_trans + j * 3;
        for (idx s = 0; s < n; s++) {
            double c = C[s * nq + idx_q[j]], sn = S[s * nq + idx_q[j]];
            const double *Rp = R + (p * n + s) * 9, *op = o + (p * n + s) * 3;
            double *Rj = R + ((j + 1) * n + s) * 9, *oj = o + ((j + 1) * n + s) * 3;
            for (int a = 0; a < 3; a++) {
                double acc = 0.0;
                for (int b = 0; b < 3; b++) {
                    B[a * 3 + b] = Rp[a * 3] * Mr[b] + Rp[a * 3 + 1] * Mr[3 + b]
                                   + Rp[a * 3 + 2] * Mr[6 + b];
                    acc += Rp[a * 3 + b] * Mt[b];
                }
                oj[a] = op[a] + acc;
                /* B · R_axis(q): the axis column stays, the other two turn by q */
                Rj[a * 3 + ax] = B[a * 3 + ax];
                Rj[a * 3 + i1] = B[a * 3 + i1] * c + B[a * 3 + i2] * sn;
                Rj[a * 3 + i2] = B[a * 3 + i2] * c - B[a * 3 + i1] * sn;
            }
        }
    }
}

static PyObject *tree_placements(PyObject *self, PyObject *args)
{
    Py_buffer b[9] = {{0}};
    idx n, nq, J;
    if (!PyArg_ParseTuple(args, "y*y*nny*y*y*y*y*nw*w*", &b[0], &b[1], &n, &nq, &b[2], &b[3],
                          &b[4], &b[5], &b[6], &J, &b[7], &b[8]))
        return NULL;
    int ok = check_len(&b[0], n * nq, "C") && check_len(&b[1], n * nq, "S")
             && check_len(&b[2], J, "parent") && check_len(&b[3], J, "axis")
             && check_len(&b[4], J, "idx_q") && check_len(&b[5], 9 * J, "M_rot")
             && check_len(&b[6], 3 * J, "M_trans") && check_len(&b[7], (J + 1) * n * 9, "R")
             && check_len(&b[8], (J + 1) * n * 3, "o") && check_range(&b[3], 0, 3, "axis")
             && check_range(&b[4], 0, nq, "idx_q");
    const int64_t *parent = b[2].buf;
    for (idx j = 0; ok && j < J; j++)
        if (parent[j] < 0 || parent[j] > j) { /* a slot already placed: the base or before */
            PyErr_Format(PyExc_ValueError, "kernels: parent[%zd] = %lld is not a slot placed "
                         "before joint slot %zd", j, (long long)parent[j], j + 1);
            ok = 0;
        }
    if (!ok) {
        release(b, 9);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    tree_placements_loop(b[0].buf, b[1].buf, n, nq, b[2].buf, b[3].buf, b[4].buf, b[5].buf,
                         b[6].buf, J, b[7].buf, b[8].buf);
    Py_END_ALLOW_THREADS
    release(b, 9);
    Py_RETURN_NONE;
}

/* --- point Jacobians (docs/model.md §11) ------------------------------------------------- */
static void point_jacobians_loop(const double *R, const double *o, idx S, idx n,
                                 const int64_t *axis, const int64_t *col, const int64_t *pt_slot,
                                 const double *pt_local, const int64_t *pt_support, idx depth,
                                 const int64_t *pt_row, const double *pt_sign, idx P,
                                 idx ang_point, idx ang_row, idx nv, double *K, double *pos)
{
    idx rows = ang_row + 3;
    memset(K, 0, sizeof(double) * n * rows * nv);
    for (idx s = 0; s < n; s++) {
        double *Ks = K + s * rows * nv;
        for (idx i = 0; i < P; i++) {
            idx b = pt_slot[i], row = pt_row[i];
            double sign = pt_sign[i];
            const double *Rb = R + (b * n + s) * 9, *ob = o + (b * n + s) * 3,
                         *loc = pt_local + i * 3;
            double *x = pos + (s * P + i) * 3;
            for (int a = 0; a < 3; a++)
                x[a] = Rb[a * 3] * loc[0] + Rb[a * 3 + 1] * loc[1] + Rb[a * 3 + 2] * loc[2]
                       + ob[a];
            for (idx m = 0; m < depth; m++) {
                idx c = pt_support[i * depth + m];
                if (c < 0)
                    break;
                idx ax = axis[c], v = col[c];
                const double *Rc = R + (c * n + s) * 9, *oc = o + (c * n + s) * 3;
                double z0 = Rc[ax], z1 = Rc[3 + ax], z2 = Rc[6 + ax];
                double d0 = x[0] - oc[0], d1 = x[1] - oc[1], d2 = x[2] - oc[2];
                Ks[row * nv + v] += sign * (z1 * d2 - z2 * d1);
                Ks[(row + 1) * nv + v] += sign * (z2 * d0 - z0 * d2);
                Ks[(row + 2) * nv + v] += sign * (z0 * d1 - z1 * d0);
                if (i == ang_point)
                    for (int a = 0; a < 3; a++)
                        Ks[(ang_row + a) * nv + v] = Rc[a * 3 + ax];
            }
        }
    }
}

static PyObject *point_jacobians(PyObject *self, PyObject *args)
{
    Py_buffer b[11] = {{0}};
    idx S, n, depth, P, ang_point, ang_row, nv;
    if (!PyArg_ParseTuple(args, "y*y*nny*y*y*y*y*ny*y*nnnnw*w*", &b[0], &b[1], &S, &n, &b[2],
                          &b[3], &b[4], &b[5], &b[6], &depth, &b[7], &b[8], &P, &ang_point,
                          &ang_row, &nv, &b[9], &b[10]))
        return NULL;
    int ok = check_len(&b[0], S * n * 9, "R") && check_len(&b[1], S * n * 3, "o")
             && check_len(&b[2], S, "axis") && check_len(&b[3], S, "col")
             && check_len(&b[4], P, "pt_slot") && check_len(&b[5], 3 * P, "pt_local")
             && check_len(&b[6], P * depth, "pt_support") && check_len(&b[7], P, "pt_row")
             && check_len(&b[8], P, "pt_sign") && check_len(&b[9], n * (ang_row + 3) * nv, "K")
             && check_len(&b[10], n * P * 3, "pos") && check_range(&b[2], 0, 3, "axis")
             && check_range(&b[3], 0, nv, "col") && check_range(&b[4], 0, S, "pt_slot")
             && check_range(&b[6], -1, S, "pt_support")
             && check_range(&b[7], 0, ang_row + 1, "pt_row"); /* its 3 rows within K's */
    if (!ok) {
        release(b, 11);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    point_jacobians_loop(b[0].buf, b[1].buf, S, n, b[2].buf, b[3].buf, b[4].buf, b[5].buf,
                         b[6].buf, depth, b[7].buf, b[8].buf, P, ang_point, ang_row, nv,
                         b[9].buf, b[10].buf);
    Py_END_ALLOW_THREADS
    release(b, 11);
    Py_RETURN_NONE;
}

/* --- point drifts (docs/model.md §11) ---------------------------------------------------- */
static inline void cross3(const double *a, const double *b, double *out)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void point_drifts_loop(const double *R, const double *o, idx S, idx n,
                              const int64_t *parent, const int64_t *axis, const int64_t *col,
                              const double *V, idx nv, const int64_t *pt_slot,
                              const int64_t *pt_row, const double *pt_sign, const double *pos,
                              idx P, idx ang_point, idx ang_row, double *drift, double *omega,
                              double *work)
{
    idx rows = ang_row + 3;
    double *w = work, *al = w + 3 * S, *acc = al + 3 * S;
    double r[3], t1[3], t2[3];
    memset(work, 0, sizeof(double) * 9 * S);
    memset(drift, 0, sizeof(double) * n * rows);
    for (idx s = 0; s < n; s++) {
        for (int a = 0; a < 3; a++)
            omega[s * 3 + a] = 0.0;
        for (idx j = 1; j < S; j++) {
            idx p = parent[j];
            const double *oj = o + (j * n + s) * 3, *op = o + (p * n + s) * 3;
            for (int a = 0; a < 3; a++)
                r[a] = oj[a] - op[a];
            cross3(al + 3 * p, r, t1);
            cross3(w + 3 * p, r, t2);
            cross3(w + 3 * p, t2, r); /* ω_p × (ω_p × r), r no longer needed */
            double qd = V[s * nv + col[j]];
            idx ax = axis[j];
            const double *Rj = R + (j * n + s) * 9;
            for (int a = 0; a < 3; a++) {
                acc[3 * j + a] = acc[3 * p + a] + t1[a] + r[a];
                t1[a] = Rj[a * 3 + ax]; /* z_j */
            }
            cross3(w + 3 * p, t1, t2);
            for (int a = 0; a < 3; a++) {
                al[3 * j + a] = al[3 * p + a] + t2[a] * qd;
                w[3 * j + a] = w[3 * p + a] + t1[a] * qd;
                omega[(j * n + s) * 3 + a] = w[3 * j + a];
            }
        }
        double *ds = drift + s * rows;
        for (idx i = 0; i < P; i++) {
            idx b = pt_slot[i], row = pt_row[i];
            double sign = pt_sign[i];
            const double *x = pos + (s * P + i) * 3, *ob = o + (b * n + s) * 3;
            for (int a = 0; a < 3; a++)
                r[a] = x[a] - ob[a];
            cross3(al + 3 * b, r, t1);
            cross3(w + 3 * b, r, t2);
            cross3(w + 3 * b, t2, r);
            for (int a = 0; a < 3; a++)
                ds[row + a] += sign * (acc[3 * b + a] + t1[a] + r[a]);
        }
        for (int a = 0; a < 3; a++)
            ds[ang_row + a] = al[3 * pt_slot[ang_point] + a];
    }
}

static PyObject *point_drifts(PyObject *self, PyObject *args)
{
    Py_buffer b[12] = {{0}};
    idx S, n, nv, P, ang_point, ang_row;
    if (!PyArg_ParseTuple(args, "y*y*nny*y*y*y*ny*y*y*y*nnnw*w*", &b[0], &b[1], &S, &n, &b[2],
                          &b[3], &b[4], &b[5], &nv, &b[6], &b[7], &b[8], &b[9], &P, &ang_point,
                          &ang_row, &b[10], &b[11]))
        return NULL;
    int ok = check_len(&b[0], S * n * 9, "R") && check_len(&b[1], S * n * 3, "o")
             && check_len(&b[2], S, "parent") && check_len(&b[3], S, "axis")
             && check_len(&b[4], S, "col") && check_len(&b[5], n * nv, "V")
             && check_len(&b[6], P, "pt_slot") && check_len(&b[7], P, "pt_row")
             && check_len(&b[8], P, "pt_sign") && check_len(&b[9], n * P * 3, "pos")
             && check_len(&b[10], n * (ang_row + 3), "drift")
             && check_len(&b[11], S * n * 3, "omega") && check_range(&b[2], 0, S, "parent")
             && check_range(&b[3], 0, 3, "axis") && check_range(&b[4], 0, nv, "col")
             && check_range(&b[6], 0, S, "pt_slot")
             && check_range(&b[7], 0, ang_row + 1, "pt_row");
    if (ok && (ang_point < 0 || ang_point >= P)) {
        PyErr_Format(PyExc_ValueError, "kernels: ang_point = %zd is outside [0, %zd)",
                     ang_point, P);
        ok = 0;
    }
    double *work = ok ? malloc(sizeof(double) * (9 * S + 1)) : NULL;
    if (ok && work == NULL) {
        PyErr_NoMemory();
        ok = 0;
    }
    if (!ok) {
        release(b, 12);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    point_drifts_loop(b[0].buf, b[1].buf, S, n, b[2].buf, b[3].buf, b[4].buf, b[5].buf, nv,
                      b[6].buf, b[7].buf, b[8].buf, b[9].buf, P, ang_point, ang_row, b[10].buf,
                      b[11].buf, work);
    Py_END_ALLOW_THREADS
    free(work);
    release(b, 12);
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"gram_extremes", gram_extremes, METH_VARARGS, "A, n, m, k, lo, hi"},
    {"block_inverse", block_inverse, METH_VARARGS,
     "K, n, size, top, bottom, first, second, h, out"},
    {"tree_placements", tree_placements, METH_VARARGS,
     "C, S, n, nq, parent, axis, idx_q, M_rot, M_trans, J, R, o"},
    {"point_jacobians", point_jacobians, METH_VARARGS,
     "R, o, S, n, axis, col, pt_slot, pt_local, pt_support, depth, pt_row, pt_sign, P, "
     "ang_point, ang_row, nv, K, pos"},
    {"point_drifts", point_drifts, METH_VARARGS,
     "R, o, S, n, parent, axis, col, V, nv, pt_slot, pt_row, pt_sign, pos, P, ang_point, "
     "ang_row, drift, omega"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_kernels",
    "The compiled loops behind pollard_pin.kinematics.kernels (use that module).", -1, methods,
};

PyMODINIT_FUNC PyInit__kernels(void) { return PyModule_Create(&module); }
