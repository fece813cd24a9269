/* The argument checks of both compiled modules (checks.h), before the GIL is released. */
#include "checks.h"

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
