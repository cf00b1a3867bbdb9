"""Training side of zero-shot guidewire navigation.

The C++ simulator serves environments over a socket; this package holds the
gymnasium client, SB3 SAC training, actor export to JSON and plots.
"""

import os
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_DIR = REPO_ROOT / "build"


def app_path(name: str) -> Path:
    """A C++ executable of apps/: <$GW_BUILD_DIR, else BUILD_DIR>/apps/<name> (it may not be built)."""
    return Path(os.environ.get("GW_BUILD_DIR", BUILD_DIR)) / "apps" / name
