"""The files a description is read from: the file itself, its Extended-URDF sidecar, and the local files it
includes or names (xacro includes, MJCF includes, SDFormat includes, mesh and texture files), so that a
command can refuse to write over any of them (`mechkit.cli.output_guard`).

A reference this module cannot resolve to a local file (a `package://` or `model://` address, a xacro
substitution such as `$(find pkg)`, a network address) is left out: the readers resolve or refuse those;
what is listed here is what a write could destroy. Names are resolved as the tools that read them do: a
xacro include's glob pattern names every file it matches (xacro includes them all), and an MJCF include
is looked for beside the main file first, then beside the including file (MuJoCo 4's order).
"""

from __future__ import annotations

import glob
import re
import xml.etree.ElementTree as ET
from pathlib import Path

from mechkit.sources.extended_urdf import sidecar_of

#: Attributes naming another local file, by element tag (namespace removed), in every XML format read.
_FILE_ATTRIBUTES = {
    "include": ("filename", "file"),  # xacro:include, MJCF include
    "mesh": ("filename", "file"),  # URDF and MJCF meshes
    "texture": ("file",),
    "hfield": ("file",),
    "skin": ("file",),
}
#: Elements whose text names another file (SDFormat's include and mesh uri).
_FILE_TEXT = ("uri",)
#: A xacro include name xacro expands with glob (xacro's own test).
_GLOB = re.compile(r"[*?[]")
#: A reference that is not a plain local path: a URL scheme other than file://, or a xacro substitution.
_NOT_LOCAL = re.compile(r"^[a-z][a-z0-9+.-]*://(?<!file://)|\$\{|\$\(", re.IGNORECASE)


def description_files(path: str | Path) -> list[Path]:
    """Every local file a description is read from, resolved (symlinks followed), the file itself first.

    Args:
        path: the description's file (.urdf, .xacro, .xml, .sdf); it need not be valid XML.

    Returns:
        The resolved files that exist, without repeats: the description, its sidecar (.yaml, Extended
        URDF), and every included or named file (recursively through includes).
    """
    first = Path(path).expanduser().resolve()
    seen: list[Path] = []
    pending = [first]
    while pending:
        current = pending.pop(0)
        if current in seen or not current.is_file():
            continue
        seen.append(current)
        if current.suffix == ".urdf" and (sidecar := sidecar_of(current)) is not None:
            pending.append(sidecar.resolve())
        if current.suffix in (".urdf", ".xacro", ".xml", ".sdf", ".mjcf"):
            pending.extend(_named_files(current, first.parent))
    return seen


def _named_files(path: Path, main_folder: Path) -> list[Path]:
    """The local files an XML file names (relative to its folder; an MJCF include to the main file's
    folder first), unparsable XML naming none."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError, UnicodeDecodeError):
        return []
    compiler = root.find("compiler")  # MJCF: meshes and textures relative to meshdir / texturedir / assetdir
    asset_dir = {} if compiler is None else compiler.attrib
    out = []
    for element in root.iter():
        tag = element.tag.rsplit("}", 1)[-1] if isinstance(element.tag, str) else ""
        names = [element.get(a) for a in _FILE_ATTRIBUTES.get(tag, ())]
        if tag in _FILE_TEXT:
            names.append(element.text)
        folder = path.parent / asset_dir.get(f"{tag}dir", asset_dir.get("assetdir", ""))
        for name in names:
            if name and not _NOT_LOCAL.search(name.strip()):
                local = Path(name.strip().removeprefix("file://")).expanduser()
                if tag == "include" and element.get("filename") and _GLOB.search(str(local)):
                    out += [Path(p).resolve() for p in sorted(glob.glob(str(folder / local)))]
                    continue
                mjcf_main = tag == "include" and element.get("file") and (main_folder / local).is_file()
                base = main_folder if mjcf_main else folder  # MuJoCo reads the main file's folder first
                out.append((local if local.is_absolute() else base / local).resolve())
    return out
