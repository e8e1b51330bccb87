"""Build frozen dataclasses from plain mappings (parsed YAML), naming the key path of any error.

A field's type annotation gives its kind (``float``, ``int``, ``bool``, ``str``, a nested dataclass,
``tuple[float, ...]``, ``Vec3`` or ``Optional`` of those); its metadata may carry a ``check``
(a predicate and the phrase that describes it). Unknown keys, wrong kinds, failed checks and
missing required keys raise :class:`ParameterError` with messages such as
``targets[0].rotors.blade_length_m: must be > 0, got -0.1``.
"""

import dataclasses
import math
import types
import typing

from mdpipe.errors import ParameterError

Vec3 = typing.NewType("Vec3", tuple)


def check(predicate, phrase):
    """Field metadata: values must satisfy ``predicate``; ``phrase`` completes 'must be ...'."""
    return {"check": (predicate, phrase)}


POSITIVE = check(lambda v: v > 0, "> 0")
NON_NEGATIVE = check(lambda v: v >= 0, ">= 0")


REPR_CHARS = 60


def short_repr(value):
    """``repr(value)``, cut to a readable length for one-line messages."""
    text = repr(value)
    return text if len(text) <= REPR_CHARS else text[:REPR_CHARS - 3] + "..."


def _join(path, key):
    return f"{path}.{key}" if path else key


def _fail(path, message):
    raise ParameterError(f"{path}: {message}")


def _number(value, path, *, integer):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        _fail(path, f"expected {'an integer' if integer else 'a number'}, got {short_repr(value)}")
    try:
        finite = math.isfinite(value)
    except OverflowError:  # an integer beyond float range
        finite = False
    if not finite:
        _fail(path, f"expected a finite number, got {short_repr(value)}")
    if integer and value != int(value):
        _fail(path, f"expected an integer, got {value!r}")
    return int(value) if integer else float(value)


def _convert(kind, value, path):
    origin = typing.get_origin(kind)
    if origin in (typing.Union, types.UnionType):
        options = [a for a in typing.get_args(kind) if a is not type(None)]
        return None if value is None else _convert(options[0], value, path)
    if kind is Vec3:
        if not isinstance(value, (list, tuple)) or len(value) != 3:
            _fail(path, f"expected a list of 3 numbers [x, y, z], got {short_repr(value)}")
        return tuple(_number(v, f"{path}[{i}]", integer=False) for i, v in enumerate(value))
    if origin is tuple:
        item = typing.get_args(kind)[0]
        values = value if isinstance(value, (list, tuple)) else [value]
        return tuple(_convert(item, v, f"{path}[{i}]") for i, v in enumerate(values))
    if dataclasses.is_dataclass(kind):
        return build(kind, value, path)
    if kind is bool:
        if not isinstance(value, bool):
            _fail(path, f"expected true or false, got {short_repr(value)}")
        return value
    if kind in (int, float):
        return _number(value, path, integer=kind is int)
    if kind is str:
        if not isinstance(value, str):
            _fail(path, f"expected a string, got {short_repr(value)}")
        return value
    raise TypeError(f"unsupported field type {kind!r} at {path}")


def build(cls, data, path):
    """Build dataclass ``cls`` from mapping ``data``; ``path`` names it in error messages."""
    if data is None:
        data = {}
    if not isinstance(data, dict):
        _fail(path, f"expected a mapping of keys to values, got {short_repr(data)}")
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}
    unknown = sorted((str(key) for key in data if key not in fields))
    if unknown:
        key = unknown[0] if len(unknown[0]) <= REPR_CHARS else unknown[0][:REPR_CHARS - 3] + "..."
        _fail(_join(path, key), f"unknown key (known keys: {', '.join(fields)})")
    hints = typing.get_type_hints(cls)
    values = {}
    for name, f in fields.items():
        key_path = _join(path, name)
        if name not in data:
            if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
                _fail(key_path, "missing (required key)")
            continue
        value = _convert(hints[name], data[name], key_path)
        predicate, phrase = f.metadata.get("check", (None, None))
        if predicate is not None and value is not None:
            items = value if isinstance(value, tuple) else (value,)
            bad = [v for v in items if not predicate(v)]
            if bad:
                _fail(key_path, f"must be {phrase}, got {short_repr(bad[0])}")
        values[name] = value
    try:
        return cls(**values)
    except ParameterError as exc:
        if not path:
            raise
        _fail(path, str(exc))
