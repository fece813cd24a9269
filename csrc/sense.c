/* A control tick's closed-loop state in one call (docs/model.md §4, §11, §12, §18): the
 * passive angles for measured actuator angles by Newton on the closures (as
 * kinematics/closure.py's close_loops), then the constraint Jacobian Jc, the velocity map N,
 * the rates v = N θ̇ and the tree acceleration a₀ at θ̈ = 0 on the loops, from the tree passes
 * of tree.c (kernels.h). */
#include "kernels.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* LU with partial pivoting of A (k × k, overwritten), as LAPACK's dgetrf: 0 at an exactly zero
 * pivot (singular A). */
static int lu_factor(double *A, idx k, idx *piv)
{
    for (idx c = 0; c < k; c++) {
        double best;
        idx p = pk_pivot(A, k, c, k, &best);
        piv[c] = p;
        if (best == 0.0)
            return 0;
        if (p != c)
            for (idx j = 0; j < k; j++) {
                double t = A[c * k + j];
                A[c * k + j] = A[p * k + j];
                A[p * k + j] = t;
            }
        double inv = 1.0 / A[c * k + c];
        for (idx r = c + 1; r < k; r++) {
            double f = A[r * k + c] * inv;
            A[r * k + c] = f;
            for (idx j = c + 1; j < k; j++)
                A[r * k + j] -= f * A[c * k + j];
        }
    }
    return 1;
}

/* x ← A⁻¹ x with the factors of lu_factor. */
static void lu_solve(const double *LU, idx k, const idx *piv, double *x)
{
    for (idx c = 0; c < k; c++) {
        double t = x[c];
        x[c] = x[piv[c]];
        x[piv[c]] = t;
    }
    for (idx r = 1; r < k; r++)
        for (idx j = 0; j < r; j++)
            x[r] -= LU[r * k + j] * x[j];
    for (idx r = k - 1; r >= 0; r--) {
        for (idx j = r + 1; j < k; j++)
            x[r] -= LU[r * k + j] * x[j];
        x[r] /= LU[r * k + r];
    }
}

typedef struct {
    const int64_t *parent, *axis, *idx_q, *col, *pt_slot, *pt_support, *pt_row, *ia, *ip;
    const double *M_rot, *M_trans, *pt_local, *pt_sign;
    idx S, P, depth, ang_point, ang_row, nq, nv, m;
} layout;

/* Placements R, o, K and the points at q; r = the closure rows of Σ sign·p (p_A − p_B), Jp =
 * K[:m, ip]. */
static void kinematics(const layout *L, const double *q, double *R, double *o, double *K,
                       double *pos, double *r, double *Jp, double *cs)
{
    idx nq = L->nq, rows = L->ang_row + 3;
    for (idx i = 0; i < nq; i++) {
        cs[i] = cos(q[i]);
        cs[nq + i] = sin(q[i]);
    }
    tree_placements_loop(cs, cs + nq, 1, nq, L->parent + 1, L->axis + 1, L->idx_q + 1,
                         L->M_rot + 9, L->M_trans + 3, L->S - 1, R, o);
    point_jacobians_loop(R, o, L->S, 1, L->axis, L->col, L->pt_slot, L->pt_local,
                         L->pt_support, L->depth, L->pt_row, L->pt_sign, L->P, L->ang_point,
                         L->ang_row, L->nv, K, pos);
    memset(r, 0, sizeof(double) * rows);
    for (idx i = 0; i < L->P; i++)
        for (int a = 0; a < 3; a++)
            r[L->pt_row[i] + a] += L->pt_sign[i] * pos[i * 3 + a];
    for (idx i = 0; i < L->m; i++)
        for (idx j = 0; j < L->m; j++)
            Jp[i * L->m + j] = K[i * L->nv + L->ip[j]];
}

/* The Newton steps taken (>= 0), or −1 (not converged in max_iter steps, or not finite), −2
 * (Jp exactly singular on the way), −3 (Jp exactly singular at the solution): the caller then
 * takes the reference path, which says why. */
