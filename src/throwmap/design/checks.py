"""One named pass/fail of a design (:mod:`throwmap.design.cavity`'s checks), with the figure it was decided on."""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Check"]


@dataclass(frozen=True, slots=True)
class Check:
    """One named pass/fail of a design with the figure it was decided on (SI, ``unit``)."""

    name: str
    passed: bool
    value: float
    requirement: str
    unit: str = "m"

    def __str__(self) -> str:
        unit = self.unit[:-1] if self.unit == "throws" and self.value == 1 else self.unit  # 1 throw, 0/2 throws
        v = f"{100 * self.value:.2f} cm" if self.unit == "m" else f"{self.value:.4g} {unit}".strip()
        return f"{'PASS' if self.passed else 'FAIL'} {self.name}: {v} ({self.requirement})"

    def to_dict(self) -> dict:
        v = self.value
        return {"name": self.name, "passed": bool(self.passed), "value": v if math.isfinite(v) else None,
                "unit": self.unit, "requirement": self.requirement}
