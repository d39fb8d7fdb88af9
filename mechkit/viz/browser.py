"""Screenshots of a page in headless Chromium (WebGL through SwiftShader, no GPU, no display, offline).

Only an explicit `screenshot` call starts the browser; it runs headless, with a fresh throw-away
profile, and ends with the call. The browser is `$MECHKIT_CHROMIUM` if set, else the first of
chromium, chromium-browser, google-chrome, google-chrome-stable on PATH (Debian: `apt-get install
chromium`).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from collections.abc import Sequence
from pathlib import Path

from mechkit.base.atomic import resolve_output, write_bytes
from mechkit.base.exceptions import ExternalToolFailed, InvalidArgument, MethodUnavailable

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--enable-unsafe-swiftshader",
    "--use-angle=swiftshader",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--hide-scrollbars",
    "--mute-audio",
)


def find_chromium() -> str:
    """Path of the Chromium executable.

    Raises:
        MethodUnavailable: no Chromium found (the message says where it looked and how to install it).
    """
    chosen = os.environ.get("MECHKIT_CHROMIUM")
    if chosen:
        found = shutil.which(chosen)
        if found is None:
            raise MethodUnavailable("PNG screenshot", f"MECHKIT_CHROMIUM={chosen!r} is not an executable")
        return found
    for name in CANDIDATES:
        found = shutil.which(name)
        if found is not None:
            return found
    raise MethodUnavailable(
        "PNG screenshot",
        f"needs the Chromium browser, not found on PATH (looked for "
        f"{', '.join(CANDIDATES)}; or set MECHKIT_CHROMIUM); on Debian: apt-get install chromium",
    )


def screenshot(
    page: str | os.PathLike,
    png: str | os.PathLike,
    size: Sequence[int] = (800, 600),
    budget_ms: int = 8000,
    timeout: float = 180.0,
) -> Path:
    """Render a local HTML file (or a page served on this machine) in headless Chromium and write its screenshot.

    A file is opened with `#capture` appended to its address (mechkit pages then hide their controls).

    Args:
        page: the HTML file, or an http:// address (e.g. a live viewer's `url`).
        png: the PNG to write (replaced atomically; nothing is left when the browser fails).
        size: window width and height (pixels).
        budget_ms: virtual time the page may run before the picture is taken (ms).
        timeout: wall-clock limit of the browser run (s).

    Returns:
        The PNG's path.

    Raises:
        MethodUnavailable: no Chromium.
        InvalidArgument: the page does not exist.
        ExternalToolFailed: the browser failed or wrote no picture (with its last output lines).
    """
    executable = find_chromium()
    served = str(page).startswith("http://")
    source = Path(page).resolve() if not served else None
    if source is not None and not source.is_file():
        raise InvalidArgument("page", str(page), f"no page at {source}")
    target = Path(png)
    resolve_output(target)  # refuse a directory, a device, a FIFO before the browser runs
    with tempfile.TemporaryDirectory(prefix="mechkit-chromium-") as tmp:
        shot = Path(tmp) / "shot.png"
        command = [
            executable,
            *FLAGS,
            f"--user-data-dir={Path(tmp) / 'profile'}",
            f"--window-size={int(size[0])},{int(size[1])}",
            f"--virtual-time-budget={int(budget_ms)}",
            f"--screenshot={shot}",
            str(page) if served else source.as_uri() + "#capture",
        ]
        try:
            run = subprocess.run(
                command, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL, check=False
            )
        except subprocess.TimeoutExpired:
            raise ExternalToolFailed(executable, f"the screenshot did not finish within {timeout:.0f} s") from None
        if not shot.is_file() or shot.stat().st_size == 0:
            tail = "\n".join((run.stderr or run.stdout).strip().splitlines()[-5:])
            raise ExternalToolFailed(executable, f"exited with {run.returncode} and wrote no picture:\n{tail}")
        write_bytes(target, shot.read_bytes())
    return target


def coverage(png: str | os.PathLike, tolerance: int = 12) -> tuple[tuple[int, int, int], float]:
    """The dominant colour of a picture (its background) and the fraction of pixels that differ from it.

    Args:
        png: the picture.
        tolerance: largest difference in any channel (0..255) still counted as background.

    Returns:
        (background rgb 0..255, fraction of the other pixels).

    Raises:
        MethodUnavailable: Pillow is not installed.
    """
    try:
        import numpy as np
        from PIL import Image
    except ImportError:
        raise MethodUnavailable("reading PNG pictures", "Pillow is not installed: pip install pillow") from None
    with Image.open(png) as image:
        rgb = np.asarray(image.convert("RGB")).reshape(-1, 3).astype(int)
    colours, counts = np.unique(rgb, axis=0, return_counts=True)
    background = colours[np.argmax(counts)]
    differs = np.any(np.abs(rgb - background) > tolerance, axis=1)
    return tuple(int(c) for c in background), float(differs.mean())
