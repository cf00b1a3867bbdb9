"""The Python baselines: the scripted omega rule is the C++ one, and a short run reports what it did."""

import numpy as np
import pytest

from guidewire_nav import baselines
from guidewire_nav.env import find_server_binary


def test_scripted_rule_is_the_cpp_one():
    c = baselines.OmegaController()
    obs = np.zeros(12, dtype=np.float32)
    for omega, action in [(1.0, 1.0), (0.0, 1.0), (-0.9, 1.0), (-0.94, 1.0), (-0.96, 0.0), (-0.99, 0.0)]:
        obs[baselines.OMEGA] = omega
        assert c(obs) == action, omega
    assert baselines.PushOnly()(obs) == 0.0
    mirrored = baselines.OmegaControllerCCW()
    for omega, action in [(0.0, -1.0), (-0.94, -1.0), (-0.96, 0.0)]:
        obs[baselines.OMEGA] = omega
        assert mirrored(obs) == action, omega


def test_unknown_controller_is_named():
    with pytest.raises(ValueError, match="omega_scripted_cw"):
        baselines.evaluate(["omega_scripted_cw"], ["t1_straight_y"], episodes=1, seed=0, workers=1, env_kwargs={})


def test_short_run_on_a_training_pattern():
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    s = baselines.evaluate(["push_only", "omega_scripted"], ["t1_straight_y"], episodes=4, seed=0, workers=1,
                           env_kwargs={"anatomies": "t1_straight_y"})
    scripted = s["controllers"]["omega_scripted"]
    push = s["controllers"]["push_only"]
    assert scripted["episodes"] == push["episodes"] == 4
    # t1 is reached by the scripted rule from every start in the results table (100 of 100 training episodes).
    assert scripted["successes"] == 4
    assert scripted["per_anatomy"]["t1_straight_y"]["physics_problem"] == 0
    assert 0 <= push["successes"] <= 4
