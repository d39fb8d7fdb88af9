"""Design studies: sweep a mechanism's parameters over many designs on Dask, resumable, and refine.

Modules: `space` (axes; grid, random and Latin-hypercube designs), `metrics` (the motion study and the
generic metrics), `specific` (mechanism-specific metrics, the metric table), `evaluate` (a chunk of
designs -> rows with their status), `store` (the Parquet dataset, one part file per chunk), `engine`
(Dask distributed: embedded LocalCluster or a scheduler address), `optimise` (scipy.optimize from the
best sweep points, evaluations on the same engine).
"""

from mechkit.sweep.engine import SweepSummary, dask_client, sweep
from mechkit.sweep.metrics import Study
from mechkit.sweep.space import Axis, DesignSpace, parse_axis
from mechkit.sweep.store import read

__all__ = ["Axis", "DesignSpace", "Study", "SweepSummary", "dask_client", "parse_axis", "read", "sweep"]