static idx closed_state(const layout *L, const double *theta, const double *dtheta,
                        const double *guess, double tol, idx max_iter, double *q, double *v,
                        double *Jc, double *N, double *a0, double *lohi, double *work)
{
    idx S = L->S, nv = L->nv, m = L->m, rows = L->ang_row + 3, k1 = m > 1 ? m - 1 : 1;
    double *R = work, *o = R + 9 * S, *K = o + 3 * S, *pos = K + rows * nv,
           *r = pos + 3 * L->P, *Jp = r + rows, *LU = Jp + m * m, *x = LU + m * m,
           *cs = x + m, *drift = cs + 2 * L->nq, *omega = drift + rows, *dw = omega + 3 * S,
           *gw = dw + 9 * S + 1;
    idx *piv = (idx *)(gw + m * m + 3 * m + 2 * k1 + 1);
    double sum = 0.0; /* a finite sum: every input finite (one of them may move no closure) */
    for (idx i = 0; i < m; i++)
        sum += theta[i] + dtheta[i];
    for (idx i = 0; i < L->nq; i++)
        sum += guess[i];
    if (!isfinite(sum))
        return -1;
    memcpy(q, guess, sizeof(double) * L->nq);
    for (idx i = 0; i < m; i++)
        q[L->ia[i]] = theta[i];
    kinematics(L, q, R, o, K, pos, r, Jp, cs);
    idx steps = 0;
    for (;;) {
        double worst = 0.0;
        for (idx i = 0; i < m; i++)
            worst = fabs(r[i]) > worst || isnan(r[i]) ? fabs(r[i]) : worst;
        if (!isfinite(worst))
            return -1;
        if (worst <= tol)
            break;
        if (steps == max_iter)
            return -1;
        memcpy(LU, Jp, sizeof(double) * m * m);
        if (!lu_factor(LU, m, piv))
            return -2;
        memcpy(x, r, sizeof(double) * m);
        lu_solve(LU, m, piv, x);
        double big = 1e-300; /* damped: no passive angle moves by more than 0.5 rad at once */
        for (idx i = 0; i < m; i++)
            big = fabs(x[i]) > big ? fabs(x[i]) : big;
        double scale = 0.5 / big < 1.0 ? 0.5 / big : 1.0;
        for (idx i = 0; i < m; i++)
            q[L->ip[i]] -= x[i] * scale;
        steps++;
        kinematics(L, q, R, o, K, pos, r, Jp, cs);
    }
    gram_extremes_loop(Jp, 1, m, m, lohi, lohi + 1, gw);
    memcpy(LU, Jp, sizeof(double) * m * m);
    if (!lu_factor(LU, m, piv))
        return -3;
    memcpy(Jc, K, sizeof(double) * m * nv);
    memset(N, 0, sizeof(double) * nv * m);
    for (idx j = 0; j < m; j++) { /* N[ip, j] = −Jp⁻¹ Jc[:, ia[j]], N[ia] = I */
        for (idx i = 0; i < m; i++)
            x[i] = K[i * nv + L->ia[j]];
        lu_solve(LU, m, piv, x);
        for (idx i = 0; i < m; i++)
            N[L->ip[i] * m + j] = -x[i];
        N[L->ia[j] * m + j] = 1.0;
    }
    for (idx i = 0; i < nv; i++) {
        double acc = 0.0;
        for (idx j = 0; j < m; j++)
            acc += N[i * m + j] * dtheta[j];
        v[i] = acc;
    }
    point_drifts_loop(R, o, S, 1, L->parent, L->axis, L->col, v, nv, L->pt_slot, L->pt_row,
                      L->pt_sign, pos, L->P, L->ang_point, L->ang_row, drift, omega, dw);
    memcpy(x, drift, sizeof(double) * m); /* Jc a₀ = −J̇c v with a₀ = 0 on the actuators */
    lu_solve(LU, m, piv, x);
    memset(a0, 0, sizeof(double) * nv);
    for (idx i = 0; i < m; i++)
        a0[L->ip[i]] = -x[i];
    return steps;
}

