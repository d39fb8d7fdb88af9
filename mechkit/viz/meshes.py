"""Mesh visuals of a URDF: where their files are, and what stands in for a missing one.

A `<mesh filename=...>` is looked up, in order: an absolute path (or `file://` address) as is; a
relative path against the URDF's own folder, then each folder of the search path; a
`package://PKG/sub/path` address in each search-path folder as `DIR/PKG/sub/path`, then as
`DIR/sub/path` (a folder that is the package itself). A mesh not found is a `MissingMesh` warning and a
placeholder sphere drawn in MISSING colour; drawing goes on.

Pinocchio names a link's visuals `<link>_<k>` (k counts that link's visuals from 0); placeholders are
named the same way, so the drawing can find them.
"""

from __future__ import annotations

import os
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from mechkit.base.exceptions import MalformedDescription

MISSING = (1.0, 0.0, 1.0, 1.0)  # colour of the placeholder of a missing mesh (ours)
MESH_FORMATS = {".stl": "StlMeshGeometry", ".obj": "ObjMeshGeometry", ".dae": "DaeMeshGeometry"}


class MissingMesh(UserWarning):
    """A mesh file of a URDF visual was not found; a placeholder is drawn instead."""


@dataclass(frozen=True)
class MeshSearch:
    """Where mesh files are looked for.

    Attributes:
        base: the URDF's own folder (relative file names), or None for URDF text without a file.
        path: further folders, searched for relative names and `package://` addresses.
    """

    base: Path | None = None
    path: tuple[Path, ...] = ()

    @classmethod
    def of(cls, base: str | os.PathLike | None = None, path: Sequence[str | os.PathLike] = ()) -> MeshSearch:
        """A search from a URDF's folder and other folders.

        Args:
            base: the URDF's folder (relative names are looked for there first), or None.
            path: further folders, in order.

        Returns:
            The search.
        """
        return cls(None if base is None else Path(base), tuple(Path(p) for p in path))

    def resolve(self, filename: str) -> Path | None:
        """The existing file a URDF mesh `filename` names, or None when it is nowhere to be found.

        Args:
            filename: the mesh's file name as the URDF gives it (absolute, relative, file:// or package://).

        Returns:
            The existing file, or None when it is nowhere to be found.
        """
        if filename.startswith("package://"):
            package, _, rest = filename[len("package://") :].partition("/")
            candidates = [d / package / rest for d in self.path] + [d / rest for d in self.path]
        else:
            name = Path(filename.removeprefix("file://"))
            folders = ([self.base] if self.base is not None else []) + list(self.path)
            candidates = [name] if name.is_absolute() else [d / name for d in folders]
        return next((c.resolve() for c in candidates if c.is_file()), None)

    def where(self) -> str:
        """The folders searched, for messages."""
        folders = ([self.base] if self.base is not None else []) + list(self.path)
        return ", ".join(str(f) for f in folders) or "no folder (give a search path)"


def resolve_meshes(urdf: str, search: MeshSearch, placeholder_radius: float) -> tuple[str, set[str]]:
    """The URDF with every visual mesh's file name made absolute, and missing meshes replaced.

    Args:
        urdf: URDF text.
        search: where mesh files are looked for.
        placeholder_radius: radius of the sphere standing in for a missing mesh (m).

    Returns:
        (URDF text for `pin.buildGeomFromUrdfString`, names of the placeholder visuals as Pinocchio
        names them). The text is returned unchanged when it has no mesh visual.

    Raises:
        MalformedDescription: the URDF text is not XML.

    Warns:
        MissingMesh: once per mesh not found, naming the link, the file and the folders searched.
    """
    if "<mesh" not in urdf:
        return urdf, set()
    try:
        root = ET.fromstring(urdf)
    except ET.ParseError as err:
        raise MalformedDescription("URDF", f"not XML: {err}") from None
    placeholders = set()
    for link in root.iter("link"):
        for k, visual in enumerate(link.findall("visual")):
            geometry = visual.find("geometry")
            mesh = None if geometry is None else geometry.find("mesh")
            if mesh is None:
                continue
            filename = mesh.get("filename", "")
            found = search.resolve(filename)
            if found is not None:
                mesh.set("filename", str(found))
                continue
            warnings.warn(
                f"link {link.get('name')!r}: mesh {filename!r} not found (searched {search.where()}); "
                f"drawn as a placeholder",
                MissingMesh,
                stacklevel=3,
            )
            geometry.remove(mesh)
            ET.SubElement(geometry, "sphere", radius=repr(float(placeholder_radius)))
            placeholders.add(f"{link.get('name')}_{k}")
    return ET.tostring(root, encoding="unicode"), placeholders


def mesh_geometry(geometry_module: ModuleType, path: str, vertices: np.ndarray, bvh: Any) -> Any:
    """The meshcat geometry of a mesh file: read from the file for STL, OBJ and DAE, else built from the
    triangles Pinocchio loaded (`vertices` (N, 3) in the file's units, `bvh` coal's mesh).

    Args:
        geometry_module: `meshcat.geometry`.
        path: the mesh file.
        vertices: the mesh's vertices (N, 3), in the file's units, as Pinocchio loaded them.
        bvh: coal's mesh (its triangles).

    Returns:
        The meshcat geometry.
    """
    kind = MESH_FORMATS.get(Path(path).suffix.lower())
    if kind is not None:
        return getattr(geometry_module, kind).from_file(path)
    triangles = np.array([[t[0], t[1], t[2]] for t in map(bvh.tri_indices, range(bvh.num_tris))], dtype=np.uint32)
    return geometry_module.TriangularMeshGeometry(vertices, triangles.reshape(-1, 3))
