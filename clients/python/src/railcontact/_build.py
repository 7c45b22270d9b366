"""Request messages from plain Python values.

Every input of the high-level API may be given as the protobuf message
itself, or as a mapping that mirrors it key for key (the keys of the
``railcontact solve`` case files, which equal the proto's field names), with
these conveniences:

* an enum as its short name in any case: ``model="exact"`` (or
  ``"Exact"``, as the command line takes it), ``kind="conformal_circular"``,
  ``sides="left"`` (or its full name, or its number; :func:`enum_names`
  lists the names);
* a message whose fields are all numbers as a sequence, in field order:
  creepages ``(creepage_long, creepage_lat, spin_per_m)``, profile points
  ``(y_m, z_m)``;
* a bare number for a message sets its first field: ``load=1e5`` (the
  normal or vertical force), ``friction=0.3`` (the coefficient).
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping, Sequence

from google.protobuf.descriptor import FieldDescriptor

from .errors import invalid

_MESSAGE = FieldDescriptor.TYPE_MESSAGE
_ENUM = FieldDescriptor.TYPE_ENUM


def enum_prefix(enum_descriptor) -> str:
    """The common prefix of an enum's value names (``MODEL_`` of ``Model``)."""
    names = [v.name for v in enum_descriptor.values]
    prefix = names[0]
    for name in names[1:]:
        while not name.startswith(prefix):
            prefix = prefix[:-1]
    return prefix[: prefix.rfind("_") + 1]


def enum_name(enum_descriptor, number: int) -> str:
    """The short lower-case name of an enum value (``exact`` for MODEL_EXACT)."""
    value = enum_descriptor.values_by_number.get(number)
    if value is None:
        return str(number)
    return value.name[len(enum_prefix(enum_descriptor)):].lower()


def enum_names(enum_descriptor) -> tuple:
    """The short lower-case names a value of the enum may be given by, in
    the proto's order (``exact``, ``hertz_fastsim``, ... of
    ``WheelRailModel``); never its ``*_UNSPECIFIED`` value, which says
    "not set" on the wire and is no name to give."""
    return tuple(
        enum_name(enum_descriptor, v.number)
        for v in enum_descriptor.values
        if not v.name.endswith("_UNSPECIFIED")
    )


def enum_number(enum_descriptor, value, path: str) -> int:
    """An enum value's number from its short name or full name, in any
    case (``"Exact"``, ``"exact"``, ``"MODEL_EXACT"``), or its number. An
    unknown name, or the ``unspecified`` one, raises
    :class:`RailcontactError` (INVALID_ARGUMENT at ``path``) listing the
    valid names."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return int(value)
    if isinstance(value, str):
        full = value.upper()
        for candidate in (full, enum_prefix(enum_descriptor) + full):
            if candidate in enum_descriptor.values_by_name and not candidate.endswith("_UNSPECIFIED"):
                return enum_descriptor.values_by_name[candidate].number
    names = ", ".join(f'"{n}"' for n in enum_names(enum_descriptor))
    raise invalid(path, f"{value!r} is not one of {names} (any case)")


def build(message_class, value, path: str):
    """A ``message_class`` message from ``value`` (see the module's doc);
    ``path`` names it in errors."""
    if isinstance(value, message_class):
        return value
    message = message_class()
    fill(message, value, path)
    return message


def fill(message, value, path: str) -> None:
    """Sets ``message``'s fields from ``value`` (a mapping, a sequence of
    numbers, a number or a message of the same type)."""
    descriptor = message.DESCRIPTOR
    if isinstance(value, type(message)):
        message.CopyFrom(value)
    elif isinstance(value, Mapping):
        for key, item in value.items():
            field = descriptor.fields_by_name.get(key)
            if field is None:
                known = ", ".join(descriptor.fields_by_name)
                raise invalid(_join(path, key), f"unknown key; {descriptor.name} has: {known}")
            if item is not None:
                _set(message, field, item, _join(path, key))
    elif isinstance(value, numbers.Real) and not isinstance(value, bool):
        _set(message, descriptor.fields[0], value, _join(path, descriptor.fields[0].name))
    elif isinstance(value, Sequence) and not isinstance(value, str):
        if len(value) > len(descriptor.fields):
            raise invalid(path, f"at most {len(descriptor.fields)} values, got {len(value)}")
        for field, item in zip(descriptor.fields, value):
            _set(message, field, item, _join(path, field.name))
    else:
        raise invalid(path, f"expected a {descriptor.name} (message, mapping, sequence or number), got {value!r}")


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def _set(message, field, value, path: str) -> None:
    repeated = field.is_repeated
    if field.type == _MESSAGE:
        if repeated:
            target = getattr(message, field.name)
            for i, item in enumerate(value):
                fill(target.add(), item, f"{path}[{i}]")
        else:
            target = getattr(message, field.name)
            target.SetInParent()  # an empty mapping still sets the field (or oneof)
            fill(target, value, path)
        return
    if field.type == _ENUM:
        if repeated:
            getattr(message, field.name).extend(
                enum_number(field.enum_type, v, f"{path}[{i}]") for i, v in enumerate(value)
            )
        else:
            setattr(message, field.name, enum_number(field.enum_type, value, path))
        return
    try:
        if repeated:
            getattr(message, field.name).extend(float(v) if isinstance(v, numbers.Real) else v for v in value)
        else:
            if field.cpp_type == FieldDescriptor.CPPTYPE_DOUBLE and isinstance(value, numbers.Real):
                value = float(value)
            setattr(message, field.name, value)
    except (TypeError, ValueError) as e:
        raise invalid(path, f"{value!r}: {e}") from None