PyObject *pk_closed_state(PyObject *self, PyObject *args)
{
    Py_buffer b[22] = {{0}};
    layout L;
    double tol;
    idx max_iter;
    if (!PyArg_ParseTuple(args, "y*y*y*y*y*y*y*y*y*y*y*y*y*nnnnnnnny*y*y*dnw*w*w*w*w*w*",
                          &b[0], &b[1], &b[2], &b[3], &b[4], &b[5], &b[6], &b[7], &b[8], &b[9],
                          &b[10], &b[11], &b[12], &L.S, &L.P, &L.depth, &L.ang_point,
                          &L.ang_row, &L.nq, &L.nv, &L.m, &b[13], &b[14], &b[15], &tol,
                          &max_iter, &b[16], &b[17], &b[18], &b[19], &b[20], &b[21]))
        return NULL;
    idx S = L.S, P = L.P, nq = L.nq, nv = L.nv, m = L.m, rows = L.ang_row + 3;
    int ok = S >= 1 && P >= 1 && L.depth >= 0 && m >= 1 && m <= L.ang_row && nq >= 1
             && nv >= m;
    if (!ok)
        PyErr_SetString(PyExc_ValueError, "kernels: closed_state sizes out of range");
    ok = ok && pk_check_len(&b[0], S, "parent") && pk_check_len(&b[1], S, "axis")
         && pk_check_len(&b[2], S, "idx_q") && pk_check_len(&b[3], S, "col")
         && pk_check_len(&b[4], 9 * S, "M_rot") && pk_check_len(&b[5], 3 * S, "M_trans")
         && pk_check_len(&b[6], P, "pt_slot") && pk_check_len(&b[7], 3 * P, "pt_local")
         && pk_check_len(&b[8], P * L.depth, "pt_support") && pk_check_len(&b[9], P, "pt_row")
         && pk_check_len(&b[10], P, "pt_sign") && pk_check_len(&b[11], m, "ia")
         && pk_check_len(&b[12], m, "ip") && pk_check_len(&b[13], m, "theta")
         && pk_check_len(&b[14], m, "dtheta") && pk_check_len(&b[15], nq, "guess")
         && pk_check_len(&b[16], nq, "q") && pk_check_len(&b[17], nv, "v")
         && pk_check_len(&b[18], m * nv, "Jc") && pk_check_len(&b[19], nv * m, "N")
         && pk_check_len(&b[20], nv, "a0") && pk_check_len(&b[21], 2, "lohi")
         && pk_check_range(&b[0], 0, S, "parent") && pk_check_range(&b[1], 0, 3, "axis")
         && pk_check_range(&b[2], 0, nq, "idx_q") && pk_check_range(&b[3], 0, nv, "col")
         && pk_check_range(&b[6], 0, S, "pt_slot") && pk_check_range(&b[8], -1, S, "pt_support")
         && pk_check_range(&b[9], 0, rows - 2, "pt_row") /* its 3 rows within K's */
         && pk_check_range(&b[11], 0, nv < nq ? nv : nq, "ia")
         && pk_check_range(&b[12], 0, nv < nq ? nv : nq, "ip");
    const int64_t *parent = b[0].buf;
    for (idx j = 1; ok && j < S; j++)
        if (parent[j] >= j) { /* a slot placed before it: the base or an earlier joint */
            PyErr_Format(PyExc_ValueError, "kernels: parent[%zd] = %lld is not a slot placed "
                         "before it", j, (long long)parent[j]);
            ok = 0;
        }
    if (ok && (L.ang_point < 0 || L.ang_point >= P)) {
        PyErr_Format(PyExc_ValueError, "kernels: ang_point = %zd is outside [0, %zd)",
                     L.ang_point, P);
        ok = 0;
    }
    idx k1 = m > 1 ? m - 1 : 1;
    size_t doubles = 9 * S + 3 * S + rows * nv + 3 * P + rows + 2 * m * m + m + 2 * nq + rows
                     + 3 * S + 9 * S + 1 + m * m + 3 * m + 2 * k1 + 1;
    double *work = ok ? malloc(sizeof(double) * doubles + sizeof(idx) * m) : NULL;
    if (ok && work == NULL) {
        PyErr_NoMemory();
        ok = 0;
    }
    if (!ok) {
        pk_release(b, 22);
        return NULL;
    }
    L.parent = b[0].buf, L.axis = b[1].buf, L.idx_q = b[2].buf, L.col = b[3].buf;
    L.M_rot = b[4].buf, L.M_trans = b[5].buf, L.pt_slot = b[6].buf, L.pt_local = b[7].buf;
    L.pt_support = b[8].buf, L.pt_row = b[9].buf, L.pt_sign = b[10].buf;
    L.ia = b[11].buf, L.ip = b[12].buf;
    idx steps;
    /* one sample of a few µs: the GIL is kept (releasing it costs more than it frees) */
    steps = closed_state(&L, b[13].buf, b[14].buf, b[15].buf, tol, max_iter, b[16].buf,
                         b[17].buf, b[18].buf, b[19].buf, b[20].buf, b[21].buf, work);
    free(work);
    pk_release(b, 22);
    return PyLong_FromSsize_t(steps);
}
