"""Second-order truncated Taylor jets: exact forward-mode derivatives along time.

A :class:`Jet` holds ``(v, d, dd)`` = (value, first, second time derivative) of an array
quantity; ``dd`` may be None (first-order jet, half the work, used for Jacobians). Arithmetic
and the elementary functions propagate them by the chain rule (Leibniz rule for products), so the
IK closed forms of docs/model.md §7 give exact velocities and
accelerations with no finite differences.

Shapes: ``d`` and ``dd`` need only broadcast against ``v``. This lets one value carry many
derivative directions: ``v`` of shape (N, 1, ...) with ``d`` of shape (N, K, ...) is K
directional derivatives of the same N samples (used for Jacobians). ``v``, ``d`` and ``dd``
always have the same number of dimensions.

Every helper below (``sin``, ``stack``, ``matvec``, ``Rx`` ...) also accepts plain numpy arrays
and then returns plain arrays, so the same closed-form code serves positions only (fast) and
jets. ``A @ B`` on jets multiplies trailing 3x3 matrices; the right operand is a 3-vector when it
is a jet with one dimension fewer than the left one, or a 1-D array; otherwise use
:func:`matvec` to be explicit.
"""
from __future__ import annotations

import numpy as np

__all__ = ["Jet", "value", "sin", "cos", "sqrt", "atan2", "asin", "acos", "stack", "matvec",
           "transpose", "cross", "dot", "Rx", "Ry", "Rz", "rot", "rot_left", "clip_unit"]


def _pad(a: np.ndarray, n: int) -> np.ndarray:
    return a.reshape((1,) * (n - a.ndim) + a.shape) if a.ndim < n else a


def _mv(a, b):
    return np.einsum("...ij,...j->...i", a, b)  # ~4x faster than matmul for stacked 3x3


class Jet:
    """(value, d/dt, d²/dt²) of an array; exact second-order forward mode."""

    __slots__ = ("v", "d", "dd")
    __array_ufunc__ = None  # numpy operands defer to the reflected Jet operators

    def __init__(self, v, d=None, dd=None, order: int = 2):
        v = np.asarray(v, dtype=float)
        d = np.zeros_like(v) if d is None else np.asarray(d, dtype=float)
        if order == 1:
            n = max(v.ndim, d.ndim)
            self.v, self.d, self.dd = _pad(v, n), _pad(d, n), None
            return
        dd = np.zeros_like(v) if dd is None else np.asarray(dd, dtype=float)
        n = max(v.ndim, d.ndim, dd.ndim)
        self.v, self.d, self.dd = _pad(v, n), _pad(d, n), _pad(dd, n)

    @classmethod
    def _make(cls, v, d, dd):
        return cls(v, d, dd, order=1 if dd is None else 2)

    # -- structure ------------------------------------------------------------------------
    @property
    def shape(self):
        return self.v.shape

    @property
    def ndim(self):
        return self.v.ndim

    def __getitem__(self, idx):
        return Jet._make(self.v[idx], self.d[idx], _opt(lambda a: a[idx], self.dd))

    @property
    def T(self):
        """Transpose of the trailing two axes."""
        sw = lambda a: np.swapaxes(a, -1, -2)  # noqa: E731
        return Jet._make(sw(self.v), sw(self.d), _opt(sw, self.dd))

    def sum(self, axis=-1):
        return Jet._make(self.v.sum(axis), self.d.sum(axis), _opt(lambda a: a.sum(axis), self.dd))

    def __repr__(self):
        return f"Jet(v={self.v!r}, d={self.d!r}, dd={self.dd!r})"

    # -- linear operations ----------------------------------------------------------------
    def __neg__(self):
        return Jet._make(-self.v, -self.d, _opt(np.negative, self.dd))

    def __add__(self, o):
        if isinstance(o, Jet):
            return Jet._make(self.v + o.v, self.d + o.d, _opt(np.add, self.dd, o.dd))
        return Jet._make(self.v + np.asarray(o), self.d, self.dd)

    __radd__ = __add__

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    # -- bilinear operations (Leibniz rule) ------------------------------------------------
    def _bilinear(self, o, op):
        if not isinstance(o, Jet):
            o = np.asarray(o, dtype=float)
            return Jet._make(op(self.v, o), op(self.d, o), _opt(lambda a: op(a, o), self.dd))
        dd = None
        if self.dd is not None and o.dd is not None:
            dd = op(self.dd, o.v) + 2.0 * op(self.d, o.d) + op(self.v, o.dd)
        return Jet._make(op(self.v, o.v), op(self.d, o.v) + op(self.v, o.d), dd)

    def _rbilinear(self, o, op):
        o = np.asarray(o, dtype=float)
        return Jet._make(op(o, self.v), op(o, self.d), _opt(lambda a: op(o, a), self.dd))

    def __mul__(self, o):
        return self._bilinear(o, np.multiply)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if isinstance(o, Jet):
            return self * o.reciprocal()
        return self * (1.0 / np.asarray(o, dtype=float))

    def __rtruediv__(self, o):
        return self.reciprocal() * o

    def reciprocal(self):
        r = 1.0 / self.v
        return _chain(self, r, -r * r, 2.0 * r * r * r)

    def __pow__(self, n):
        if n == 2:
            return self * self
        return _chain(self, self.v ** n, n * self.v ** (n - 1), n * (n - 1) * self.v ** (n - 2))

    def __matmul__(self, o):
        vec = o.ndim == self.ndim - 1 if isinstance(o, Jet) else np.ndim(o) == 1
        return self._bilinear(o, _mv if vec else np.matmul)

    def __rmatmul__(self, o):
        return self._rbilinear(o, _mv if self.ndim == 1 else np.matmul)


