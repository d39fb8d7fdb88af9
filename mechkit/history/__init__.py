"""A mechanism's history along a motion: the arrays a motion study or a simulation gives (`MotionResult`),
their table form (pandas, Parquet, CSV) and the joints' world axes the reaction tables split along.

It sits below both `mechkit.motion` and `mechkit.simulation`, and knows nothing of `Mechanism`: the
simulator, which `Mechanism.simulate` reaches, needs nothing that imports `Mechanism`.
"""

from mechkit.history.axes import JointAxes
from mechkit.history.result import MotionResult, coordinate_names, read_csv, read_parquet, write_csv, write_parquet

__all__ = ["JointAxes", "MotionResult", "coordinate_names", "read_csv", "read_parquet", "write_csv", "write_parquet"]
