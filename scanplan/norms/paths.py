"""Where norm sets live: the bundled folder and the user's norm directory."""

from __future__ import annotations

import os
from pathlib import Path

DEFAULT_NORM_SET = "gkinp-02-036-02"
CATALOGUE = "catalogue"


def bundled_norms_dir() -> Path:
    """Folder holding the bundled norm sets and the catalogue."""
    here = Path(__file__).resolve().parent.parent  # the scanplan package
    for candidate in (here / "_data" / "norms", here.parent / "norms"):
        if (candidate / DEFAULT_NORM_SET).is_dir():
            return candidate
    raise RuntimeError(  # a broken installation, not a user error
        f"scanplan's bundled norms are missing (looked in {here / '_data' / 'norms'} and "
        f"{here.parent / 'norms'}); reinstall scanplan"
    )


def user_norms_dir() -> Path:
    """Folder where ``scanplan norms import`` puts user norm sets: ``SCANPLAN_NORMS_DIR``,
    else ``norms`` in the platform's user data folder (platformdirs: Linux
    ``$XDG_DATA_HOME/scanplan`` or ``~/.local/share/scanplan``, macOS
    ``~/Library/Application Support/scanplan``, Windows ``%LOCALAPPDATA%\\scanplan``)."""
    env = os.environ.get("SCANPLAN_NORMS_DIR")
    if env:
        return Path(env).expanduser()
    import platformdirs

    return platformdirs.user_data_path("scanplan", appauthor=False) / "norms"

