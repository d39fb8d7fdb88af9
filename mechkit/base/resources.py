"""Where the packaged files are: the xacro templates and the generated URDFs.

The repository keeps them in its top-level `xacro/` and `urdf/` folders; `mechkit/xacro` and
`mechkit/urdf` link to them, so the wheel and the sdist carry copies as package data and an editable
install reads the folders themselves. Either way they are found through `importlib.resources`, never
beside the package directory.
"""

from __future__ import annotations

from importlib.resources import as_file, files
from pathlib import Path


def _folder(name: str) -> Path:
    with as_file(files("mechkit") / name) as path:  # a real folder for wheel, sdist and editable installs
        return Path(path)


def xacro_dir() -> Path:
    """The folder of the xacro templates (`<name>.urdf.xacro` and shared macros)."""
    return _folder("xacro")


def urdf_dir() -> Path:
    """The folder of the URDFs generated at the default parameters (`<name>.urdf`)."""
    return _folder("urdf")
