"""Reports as plain Python objects: JSON text → dicts, every vector or matrix of numbers a
numpy array (integers int64, numbers with a fraction or NaN float64, booleans bool)."""

import json
import math
import os

import numpy as np

#: Keys whose lists hold text or records even when empty (an empty list stays a list).
_LIST_KEYS = ("warnings", "errors", "notes", "frames", "impacts", "rows", "samples")


def _shape(v):
    """The shape of a rectangular nested list of scalars and its dtype, or None."""
    if not isinstance(v, list):
        if isinstance(v, bool):
            return (), bool
        if isinstance(v, int):
            return (), int
        if isinstance(v, float) or v is None:
            return (), float
        return None
    if not v:
        return None
    shapes = [_shape(x) for x in v]
    if any(s is None for s in shapes):
        return None
    first = shapes[0][0]
    if any(s[0] != first for s in shapes):
        return None
    kinds = {s[1] for s in shapes}
    if kinds == {bool}:
        kind = bool
    elif bool in kinds:
        return None
    elif kinds == {int}:
        kind = int
    else:
        kind = float
    if kind is float and all(x is None for x in _leaves(v)):
        return None
    return (len(v),) + first, kind


def _leaves(v):
    if isinstance(v, list):
        for x in v:
            yield from _leaves(x)
    else:
        yield v


def arrays(value, key=""):
    """``value`` (parsed JSON) with its numeric lists as numpy arrays (module docs)."""
    if isinstance(value, dict):
        return {k: arrays(v, k) for k, v in value.items()}
    if isinstance(value, list):
        if not value:
            if key.endswith(_LIST_KEYS):
                return []
            return np.empty(0)
        shape = _shape(value)
        if shape is not None:
            dtype = {bool: np.bool_, int: np.int64, float: np.float64}[shape[1]]
            if dtype is np.float64:
                value = [_nan(x) for x in value]
            return np.array(value, dtype=dtype)
        return [arrays(v, key) for v in value]
    return value


def _nan(v):
    if isinstance(v, list):
        return [_nan(x) for x in v]
    return float("nan") if v is None else v


def report(text):
    """A report (JSON text) as a dict of plain objects and numpy arrays."""
    return arrays(json.loads(text))


def value(v):
    """A value as plain JSON: numpy scalars and arrays as Python numbers and lists, paths as
    text, a structure as its scene TOML, a non-finite number as its text."""
    if hasattr(v, "to_toml") and callable(v.to_toml):
        return v.to_toml()
    if isinstance(v, os.PathLike):
        return os.fspath(v)
    if isinstance(v, np.ndarray):
        return [value(x) for x in v.tolist()]
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, (list, tuple)):
        return [value(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    return v


def text(v):
    """A keyword value as the command line hands it to the engine: a number or a list as
    its text (``2.5``, ``8,12``; Python's shortest round-trip form, read back exactly),
    ``True``/``False`` as a boolean. The engine then reads, checks and refuses it exactly
    as a flag's value, with the same message (``sides = "2.5": expected a non-negative
    integer``)."""
    v = value(v)
    if isinstance(v, bool) or v is None:
        return v
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, list):
        return ",".join(str(text(x)) for x in v)
    return v


def arguments(values):
    """Keyword values as the JSON text the engine reads (see :func:`text`)."""
    return json.dumps({k: text(v) for k, v in values.items()}, allow_nan=False)


def dumps(values):
    """Named values as the JSON text the engine reads."""
    return json.dumps({k: value(v) for k, v in values.items()}, allow_nan=False)
