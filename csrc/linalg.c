/* Gram extremes (docs/model.md §12) and the block-triangular inverse (§11): small dense
 * linear algebra per sample (kernels.h). */
#include "kernels.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define EPS DBL_EPSILON
#define PSD_SLACK 1e-12 /* relative: round-off may push λ_min(T) of a singular Gram below 0 */
#define MAX_STEPS 100   /* Laguerre steps: a handful for a simple root, linear at a multiple one */

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

void gram_extremes_loop(const double *A, idx n, idx m, idx k, double *lo, double *hi,
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

PyObject *pk_gram_extremes(PyObject *self, PyObject *args)
{
    Py_buffer b[3] = {{0}};
    idx n, m, k;
    if (!PyArg_ParseTuple(args, "y*nnnw*w*", &b[0], &n, &m, &k, &b[1], &b[2]))
        return NULL;
    if (!(pk_check_len(&b[0], n * m * k, "A") && pk_check_len(&b[1], n, "lo")
          && pk_check_len(&b[2], n, "hi"))) {
        pk_release(b, 3);
        return NULL;
    }
    idx k1 = k > 1 ? k - 1 : 1;
    double *work = malloc(sizeof(double) * (k * k + 3 * k + 2 * k1 + 1));
    if (work == NULL) {
        pk_release(b, 3);
        return PyErr_NoMemory();
    }
    Py_BEGIN_ALLOW_THREADS
    gram_extremes_loop(b[0].buf, n, m, k, b[1].buf, b[2].buf, work);
    Py_END_ALLOW_THREADS
    free(work);
    pk_release(b, 3);
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
        double best;
        idx pivot = pk_pivot(work, w, c, k, &best);
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

PyObject *pk_block_inverse(PyObject *self, PyObject *args)
{
    Py_buffer b[6] = {{0}};
    idx n, size, h;
    if (!PyArg_ParseTuple(args, "y*nny*y*y*y*nw*", &b[0], &n, &size, &b[1], &b[2], &b[3],
                          &b[4], &h, &b[5]))
        return NULL;
    static const char *names[] = {"top", "bottom", "first", "second"};
    int ok = pk_check_len(&b[0], n * size * size, "K")
             && pk_check_len(&b[5], n * size * size, "out");
    for (int i = 0; ok && i < 4; i++)
        ok = pk_check_len(&b[1 + i], h, names[i])
             && pk_check_range(&b[1 + i], 0, size, names[i]);
    if (!ok) {
        pk_release(b, 6);
        return NULL;
    }
    double *scratch = malloc(sizeof(double) * (7 * h * h + 1));
    if (scratch == NULL) {
        pk_release(b, 6);
        return PyErr_NoMemory();
    }
    Py_BEGIN_ALLOW_THREADS
    block_inverse_loop(b[0].buf, n, size, b[1].buf, b[2].buf, b[3].buf, b[4].buf, h, b[5].buf,
                       scratch);
    Py_END_ALLOW_THREADS
    free(scratch);
    pk_release(b, 6);
    Py_RETURN_NONE;
}

