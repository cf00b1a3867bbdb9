"""Reproducible, interruptible training (issue 37 item 5): a simulation server that dies does not end the
run (its episode ends truncated, a new server takes over), and --resume continues a run from its latest
checkpoint with its replay buffer and step counter."""

import json
import signal

import numpy as np
import pytest

from guidewire_nav.env import GuidewireEnv, RestartingEnv, find_server_binary


@pytest.fixture(autouse=True)
def _server_built():
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")


def test_a_dying_server_is_replaced_and_the_cut_episode_ends_truncated():
    env = RestartingEnv(lambda: GuidewireEnv(anatomies="t1_straight_y"), name="test server")
    try:
        env.reset(seed=3)
        for _ in range(3):
            obs, _, terminated, truncated, _ = env.step([0.2])
            assert not (terminated or truncated)
        first = env.env._proc
        first.send_signal(signal.SIGKILL)
        first.wait()
        obs2, reward, terminated, truncated, info = env.step([0.2])
        assert truncated and not terminated and info["server_restarted"] and reward == 0.0
        assert (obs2 == obs).all()  # the last observation the lost episode had
        assert env.restarts == 1 and env.env._proc is not first and env.env._proc.poll() is None
        env.reset()  # the seeded stream goes on, on the new server
        _, _, terminated, truncated, info = env.step([0.2])
        assert not truncated and "server_restarted" not in info
    finally:
        env.close()


def _train(out, *extra):
    from guidewire_nav import train

    return train.main(["--out", str(out), "--anatomies", "t1_straight_y", "--learning-starts", "60",
                       "--envs", "1", "--eval-episodes", "0", "--checkpoint-every", "60", "--no-progress", *extra])


def test_resume_continues_the_run_from_its_checkpoint(tmp_path):
    out = tmp_path / "run"
    assert _train(out, "--total-steps", "120") == 0
    assert json.loads((out / "summary.json").read_text())["steps"] == 120
    assert (out / "checkpoints" / "sac_replay_buffer_120_steps.pkl").is_file()
    assert (out / "final_replay_buffer.pkl").is_file()

    # other settings than the run's: refused, naming them; nothing of the run is touched
    with pytest.raises(SystemExit, match="seed = 5 \\(run: 0\\)"):
        _train(out, "--total-steps", "180", "--seed", "5", "--resume")
    with pytest.raises(SystemExit, match="not beyond it"):
        _train(out, "--total-steps", "120", "--resume")

    import torch

    threads = torch.get_num_threads()
    try:  # torch's thread count is the machine's, not the run's: a resumed part may set its own
        assert _train(out, "--total-steps", "180", "--resume", "--torch-threads", "1") == 0
        assert torch.get_num_threads() == 1
    finally:
        torch.set_num_threads(threads)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["steps"] == 180 and summary["resumed_at_steps"] == [120]
    settings = json.loads((out / "settings.json").read_text())
    assert settings["total_steps"] == 120 and settings["resumed"][0]["at_step"] == 120  # the run's own, then each part
    assert (out / "checkpoints" / "sac_180_steps.zip").is_file()
    assert (out / "monitor.monitor.csv").is_file() and (out / "monitor_from_120.monitor.csv").is_file()

    from stable_baselines3 import SAC

    model = SAC.load(out / "final_model.zip", device="cpu")
    model.load_replay_buffer(out / "final_replay_buffer.pkl")
    assert model.num_timesteps == 180
    assert model.replay_buffer.size() == 180  # the 120 transitions it had, and the 60 after


def test_a_resumed_fine_tune_goes_on_with_its_own_actor_anchored_to_its_start(tmp_path):
    """--resume of an --init-actor run continues from the checkpoint's actor (not the start's again), while the
    anchor still pulls towards the actor the run started from. A fast actor rate moves the actor far in the first
    part; the resumed part, cut after a moment by --max-minutes (a few steps, as many as the machine's speed lets it
    take, each moving the actor at that rate), ends nearer that actor than the start."""
    import torch
    from stable_baselines3 import SAC
    from guidewire_nav.train import anchor_loss

    start_run = tmp_path / "start"
    assert _train(start_run, "--total-steps", "60") == 0
    tune = ["--init-actor", str(start_run / "actor.json"), "--actor-learning-rate", "3e-2", "--anchor-weight", "0.001"]
    out = tmp_path / "tuned"
    assert _train(out, "--total-steps", "120", *tune) == 0
    assert _train(out, "--total-steps", "100000", "--resume", "--max-minutes", "0.001", *tune) == 0

    load = lambda path: SAC.load(path, device="cpu").actor  # noqa: E731
    start, part1, last = load(start_run / "final_model.zip"), load(out / "checkpoints" / "sac_120_steps.zip"), \
        load(out / "final_model.zip")
    obs = torch.as_tensor(np.random.default_rng(0).uniform(-1, 1, (256, start.observation_space.shape[0])),
                          dtype=torch.float32)
    with torch.no_grad():
        moved = anchor_loss(part1, start, obs).item()
        assert moved > 1e-3  # the first part left its start
        went_on = anchor_loss(last, part1, obs).item()
        assert went_on < 0.5 * anchor_loss(last, start, obs).item()  # the resumed part went on from there


def test_resume_counts_the_transitions_of_every_env(tmp_path, capsys):
    # Two envs fill one buffer row per vector step with two transitions: 120 steps are 120 transitions, not 60.
    out = tmp_path / "run2"
    assert _train(out, "--total-steps", "120", "--envs", "2") == 0
    capsys.readouterr()
    assert _train(out, "--total-steps", "160", "--envs", "2", "--resume") == 0
    assert "at step 120 (120 transitions in the replay buffer)" in capsys.readouterr().err
