"""Keyword values on their way to the engine.

Nothing here writes or reads text: the native module converts Python objects to the
engine's values and its reports back to Python objects itself (``src/convert.rs``: numbers,
strings, booleans, lists, dicts, numpy arrays and scalars, paths, a ``Structure`` as its
scene; every rectangular list of numbers in a report a numpy array). This module only
selects which keyword values are handed on."""


def arguments(values):
    """The keyword values given, as the engine's named values (``None``: not given)."""
    return {k: v for k, v in values.items() if v is not None}


def plain(values):
    """Named values (a dict of tables, limits or a sweep spec) as they are."""
    return dict(values)
