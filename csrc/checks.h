/* The argument checks both compiled modules make before they release the GIL (checks.c):
 * each returns 0 with a ValueError set when a buffer does not fit. */
#ifndef POLLARD_CHECKS_H
#define POLLARD_CHECKS_H
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>

typedef Py_ssize_t idx;

int pk_check_len(const Py_buffer *b, idx count, const char *what);  /* count float64/int64 */
int pk_check_range(const Py_buffer *b, idx lo, idx hi, const char *what);  /* int64 in [lo, hi) */
void pk_release(Py_buffer *bufs, int count);

#endif
