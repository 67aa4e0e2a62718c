"""The draft reproduced in one command: :func:`reproduce` makes every figure of the draft that
has an analogue (Figs. 2, 5, 7, 8, 9, 13, 14, 15, 16), runs its four experiments (≥ 200 engine trials each at full
size) and writes one Markdown and one HTML report with the parameters chosen where the draft is silent and the
errata. :mod:`.plan` lists what is made, :mod:`.figures` makes each figure, :mod:`.run` runs it all, :mod:`.report`
writes the reports."""

from .plan import EXPERIMENTS, FIGURES, SIZES
from .run import Reproduction, reproduce

__all__ = ["reproduce", "Reproduction", "FIGURES", "EXPERIMENTS", "SIZES"]
