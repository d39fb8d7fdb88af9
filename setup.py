"""Packaging beyond pyproject.toml: the repository's top-level `xacro/` and `urdf/` folders ship inside
the wheel as the packages `mechkit.xacro` and `mechkit.urdf` (read with `importlib.resources`), for
wheel, sdist and editable installs alike."""

from setuptools import find_packages, setup

DATA_PACKAGES = {"mechkit.xacro": "xacro", "mechkit.urdf": "urdf"}

setup(
    packages=find_packages(include=["mechkit", "mechkit.*"]) + list(DATA_PACKAGES),
    package_dir=DATA_PACKAGES,
    package_data={"mechkit": ["py.typed"], "mechkit.xacro": ["*.xacro"], "mechkit.urdf": ["*.urdf"]},
)
