"""Reading a self-contained meshcat page back: the commands it replays, and the objects they set."""

from __future__ import annotations

import base64
import re

import pytest

umsgpack = pytest.importorskip("umsgpack")


def commands(html: str) -> list[dict]:
    """The meshcat commands a page replays."""
    block = html.split("const commands = [", 1)[1].split("];", 1)[0]
    return [umsgpack.unpackb(base64.b64decode(b)) for b in re.findall(r'"([A-Za-z0-9+/=]+)"', block)]


def objects(cmds: list[dict]) -> dict[str, int]:
    """meshcat path -> colour of every object set."""
    out = {}
    for c in cmds:
        if c["type"] == "set_object":
            materials = c["object"]["materials"]
            out[c["path"]] = materials[0]["color"]
    return out


def page_objects(html: str) -> dict[str, dict]:
    """meshcat path -> object of every set_object command of a page."""
    return {c["path"]: c["object"] for c in commands(html) if c["type"] == "set_object"}