def _chain(a: Jet, f0, f1, f2) -> Jet:
    """f(a) given f, f', f'' at a.v: (f∘a)' = f'·a', (f∘a)'' = f''·a'² + f'·a''."""
    if a.dd is None:
        return Jet(f0, f1 * a.d, order=1)
    return Jet(f0, f1 * a.d, f2 * a.d * a.d + f1 * a.dd)


def _opt(f, *xs):
    """f(*xs), or None when a second derivative is absent (first-order jet)."""
    return None if any(x is None for x in xs) else f(*xs)


def value(x):
    """The value part of a jet (a plain array is returned as is)."""
    return x.v if isinstance(x, Jet) else np.asarray(x)


def sin(a):
    if not isinstance(a, Jet):
        return np.sin(a)
    s, c = np.sin(a.v), np.cos(a.v)
    return _chain(a, s, c, -s)


def cos(a):
    if not isinstance(a, Jet):
        return np.cos(a)
    s, c = np.sin(a.v), np.cos(a.v)
    return _chain(a, c, -s, -c)


def sqrt(a):
    if not isinstance(a, Jet):
        return np.sqrt(a)
    r = np.sqrt(a.v)
    return _chain(a, r, 0.5 / r, -0.25 / (r * a.v))


def asin(a):
    if not isinstance(a, Jet):
        return np.arcsin(a)
    w = 1.0 / np.sqrt(1.0 - a.v * a.v)
    return _chain(a, np.arcsin(a.v), w, a.v * w * w * w)


def acos(a):
    if not isinstance(a, Jet):
        return np.arccos(a)
    w = 1.0 / np.sqrt(1.0 - a.v * a.v)
    return _chain(a, np.arccos(a.v), -w, -a.v * w * w * w)


def atan2(y, x):
    """atan2 with exact derivatives: θ' = (x y' − y x')/r², r² = x² + y²."""
    if not isinstance(y, Jet) and not isinstance(x, Jet):
        return np.arctan2(y, x)
    y = y if isinstance(y, Jet) else Jet(y)
    x = x if isinstance(x, Jet) else Jet(x)
    r2 = x.v * x.v + y.v * y.v
    n = x.v * y.d - y.v * x.d
    if x.dd is None or y.dd is None:
        return Jet(np.arctan2(y.v, x.v), n / r2, order=1)
    dn = x.v * y.dd - y.v * x.dd  # the x'y' terms cancel
    dr2 = 2.0 * (x.v * x.d + y.v * y.d)
    return Jet(np.arctan2(y.v, x.v), n / r2, (dn * r2 - n * dr2) / (r2 * r2))


def clip_unit(a):
    """Clip the value into [−1, 1] (rounding guard before asin/acos); derivatives kept."""
    if not isinstance(a, Jet):
        return np.clip(a, -1.0, 1.0)
    return Jet._make(np.clip(a.v, -1.0, 1.0), a.d, a.dd)


