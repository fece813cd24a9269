/* The compiled kernels behind pollard_pin.kinematics.kernels (C, built when the package is
 * installed; setup.py): the loops over samples, with the GIL released. kernels.py is the typed
 * front: it makes every array C-contiguous float64 / int64, allocates the outputs and documents
 * the mathematics (docs/model.md §11–§12); this code checks sizes and indices, then computes.
 *
 * module.c: the argument checks and the module; linalg.c: Gram extremes and the block inverse;
 * tree.c: placements, point Jacobians and drifts. Every function takes buffers (read-only "y*",
 * written "w*") and their dimensions. */
#ifndef POLLARD_KERNELS_H
#define POLLARD_KERNELS_H
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>

typedef Py_ssize_t idx;

/* argument checks (module.c), before the GIL is released: 0 with a ValueError set */
int pk_check_len(const Py_buffer *b, idx count, const char *what);
int pk_check_range(const Py_buffer *b, idx lo, idx hi, const char *what);
void pk_release(Py_buffer *bufs, int count);

/* the kernels (linalg.c, tree.c) */
PyObject *pk_gram_extremes(PyObject *self, PyObject *args);
PyObject *pk_block_inverse(PyObject *self, PyObject *args);
PyObject *pk_tree_placements(PyObject *self, PyObject *args);
PyObject *pk_point_jacobians(PyObject *self, PyObject *args);
PyObject *pk_point_drifts(PyObject *self, PyObject *args);

#endif
