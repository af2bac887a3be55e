"""The scene format's tags with their defaults and ranges (from `softsub schema`, see
schema_table.py), parsed into Python values. Pure Python, no bpy."""
import math
import re

from .schema_table import SCHEMA

FUNCTION_KINDS = ("Linear", "LennardJones", "LennardJonesForce", "Curve")


def rows(section):
    return SCHEMA[section]


def row(section, tag):
    for r in SCHEMA[section]:
        if r[0] == tag:
            return r
    raise KeyError(f"{section}/{tag}")


def tags(section):
    return [r[0] for r in SCHEMA[section]]


def parse_value(kind, text):
    """Text of an element -> a Python value of the schema type (ValueError if bad)."""
    t = text.strip()
    if kind == "real":
        v = float(t)
        if not math.isfinite(v):
            raise ValueError(f"'{t}' is not a finite number")
        return v
    if kind == "int":
        if not re.fullmatch(r"[+-]?\d+", t):
            raise ValueError(f"'{t}' is not an integer")
        return int(t)
    if kind == "bool":
        if t in ("true", "1"):
            return True
        if t in ("false", "0"):
            return False
        raise ValueError(f"'{t}' is not true, false, 1 or 0")
    if kind in ("vec3", "colour"):
        parts = t.split()
        if len(parts) != 3:
            raise ValueError(f"'{t}' is not 3 numbers")
        return tuple(float(p) for p in parts)
    if kind == "real list":
        return [float(p) for p in t.split()]
    if kind == "vec3 list":
        parts = t.split()
        if len(parts) % 3:
            raise ValueError("the count of numbers is not a multiple of 3")
        return [(float(parts[i]), float(parts[i + 1]), float(parts[i + 2])) for i in range(0, len(parts), 3)]
    return t  # string, enum


def default(section, tag):
    """The tag's default as a Python value, or None where the schema has none."""
    _, kind, _, text, _, _ = row(section, tag)
    try:
        return parse_value(kind, text)
    except ValueError:
        return None


def enum_items(section, tag):
    """Allowed names of an enum tag, e.g. the integrators."""
    allowed = row(section, tag)[4]
    return [a.strip() for a in allowed.split(";")[0].split(",")]


_RANGE = re.compile(r"^(integer )?(\(|\[)([^,]+), ([^\]\)]+)(\)|\])")


def bounds(section, tag):
    """(lo, lo_inclusive, hi, hi_inclusive) of a numeric tag; None where unbounded."""
    allowed = row(section, tag)[4].split(";")[0].strip()
    allowed = allowed.replace("integer ", "").replace("numbers ", "").replace("3 numbers in ", "")
    m = _RANGE.match(allowed)
    if m:
        return (float(m.group(3)), m.group(2) == "[", float(m.group(4)), m.group(5) == "]")
    m = re.match(r"^(>=|>) (\S+)", allowed)
    if m:
        return (float(m.group(2)), m.group(1) == ">=", None, False)
    return (None, False, None, False)


def check_range(section, tag, value):
    """None if value is allowed by the tag's range, else the softsub-style problem text."""
    lo, lo_in, hi, hi_in = bounds(section, tag)
    values = value if isinstance(value, (tuple, list)) else (value,)
    for v in values:
        if not math.isfinite(v):
            return f"{v} is not a finite number"
        bad = (lo is not None and (v < lo or (v == lo and not lo_in))) or (
            hi is not None and (v > hi or (v == hi and not hi_in)))
        if bad:
            return f"{format_number(v)} is out of range (allowed: {row(section, tag)[4]})"
    return None


def format_number(v):
    """The shortest decimal that reads back to the same single-precision float (Blender
    keeps every property in single precision), as an integer when it is one."""
    import struct
    v = float(v)
    target = struct.pack("<f", v)
    single = struct.unpack("<f", target)[0]
    # An integer once held in single precision is written as one: a rotation converted in
    # double precision to 40.0000001 was written "4e1" (a review).
    if single == int(single) and abs(single) < 1e15:
        return str(int(single))
    for digits in range(1, 10):
        text = f"{v:.{digits}g}"
        if struct.pack("<f", float(text)) == target:
            return _tidy(text)
    return repr(v)


def format_double(v):
    """The shortest decimal that reads back to the same double (exact values)."""
    v = float(v)
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def _tidy(text):
    if "e" in text:
        mant, exp = text.split("e")
        return f"{mant}e{int(exp)}"
    return text