def _stack(arrays, axis, shape=None):
    """np.stack of float arrays broadcast to ``shape`` (default: their common shape), each
    copied into its slot of one new array (np.broadcast_arrays and np.stack's own checks cost
    more than the copy for the closed form's small stacks; the same values either way)."""
    first = arrays[0].shape
    if all(a.shape == first for a in arrays) and shape in (None, first):
        return np.stack(arrays, axis)
    sh = np.broadcast_shapes(*[a.shape for a in arrays]) if shape is None else shape
    ax = axis % (len(sh) + 1)
    out = np.empty(sh[:ax] + (len(arrays),) + sh[ax:])
    lead = (slice(None),) * ax
    for k, a in enumerate(arrays):
        out[lead + (k,)] = a
    return out


def stack(items, axis=-1):
    """np.stack with broadcasting; items may mix jets, arrays and scalars."""
    if not any(isinstance(i, Jet) for i in items):
        return _stack([np.asarray(i, dtype=float) for i in items], axis)
    jets = [i if isinstance(i, Jet) else Jet(i) for i in items]
    sv = np.broadcast_shapes(*[j.v.shape for j in jets])

    def part(arrays):
        return _stack(arrays, axis, np.broadcast_shapes(sv, *[a.shape for a in arrays]))

    dd = None
    if not any(isinstance(i, Jet) and i.dd is None for i in items):
        dd = part([j.dd for j in jets])
    return Jet._make(part([j.v for j in jets]), part([j.d for j in jets]), dd)


def matvec(A, x):
    """A (..., 3, 3) times x (..., 3), batched."""
    if isinstance(A, Jet):
        return A._bilinear(x, _mv)
    if isinstance(x, Jet):
        return x._rbilinear(A, _mv)
    return _mv(np.asarray(A), np.asarray(x))


def transpose(A):
    return A.T if isinstance(A, Jet) else np.swapaxes(A, -1, -2)


def cross(a, b):
    op = lambda u, w: np.cross(u, w)  # noqa: E731
    if isinstance(a, Jet):
        return a._bilinear(b, op)
    if isinstance(b, Jet):
        return b._rbilinear(a, op)
    return np.cross(a, b)


def dot(a, b):
    """Sum over the trailing axis of a*b."""
    p = a * b
    return p.sum(-1) if isinstance(p, Jet) else np.sum(p, axis=-1)


def _rot(a, i, j):
    c, s = cos(a), sin(a)
    if not isinstance(c, Jet):  # plain angles: fill the matrix (the values stack() gives)
        c, s = np.asarray(c, dtype=float), np.asarray(s, dtype=float)
        out = np.zeros(np.broadcast_shapes(c.shape, s.shape) + (3, 3))
        out[..., 3 - i - j, 3 - i - j] = 1.0
        out[..., i, i], out[..., i, j], out[..., j, i], out[..., j, j] = c, -s, s, c
        return out
    z, o = 0.0, 1.0
    rows = [[o, z, z], [z, o, z], [z, z, o]]
    rows[i][i], rows[i][j], rows[j][i], rows[j][j] = c, -s, s, c
    return stack([stack(r, -1) for r in rows], -2)


_PLANE = {0: (1, 2), 1: (2, 0), 2: (0, 1)}  # axis -> (i, j) of its rotation plane


def rot(R, axis: int, a):
    """R @ R_axis(a) (R None: identity). Mixes two columns, much cheaper than a 3x3 product."""
    i, j = _PLANE[axis]
    if R is None:
        return _rot(a, i, j)
    c, s = cos(a), sin(a)
    c, s = c[..., None], s[..., None]
    cols = [R[..., :, k] for k in range(3)]
    cols[i], cols[j] = cols[i] * c + cols[j] * s, cols[j] * c - cols[i] * s
    return _mix(cols, -1)


def rot_left(axis: int, a, R):
    """R_axis(a) @ R: mixes two rows."""
    i, j = _PLANE[axis]
    c, s = cos(a), sin(a)
    c, s = c[..., None], s[..., None]
    rows = [R[..., k, :] for k in range(3)]
    rows[i], rows[j] = rows[i] * c - rows[j] * s, rows[i] * s + rows[j] * c
    return _mix(rows, -2)


def _mix(parts, axis):
    """stack(parts, axis) of a rotation's three rows or columns; plain arrays go straight to
    :func:`_stack` (no jet to look for)."""
    if any(isinstance(p, Jet) for p in parts):
        return stack(parts, axis)
    return _stack(parts, axis)


def Rx(a):
    """Rotation about x by a (array or jet), shape a.shape + (3, 3)."""
    return _rot(a, 1, 2)


def Ry(a):
    return _rot(a, 2, 0)


def Rz(a):
    return _rot(a, 0, 1)
