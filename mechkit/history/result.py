"""The result of a motion study (or a simulation) as arrays, and its table form: pandas DataFrame, Parquet, CSV.

Columns of the table (SI units, world frame; see `MotionResult`):
`t`; `q/<coord>`, `v/<coord>`, `a/<coord>` for every coordinate of the tree; `effort/<joint>` for
every driven joint; `reaction/<joint>/<fx|fy|fz|mx|my|mz>` for every joint (tree and cut) and
`axis/<joint>/<x|y|z>` its unit axis (NaN for joints without one); `determinate/<joint>/<component>`
when the determinacy test ran. The mechanism's name, its actuated and driven joints and its support
joints travel as metadata: `DataFrame.attrs`, Parquet schema metadata, `#` header lines of the CSV.
"""

from __future__ import annotations

import io
import json
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.atomic import write_bytes, write_text
from mechkit.base.exceptions import MalformedDescription, MethodUnavailable

if TYPE_CHECKING:
    import pandas as pd
    import pinocchio as pin

COMPONENTS = ("fx", "fy", "fz", "mx", "my", "mz")
AXES = ("x", "y", "z")
META = ("mechanism", "source", "actuated", "coordinates", "joints", "supports", "failures")


def pandas() -> ModuleType:
    """The pandas module (the `motion` extra), or a `MethodUnavailable` naming the install."""
    try:
        import pandas as pd
    except ImportError:
        raise MethodUnavailable("motion tables", "pandas is not installed: pip install 'mechkit[motion]'") from None
    return pd


def coordinate_names(model: pin.Model) -> tuple[str, ...]:
    """Names of the q coordinates: the joint's name, `name[k]` for a joint of several coordinates.

    Args:
        model: the Pinocchio model.

    Returns:
        One name per q coordinate, in q's order.
    """
    out = []
    for j in range(1, model.njoints):
        n = model.joints[j].nq
        out += [model.names[j]] if n == 1 else [f"{model.names[j]}[{k}]" for k in range(n)]
    return tuple(out)


@dataclass(frozen=True)
class MotionResult:
    """Efforts and every joint's reaction along a motion, N samples.

    Attributes:
        mechanism: the mechanism's name.
        source: where the input law came from.
        t: (N,) times, s.
        coordinates: names of the tree's coordinates (joint name; `name[k]` for multi-coordinate joints).
        q, v, a: (N, nq) configuration, (N, nv) velocities, (N, nv) accelerations (rad, m, per s, per s^2).
        effort_names: the driven joints (actuated first, then passive inputs such as a spring's hinge).
        actuated: the actuated joints among them.
        efforts: (N, n_efforts) generalised force at each driven joint (N m or N): the motor effort at
            an actuated joint, what a passive input's spring or damper must supply at the others.
        joints: joint names: every tree joint, then every cut joint.
        supports: (n_joints,) True for joints to the ground.
        reactions: (N, n_joints, 6) wrench [f (N), m (N m)] parent side on child side, at the joint
            origin, world frame.
        axes: (N, n_joints, 3) unit joint axis, world frame (NaN where a joint has no single axis).
        determinate: (N, n_joints, 6) components static equilibrium fixes, or None (not tested).
        failures: (t (s), reason) of the samples that failed (rows of NaN; `study(skip_failures=True)`).
    """

    mechanism: str
    source: str
    t: np.ndarray
    coordinates: tuple[str, ...]
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    effort_names: tuple[str, ...]
    actuated: tuple[str, ...]
    efforts: np.ndarray
    joints: tuple[str, ...]
    supports: np.ndarray
    reactions: np.ndarray
    axes: np.ndarray
    determinate: np.ndarray | None = None
    failures: tuple[tuple[float, str], ...] = ()

    def reaction(self, joint: str) -> np.ndarray:
        """One joint's reaction over the motion.

        Args:
            joint: a joint (tree or cut).

        Returns:
            (N, 6) world wrenches [f (N), m (N m)], parent side on child side at the joint point.

        Raises:
            MalformedDescription: no such joint.
        """
        return self.reactions[:, self._joint(joint)]

    def effort(self, joint: str) -> np.ndarray:
        """One driven joint's effort over the motion.

        Args:
            joint: a driven joint (`effort_names`).

        Returns:
            (N,) efforts, N m or N.

        Raises:
            MalformedDescription: not a driven joint.
        """
        if joint not in self.effort_names:
            raise MalformedDescription(
                f"motion of {self.mechanism}", f"no effort {joint!r}; driven: {self.effort_names}"
            )
        return self.efforts[:, self.effort_names.index(joint)]

    def _joint(self, joint: str) -> int:
        if joint not in self.joints:
            raise MalformedDescription(f"motion of {self.mechanism}", f"no joint {joint!r}; joints: {self.joints}")
        return self.joints.index(joint)

    # ------------------------------------------------------------ table form
    def columns(self) -> dict[str, np.ndarray]:
        """Column name -> (N,) values, in table order."""
        cols: dict[str, np.ndarray] = {"t": self.t}
        for prefix, x in (("q", self.q), ("v", self.v), ("a", self.a)):
            names = self.coordinates if x.shape[1] == len(self.coordinates) else [str(k) for k in range(x.shape[1])]
            cols.update({f"{prefix}/{n}": x[:, k] for k, n in enumerate(names)})
        cols.update({f"effort/{n}": self.efforts[:, k] for k, n in enumerate(self.effort_names)})
        for j, joint in enumerate(self.joints):
            cols.update({f"reaction/{joint}/{c}": self.reactions[:, j, k] for k, c in enumerate(COMPONENTS)})
            cols.update({f"axis/{joint}/{c}": self.axes[:, j, k] for k, c in enumerate(AXES)})
        if self.determinate is not None:
            for j, joint in enumerate(self.joints):
                cols.update({f"determinate/{joint}/{c}": self.determinate[:, j, k] for k, c in enumerate(COMPONENTS)})
        return cols

    def metadata(self) -> dict[str, str]:
        """The table's metadata (strings; lists as JSON)."""
        return {
            "mechanism": self.mechanism,
            "source": self.source,
            "actuated": json.dumps(list(self.actuated)),
            "coordinates": json.dumps(list(self.coordinates)),
            "joints": json.dumps(list(self.joints)),
            "supports": json.dumps([bool(s) for s in self.supports]),
            "failures": json.dumps([[t, why] for t, why in self.failures]),
        }

    def to_dataframe(self) -> pd.DataFrame:
        """A pandas DataFrame, one row per sample (metadata in `attrs`)."""
        df = pandas().DataFrame(self.columns())
        df.attrs.update(self.metadata())
        return df

    @classmethod
    def from_dataframe(cls, df: pd.DataFrame) -> MotionResult:
        """The result back from its table (`to_dataframe`, `read_parquet`, `read_csv`).

        Args:
            df: the table, its metadata in `df.attrs`.

        Returns:
            The result.

        Raises:
            MalformedDescription: a column or a metadata entry is missing.
        """
        missing = [k for k in META if k not in df.attrs]
        if missing or "t" not in df.columns:
            raise MalformedDescription("motion table", f"missing metadata {missing} or the column 't'")
        meta = {k: json.loads(df.attrs[k]) if k not in ("mechanism", "source") else df.attrs[k] for k in META}
        joints = tuple(meta["joints"])

        def block(prefix: str, names, comps=None) -> np.ndarray:
            cols = [f"{prefix}/{n}" + (f"/{c}" if c else "") for n in names for c in (comps or [None])]
            absent = [c for c in cols if c not in df.columns]
            if absent:
                raise MalformedDescription("motion table", f"missing columns {absent[:3]}")
            x = df[cols].to_numpy()
            return x.reshape(len(df), len(names), len(comps)) if comps else x

        def names(prefix: str) -> list[str]:
            return [c.split("/", 1)[1] for c in df.columns if c.startswith(prefix + "/")]

        determinate = None
        if any(c.startswith("determinate/") for c in df.columns):
            determinate = block("determinate", joints, COMPONENTS).astype(bool)
        effort_names = tuple(names("effort"))
        return cls(
            meta["mechanism"],
            meta["source"],
            df["t"].to_numpy(dtype=float),
            tuple(meta["coordinates"]),
            block("q", names("q")).astype(float),
            block("v", names("v")).astype(float),
            block("a", names("a")).astype(float),
            effort_names,
            tuple(meta["actuated"]),
            block("effort", effort_names).astype(float),
            joints,
            np.array(meta["supports"], dtype=bool),
            block("reaction", joints, COMPONENTS).astype(float),
            block("axis", joints, AXES).astype(float),
            determinate,
            tuple((float(t), str(why)) for t, why in meta["failures"]),
        )


