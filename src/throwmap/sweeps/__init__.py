"""Sweeps on Dask: a grid or a seeded random design over the parameters of an experiment
or an analysis, run on a local or an existing Dask cluster, stored as partitioned Parquet, resumable.

====================  ==============================================================================
:mod:`.schema`        the sweep file (TOML): :class:`SweepSpec`, the ``throw``/``limit_set`` configs, the hash
:mod:`.design`        the design points (grid or random), each validated by the target's config type
:mod:`.targets`       what one Dask task computes (:func:`run_chunk`), per target
:mod:`.store`         ``OUT/_manifest.json`` and ``OUT/part-NNNNNN.parquet``, written atomically
:mod:`.run`           :func:`run_sweep` (Dask), :func:`sweep_status`
====================  ==============================================================================

``import throwmap`` imports neither this package nor dask; dask and pyarrow are imported inside functions.
"""

from .design import Design, make_design
from .run import SweepRun, run_sweep, sweep_status
from .schema import LimitSetConfig, SweepSpec, ThrowConfig, parse_sweep, read_sweep, spec_hash
from .store import read_table

__all__ = ["SweepSpec", "ThrowConfig", "LimitSetConfig", "parse_sweep", "read_sweep", "spec_hash", "Design",
           "make_design", "SweepRun", "run_sweep", "sweep_status", "read_table"]
