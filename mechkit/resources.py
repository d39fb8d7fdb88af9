"""Where the packaged files are: the xacro templates and the generated URDFs.

The repository's top-level `xacro/` and `urdf/` folders are installed as the packages `mechkit.xacro`
and `mechkit.urdf` (see `setup.py`), so an installed mechkit reads its own copies, never files
beside its package directory.
"""

from __future__ import annotations

from importlib.resources import as_file, files
from pathlib import Path


def _folder(package: str) -> Path:
    with as_file(files(package)) as path:  # a real folder for wheel, sdist and editable installs
        return Path(path)


def xacro_dir() -> Path:
    """The folder of the xacro templates (`<name>.urdf.xacro` and shared macros)."""
    return _folder("mechkit.xacro")


def urdf_dir() -> Path:
    """The folder of the URDFs generated at the default parameters (`<name>.urdf`)."""
    return _folder("mechkit.urdf")
