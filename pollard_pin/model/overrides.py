"""Dotted-key overrides of a thesis-unit parameter dictionary (``"chain0.x32"``,
``"home.tip[2]"``): :func:`lookup`, :func:`apply_overrides` (same shape as the value it
replaces), :func:`parse_assignment` of a ``KEY=VALUE`` text, and :class:`ParameterError`, the
error of every parameter rule."""
from __future__ import annotations

import copy
import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..checks import shorten
from ..errors import InputError
from .values import loads_toml


class ParameterError(InputError):
    """A parameter file or override breaks a rule; the message names key, value and rule.

    ``key`` is the dotted key whose own rule it is (``model.values.fail`` sets it), None when
    the rule is not one key's (the home pose, a malformed override)."""

    key: str | None = None


_UNSET = object()
_KEY_RE = re.compile(r"^([A-Za-z_][\w]*(?:\.[A-Za-z_][\w]*)*)((?:\[\d+\])*)$")


def _split_key(key: str) -> tuple[list[str], list[int]]:
    """``"bodies.gun.inertia[1][2]"`` → (["bodies", "gun", "inertia"], [1, 2])."""
    m = _KEY_RE.match(key) if isinstance(key, str) else None
    if m is None:
        raise ParameterError(f"parameter {shorten(key)}: not a dotted parameter key "
                             "(like 'chain0.x32' or 'home.tip[2]')")
    return m.group(1).split("."), [int(i) for i in re.findall(r"\[(\d+)\]", m.group(2))]


def lookup(d: Mapping, key: str, value: Any = _UNSET) -> Any:
    """The value at ``key`` in a thesis-unit parameter dictionary (ParameterError if none);
    ``value``, if given, is the override being applied (shown in the message)."""
    shown = "" if value is _UNSET else f" = {shorten(plain_value(value))}"
    path, index = _split_key(key)
    node: Any = d
    for j, part in enumerate(path):
        if not isinstance(node, Mapping) or part not in node:
            what = "unknown key" if j == len(path) - 1 else "unknown section"
            raise ParameterError(f"parameter {shorten(key)}{shown}: override names no "
                                 f"parameter ({what})")
        node = node[part]
    if isinstance(node, Mapping):
        raise ParameterError(f"parameter {shorten(key)}{shown}: names a section, not a parameter")
    for i in index:
        if not isinstance(node, list) or i >= len(node):
            raise ParameterError(f"parameter {shorten(key)}{shown}: index [{i}] is out of range "
                                 f"for '{path[-1]}' = {shorten(node)}")
        node = node[i]
    return node


def value_shape(value: Any) -> tuple[int, ...] | None:
    """Shape of a number (()) or nested list of numbers; None for anything else."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return ()
    if isinstance(value, (list, tuple)) and value:
        shapes = {value_shape(v) for v in value}
        if len(shapes) == 1 and None not in shapes:
            return (len(value),) + shapes.pop()
    return None


def plain_value(value: Any) -> Any:
    """Tuples/arrays → lists, numpy scalars → Python numbers (TOML layout)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [plain_value(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def apply_overrides(d: Mapping, overrides: Mapping[str, Any]) -> dict:
    """A deep copy of the thesis-unit dictionary ``d`` with ``overrides`` applied.

    Plain dotted keys (``"chain0.x32"``) replace a parameter; ``key[i]`` (``key[i][j]``)
    replaces one component of a vector (matrix) parameter. The new
    value must have the shape of the old one; values themselves are validated later by
    :func:`params_from_dict`.
    """
    out = copy.deepcopy(dict(d))
    for key, value in overrides.items():
        value = plain_value(value)
        old = lookup(out, key, value)
        if value_shape(value) != value_shape(old):
            shape = value_shape(old)
            want = ("a number" if shape == () else
                    f"a list of {shape[0]} numbers" if len(shape) == 1 else
                    f"a {'x'.join(map(str, shape))} matrix (list of {shape[0]} rows)")
            raise ParameterError(f"parameter {shorten(key)} = {shorten(value)}: must be {want}")
        path, index = _split_key(key)
        node: Any = out
        for part in path[:-1]:
            node = node[part]
        if not index:
            node[path[-1]] = value
            continue
        node = node[path[-1]]
        for i in index[:-1]:
            node = node[i]
        node[index[-1]] = value
    return out


def parse_assignment(text: str) -> tuple[str, Any]:
    """``"chain0.x32=0.35"`` or ``"home.tip=[0.5, 0, 0.2]"`` → (key, value), value as TOML
    (one line, ASCII, no ``_`` digit separators)."""
    key, sep, value = text.partition("=")
    where = f"override {shorten(text)}"
    if not sep or not key.strip():
        raise ParameterError(f"{where}: expected KEY=VALUE, e.g. chain0.x32=0.35")
    bad = next((c for c in value if not c.isprintable() or not c.isascii() or c == "_"), None)
    if bad is not None:  # TOML would read a newline as a second key and drop it
        why = ("'_' digit separators are not accepted" if bad == "_" else
               f"{bad!r} is not an ASCII character" if bad.isprintable() else
               f"the value holds a control character {bad!r}: one KEY=VALUE per override")
        raise ParameterError(f"{where}: {why}")
    try:
        # a huge integer goes on to the parameter's own check, which names its key
        return key.strip(), loads_toml(f"v = {value.strip()}", where, ParameterError,
                                       ints=False)["v"]
    except ParameterError as exc:
        if "not valid TOML" not in str(exc):
            raise
        raise ParameterError(f"{where}: the value is not a number or a list of "
                             "numbers") from None


__all__ = ["ParameterError", "apply_overrides", "lookup", "parse_assignment", "plain_value",
           "value_shape"]
