"""Test oracles: :mod:`.reference`, an independent SciPy implementation of the "paper" throw
(grid scan + brentq, a linear solve per impact, ``solve_ivp`` for every swing)."""
