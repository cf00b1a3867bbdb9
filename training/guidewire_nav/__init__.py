"""Training side of zero-shot guidewire navigation.

The C++ simulator serves environments over a socket; this package holds the
gymnasium client, SB3 SAC training, actor export to JSON and plots.
"""

from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_DIR = REPO_ROOT / "build"
