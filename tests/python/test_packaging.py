"""The Python package as its users expect it: console scripts, gymnasium registration, SB3's
info["is_success"], help text on every flag."""

import argparse
import importlib
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import guidewire_nav
from guidewire_nav.env import find_server_binary

REPO = Path(__file__).resolve().parents[2]
SCRIPTS = tomllib.loads((REPO / "training" / "pyproject.toml").read_text())["project"]["scripts"]


def test_console_scripts_name_the_tools():
    assert {"gw-train", "gw-export", "gw-score-checkpoints"} <= set(SCRIPTS)
    for name, target in SCRIPTS.items():
        module, _, func = target.partition(":")
        assert callable(getattr(importlib.import_module(module), func)), name


@pytest.mark.parametrize("name", sorted(SCRIPTS))
def test_console_script_help_runs(name):
    # The installed wrapper when `pip install -e training` made it, else the same entry point in-process.
    wrapper = Path(sys.executable).parent / name
    if wrapper.is_file():
        cmd = [str(wrapper), "--help"]
    else:
        module, _, func = SCRIPTS[name].partition(":")
        cmd = [sys.executable, "-c", f"import sys; from {module} import {func}; sys.argv[0] = {name!r}; {func}()",
               "--help"]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("usage:"), done.stdout[:200]


class _Parsed(Exception):
    pass


@pytest.mark.parametrize("name", sorted(SCRIPTS))
def test_every_flag_has_help_text(name, monkeypatch):
    """The parser each main() builds, caught at parse_args: every option (and positional) says what it is."""
    caught = []

    def catch(self, *args, **kwargs):
        caught.append(self)
        raise _Parsed

    monkeypatch.setattr(argparse.ArgumentParser, "parse_args", catch)
    monkeypatch.setattr(sys, "argv", [name])
    module, _, func = SCRIPTS[name].partition(":")
    with pytest.raises(_Parsed):
        getattr(importlib.import_module(module), func)()
    missing = [a.option_strings or a.dest for a in caught[0]._actions
               if not isinstance(a, argparse._HelpAction) and not (a.help or "").strip()]
    assert not missing, f"{name}: flags without help text: {missing}"


def test_train_flags_follow_the_settings():
    from guidewire_nav.train import Settings, parse_settings, settings_parser

    flags = {a.dest: a for a in settings_parser()._actions if a.option_strings and a.dest != "help"}
    assert set(flags) == set(Settings.__dataclass_fields__)
    assert all(a.help and a.help.strip() for a in flags.values())
    assert parse_settings([]) == Settings()
    s = parse_settings(["--total-steps", "300", "--no-progress", "--task", "training/tasks/paper.json",
                        "--actor-learning-rate", "1e-5"])
    assert (s.total_steps, s.progress, s.task, s.actor_learning_rate) == (300, False, "training/tasks/paper.json", 1e-5)


def test_train_defines_no_class_inside_main():
    """CleanRL-style: main reads top to bottom; the SAC subclass and the callbacks live at module level."""
    import ast

    tree = ast.parse((REPO / "training" / "guidewire_nav" / "train.py").read_text())
    main = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "main")
    assert not [n for n in ast.walk(main) if isinstance(n, (ast.ClassDef, ast.FunctionDef)) and n is not main]
    top = {n.name for n in tree.body if isinstance(n, ast.ClassDef)}
    assert {"SACWithActorRate", "ActorUpdates", "EvalCallback"} <= top


def test_actor_rate_survives_load_and_is_not_saved(tmp_path):
    import gymnasium as gym
    from stable_baselines3 import SAC
    from stable_baselines3.common.logger import configure

    from guidewire_nav.train import SACWithActorRate

    class Box(gym.Env):
        observation_space = gym.spaces.Box(-1, 1, (3,), np.float32)
        action_space = gym.spaces.Box(-1, 1, (1,), np.float32)

    model = SACWithActorRate("MlpPolicy", Box(), actor_learning_rate=1e-6, learning_rate=1e-4, device="cpu")
    model.set_logger(configure(None, []))  # _update_learning_rate records the rate
    model._update_learning_rate([model.actor.optimizer, model.critic.optimizer])
    assert model.actor.optimizer.param_groups[0]["lr"] == 1e-6
    assert model.critic.optimizer.param_groups[0]["lr"] == 1e-4
    model.save(tmp_path / "m.zip")
    assert not hasattr(SAC.load(tmp_path / "m.zip", device="cpu"), "actor_learning_rate")
    loaded = SACWithActorRate.load(tmp_path / "m.zip", device="cpu", actor_learning_rate=2e-6)
    loaded.set_logger(configure(None, []))
    loaded._update_learning_rate([loaded.actor.optimizer])
    assert loaded.actor.optimizer.param_groups[0]["lr"] == 2e-6


def test_gym_make_steps_and_reports_is_success():
    import gymnasium as gym

    if not find_server_binary().is_file():
        pytest.skip(f"guidewire-server not built ({find_server_binary()}); set GW_SERVER_BIN or GW_BUILD_DIR")
    assert guidewire_nav.ENV_ID == "GuidewireNav-v0"
    env = gym.make("GuidewireNav-v0", anatomies="t1_straight_y")
    try:
        assert env.spec.id == "GuidewireNav-v0"
        obs, info = env.reset(seed=4)
        assert env.observation_space.contains(obs)
        done, steps = False, 0
        while not done and steps < 2000:
            obs, reward, terminated, truncated, info = env.step(env.action_space.sample() * 0)
            assert info["is_success"] == info["success"] and isinstance(info["is_success"], bool)
            done, steps = terminated or truncated, steps + 1
        assert done, "the server ends every episode itself (no TimeLimit wrapper)"
        assert info["is_success"] == (info["success"] is True)
    finally:
        env.close()
