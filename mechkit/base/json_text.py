"""Strict JSON: what mechkit writes as JSON is JSON (RFC 8259), never `Infinity` or `NaN`.

A quantity that does not exist (the stiffness along a direction held rigidly, a value not computed) is
`null`, and a sibling key `<name>_why` says why (`nulls`). A non-finite number that reaches `dumps` is a
bug of the caller: it is refused, never written.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from mechkit.base.exceptions import OutputError


def dumps(obj: Any, **options: Any) -> str:
    """`json.dumps` of plain data (numpy scalars and arrays converted), refusing non-finite numbers.

    Args:
        obj: dicts, lists, tuples, strings, numbers, bools, None and numpy values.
        **options: `json.dumps` keywords (indent, sort_keys, ...).

    Returns:
        The JSON text.

    Raises:
        OutputError: a NaN or infinity somewhere in `obj` (its path named).
    """
    return json.dumps(_plain(obj, "$"), allow_nan=False, **options)


def nulls(values: Mapping[str, float], why: str) -> tuple[dict[str, float | None], dict[str, str]]:
    """Values for JSON: each non-finite one as None, with the reason beside it.

    Args:
        values: name -> number.
        why: the reason a non-finite value does not exist as a number (e.g. "held rigidly").

    Returns:
        (name -> the value or None, name -> `why` for each None): the second goes under `<key>_why`.
    """
    out = {k: (float(v) if math.isfinite(v) else None) for k, v in values.items()}
    return out, {k: why for k, v in out.items() if v is None}


def _plain(obj: Any, path: str) -> Any:
    """`obj` as JSON-ready Python values; a non-finite float refused with where it is."""
    if isinstance(obj, Mapping):
        return {str(k): _plain(v, f"{path}.{k}") for k, v in obj.items()}
    if isinstance(obj, np.ndarray):
        return _plain(obj.tolist(), path)
    if isinstance(obj, (list, tuple)):
        return [_plain(v, f"{path}[{k}]") for k, v in enumerate(obj)]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        raise OutputError(path, f"{obj} is not a JSON number: a quantity that does not exist must be null")
    return obj
