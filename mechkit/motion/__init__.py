"""Motion studies: efforts and every joint's reaction along a motion, as data, plots and peak loads.

`study(mech, law)` assembles the mechanism along an input law (`inputs`: callables of time, arrays,
a CSV file, a registered scene, a motion law the mechanism declares), then computes velocities,
accelerations, the driven joints' efforts and every joint's reaction; the `MotionResult` converts to
a pandas DataFrame and writes Parquet and CSV (`result`); `peaks` finds each joint's largest force
and moment, axial and radial; `plot` draws efforts and chosen reactions over time (matplotlib,
imported on use).

The entry point is this package's `study`, not a `Mechanism` method: `Mechanism` is core and this
package sits above it (it reads scenes and writes tables), and the core never imports upwards.
"""

from mechkit.history.result import MotionResult, read_csv, read_parquet, write_csv, write_parquet
from mechkit.motion.inputs import (
    InputLaw,
    default_inputs,
    from_arrays,
    from_callable,
    from_csv,
    from_law,
    from_scene,
    resample,
)
from mechkit.motion.peaks import JointPeaks, peak_table, peaks
from mechkit.motion.study import study

__all__ = [
    "InputLaw",
    "JointPeaks",
    "MotionResult",
    "default_inputs",
    "from_arrays",
    "from_callable",
    "from_csv",
    "from_law",
    "from_scene",
    "peak_table",
    "peaks",
    "read_csv",
    "read_parquet",
    "resample",
    "study",
    "write_csv",
    "write_parquet",
]
