"""Physics kernels: plain functions of floats and arrays (SI units), compiled with Numba.

No classes, no I/O, no validation: the public API in :mod:`throwmap.throw`
validates once and calls these. Setting ``NUMBA_DISABLE_JIT=1`` runs them as
plain Python (slow, but debuggable).
"""
