"""Training side of zero-shot guidewire navigation.

The C++ simulator serves environments over a socket; this package holds the
gymnasium client, SB3 SAC training, actor export to JSON and plots.

Importing it registers the environment with gymnasium:

    import gymnasium as gym
    import guidewire_nav  # noqa: F401  (registers "GuidewireNav-v0")
    env = gym.make("GuidewireNav-v0", anatomies="t1_straight_y")  # keyword arguments of env.GuidewireEnv

The command-line tools are console scripts (training/pyproject.toml): gw-train, gw-export, ...
"""

import os
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_DIR = REPO_ROOT / "build"


def app_path(name: str) -> Path:
    """A C++ executable of apps/: <$GW_BUILD_DIR, else BUILD_DIR>/apps/<name> (it may not be built)."""
    return Path(os.environ.get("GW_BUILD_DIR", BUILD_DIR)) / "apps" / name


ENV_ID = "GuidewireNav-v0"


def _register_env() -> None:
    """gym.make(ENV_ID, **GuidewireEnv kwargs). No TimeLimit wrapper: the server ends an episode itself
    (info["step_limit"], reported as truncated)."""
    try:
        from gymnasium.envs.registration import register, registry
    except ImportError:  # a tool run outside the training venv (e.g. vmtk_centerline.py) needs no env
        return
    if ENV_ID not in registry:
        register(id=ENV_ID, entry_point="guidewire_nav.env:GuidewireEnv")


_register_env()
