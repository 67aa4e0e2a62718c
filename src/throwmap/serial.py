"""Plain values for JSON: what every record's ``to_dict`` returns (strict JSON: no NaN, no infinity).

Depends on nothing in the package, so records, results and files all use the same rule.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

__all__ = ["json_ready", "same_value", "fields_equal"]


def json_ready(obj: Any) -> Any:
    """JSON-ready copy: non-finite floats → None, tuples → lists, NumPy values and paths → Python/str."""
    if isinstance(obj, dict):
        return {str(k): json_ready(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_ready(v) for v in obj]
    if isinstance(obj, Path):
        return str(obj)
    if hasattr(obj, "tolist") and not isinstance(obj, (str, bytes)):
        return json_ready(obj.tolist())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def same_value(a: Any, b: Any) -> bool:
    """Value equality for what records hold: arrays element-wise (shape and dtype kind too), NaN equal to NaN,
    dicts, lists and tuples item by item, anything else by ``==``."""
    import numpy as np

    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)) or a.shape != b.shape:
            return False
        if a.dtype.kind in "fc" or b.dtype.kind in "fc":
            return bool(np.array_equal(a, b, equal_nan=True))
        return bool(np.array_equal(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_value(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return a is b


def fields_equal(a: Any, b: Any) -> bool:
    """Whether two dataclass records of the same type hold the same values (:func:`same_value` field by field):
    the ``__eq__`` of records that hold arrays."""
    import dataclasses

    if type(a) is not type(b):
        return NotImplemented
    return all(same_value(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
