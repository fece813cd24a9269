/* Forward passes over the model tree per sample (docs/model.md §11): joint placements, the
 * point Jacobians K and their drifts K̇v (kernels.h). */
#include "kernels.h"

#include <stdlib.h>
#include <string.h>

/* --- tree placements (docs/model.md §11) ------------------------------------------------- */
void tree_placements_loop(const double *C, const double *S, idx n, idx nq,
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

PyObject *pk_tree_placements(PyObject *self, PyObject *args)
{
    Py_buffer b[9] = {{0}};
    idx n, nq, J;
    if (!PyArg_ParseTuple(args, "y*y*nny*y*y*y*y*nw*w*", &b[0], &b[1], &n, &nq, &b[2], &b[3],
                          &b[4], &b[5], &b[6], &J, &b[7], &b[8]))
        return NULL;
    int ok = pk_check_len(&b[0], n * nq, "C") && pk_check_len(&b[1], n * nq, "S")
             && pk_check_len(&b[2], J, "parent") && pk_check_len(&b[3], J, "axis")
             && pk_check_len(&b[4], J, "idx_q") && pk_check_len(&b[5], 9 * J, "M_rot")
             && pk_check_len(&b[6], 3 * J, "M_trans") && pk_check_len(&b[7], (J + 1) * n * 9, "R")
             && pk_check_len(&b[8], (J + 1) * n * 3, "o") && pk_check_range(&b[3], 0, 3, "axis")
             && pk_check_range(&b[4], 0, nq, "idx_q");
    const int64_t *parent = b[2].buf;
    for (idx j = 0; ok && j < J; j++)
        if (parent[j] < 0 || parent[j] > j) { /* a slot already placed: the base or before */
            PyErr_Format(PyExc_ValueError, "kernels: parent[%zd] = %lld is not a slot placed "
                         "before joint slot %zd", j, (long long)parent[j], j + 1);
            ok = 0;
        }
    if (!ok) {
        pk_release(b, 9);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    tree_placements_loop(b[0].buf, b[1].buf, n, nq, b[2].buf, b[3].buf, b[4].buf, b[5].buf,
                         b[6].buf, J, b[7].buf, b[8].buf);
    Py_END_ALLOW_THREADS
    pk_release(b, 9);
    Py_RETURN_NONE;
}

/* --- point Jacobians (docs/model.md §11) ------------------------------------------------- */
void point_jacobians_loop(const double *R, const double *o, idx S, idx n,
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

PyObject *pk_point_jacobians(PyObject *self, PyObject *args)
{
    Py_buffer b[11] = {{0}};
    idx S, n, depth, P, ang_point, ang_row, nv;
    if (!PyArg_ParseTuple(args, "y*y*nny*y*y*y*y*ny*y*nnnnw*w*", &b[0], &b[1], &S, &n, &b[2],
                          &b[3], &b[4], &b[5], &b[6], &depth, &b[7], &b[8], &P, &ang_point,
                          &ang_row, &nv, &b[9], &b[10]))
        return NULL;
    int ok = pk_check_len(&b[0], S * n * 9, "R") && pk_check_len(&b[1], S * n * 3, "o")
             && pk_check_len(&b[2], S, "axis") && pk_check_len(&b[3], S, "col")
             && pk_check_len(&b[4], P, "pt_slot") && pk_check_len(&b[5], 3 * P, "pt_local")
             && pk_check_len(&b[6], P * depth, "pt_support") && pk_check_len(&b[7], P, "pt_row")
             && pk_check_len(&b[8], P, "pt_sign")
             && pk_check_len(&b[9], n * (ang_row + 3) * nv, "K")
             && pk_check_len(&b[10], n * P * 3, "pos") && pk_check_range(&b[2], 0, 3, "axis")
             && pk_check_range(&b[3], 0, nv, "col") && pk_check_range(&b[4], 0, S, "pt_slot")
             && pk_check_range(&b[6], -1, S, "pt_support")
             && pk_check_range(&b[7], 0, ang_row + 1, "pt_row"); /* its 3 rows within K's */
    if (!ok) {
        pk_release(b, 11);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    point_jacobians_loop(b[0].buf, b[1].buf, S, n, b[2].buf, b[3].buf, b[4].buf, b[5].buf,
                         b[6].buf, depth, b[7].buf, b[8].buf, P, ang_point, ang_row, nv,
                         b[9].buf, b[10].buf);
    Py_END_ALLOW_THREADS
    pk_release(b, 11);
    Py_RETURN_NONE;
}

/* --- point drifts (docs/model.md §11) ---------------------------------------------------- */
static inline void cross3(const double *a, const double *b, double *out)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

void point_drifts_loop(const double *R, const double *o, idx S, idx n,
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

PyObject *pk_point_drifts(PyObject *self, PyObject *args)
{
    Py_buffer b[12] = {{0}};
    idx S, n, nv, P, ang_point, ang_row;
    if (!PyArg_ParseTuple(args, "y*y*nny*y*y*y*ny*y*y*y*nnnw*w*", &b[0], &b[1], &S, &n, &b[2],
                          &b[3], &b[4], &b[5], &nv, &b[6], &b[7], &b[8], &b[9], &P, &ang_point,
                          &ang_row, &b[10], &b[11]))
        return NULL;
    int ok = pk_check_len(&b[0], S * n * 9, "R") && pk_check_len(&b[1], S * n * 3, "o")
             && pk_check_len(&b[2], S, "parent") && pk_check_len(&b[3], S, "axis")
             && pk_check_len(&b[4], S, "col") && pk_check_len(&b[5], n * nv, "V")
             && pk_check_len(&b[6], P, "pt_slot") && pk_check_len(&b[7], P, "pt_row")
             && pk_check_len(&b[8], P, "pt_sign") && pk_check_len(&b[9], n * P * 3, "pos")
             && pk_check_len(&b[10], n * (ang_row + 3), "drift")
             && pk_check_len(&b[11], S * n * 3, "omega") && pk_check_range(&b[2], 0, S, "parent")
             && pk_check_range(&b[3], 0, 3, "axis") && pk_check_range(&b[4], 0, nv, "col")
             && pk_check_range(&b[6], 0, S, "pt_slot")
             && pk_check_range(&b[7], 0, ang_row + 1, "pt_row");
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
        pk_release(b, 12);
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    point_drifts_loop(b[0].buf, b[1].buf, S, n, b[2].buf, b[3].buf, b[4].buf, b[5].buf, nv,
                      b[6].buf, b[7].buf, b[8].buf, b[9].buf, P, ang_point, ang_row, b[10].buf,
                      b[11].buf, work);
    Py_END_ALLOW_THREADS
    free(work);
    pk_release(b, 12);
    Py_RETURN_NONE;
}

