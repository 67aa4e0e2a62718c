"""Plain values for JSON: what every record's ``to_dict`` returns (strict JSON: no NaN, no infinity).

Depends on nothing in the package, so records, results and files all use the same rule.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

__all__ = ["json_ready"]


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