def pyarrow() -> ModuleType:
    """The pyarrow module (Parquet, the `motion` extra), or a `MethodUnavailable` naming the install."""
    try:
        import pyarrow as pa
    except ImportError:
        raise MethodUnavailable("Parquet", "pyarrow is not installed: pip install 'mechkit[motion]'") from None
    return pa


def write_parquet(result: MotionResult, path: str | Path) -> Path:
    """Write the table as Parquet (pyarrow), metadata in the schema; atomic.

    Args:
        result: the study.
        path: the file.

    Returns:
        The path written.

    Raises:
        MethodUnavailable: pandas or pyarrow is not installed.
        OutputError: the file cannot be written.
    """
    pyarrow()
    df = result.to_dataframe()
    buffer = io.BytesIO()
    df.to_parquet(buffer, engine="pyarrow", index=False)
    return write_bytes(path, buffer.getvalue())


def read_parquet(path: str | Path) -> MotionResult:
    """A result written by `write_parquet`.

    Args:
        path: the file.

    Returns:
        The result.

    Raises:
        MalformedDescription: the file cannot be read, or is not a motion table.
    """
    try:
        df = pandas().read_parquet(path, engine="pyarrow")
    except (OSError, ValueError) as err:
        raise MalformedDescription(str(path), f"cannot read the motion table ({err})") from None
    return MotionResult.from_dataframe(df)


def write_csv(result: MotionResult, path: str | Path) -> Path:
    """Write the table as CSV (floats to full precision), metadata as leading `# key: value` lines; atomic.

    Args:
        result: the study.
        path: the file.

    Returns:
        The path written.

    Raises:
        MethodUnavailable: pandas is not installed.
        OutputError: the file cannot be written.
    """
    df = result.to_dataframe()
    header = "".join(f"# {k}: {v}\n" for k, v in result.metadata().items())
    return write_text(path, header + df.to_csv(index=False))


def read_csv(path: str | Path) -> MotionResult:
    """A result written by `write_csv`.

    Args:
        path: the file.

    Returns:
        The result.

    Raises:
        MalformedDescription: the file cannot be read, or is not a motion table.
    """
    pd = pandas()
    try:
        with Path(path).open() as handle:
            lines = handle.read().splitlines(keepends=True)
    except OSError as err:
        raise MalformedDescription(str(path), f"cannot read the motion table ({err.strerror})") from None
    meta = dict(line[2:].rstrip("\n").split(": ", 1) for line in lines if line.startswith("# ") and ": " in line)
    body = "".join(line for line in lines if not line.startswith("#"))
    df = pd.read_csv(io.StringIO(body))
    df.attrs.update(meta)
    return MotionResult.from_dataframe(df)
