"""gw-train --overlap (issue 62 item 4): the gradient steps of an update are taken while the servers simulate
(between a vector step's step_async and its step_wait), spread evenly over the next rollout; the run takes as many
gradient steps as SB3's own loop, the same seed gives the same run, and the model saves and loads as plain SAC."""
import gymnasium as gym
import numpy as np
import pytest
import torch
from stable_baselines3 import SAC
from stable_baselines3.common.logger import configure
from stable_baselines3.common.vec_env import DummyVecEnv

from guidewire_nav.train import SACWithActorRate


class Walk(gym.Env):
    """A seeded 1-D walk: the action moves a point, the reward is how near 0 it is; 10 steps an episode."""
    observation_space = gym.spaces.Box(-10, 10, (3,), np.float32)
    action_space = gym.spaces.Box(-1, 1, (1,), np.float32)

    def reset(self, seed=None, options=None):
        super().reset(seed=seed)
        self.x, self.t = float(self.np_random.uniform(-1, 1)), 0
        return self._obs(), {}

    def _obs(self):
        return np.array([self.x, self.t / 10, 1.0], np.float32)

    def step(self, action):
        self.x += 0.3 * float(action[0])
        self.t += 1
        return self._obs(), -abs(self.x), False, self.t >= 10, {}


class Recording(DummyVecEnv):
    """DummyVecEnv that writes 'send' at each step_async and 'read' at each step_wait into `events`."""

    def __init__(self, events):
        super().__init__([Walk, Walk])
        self.events = events

    def step_async(self, actions):
        self.events.append("send")
        super().step_async(actions)

    def step_wait(self):
        self.events.append("read")
        return super().step_wait()


def run(overlap, events=None, steps=200, seed=3):
    events = [] if events is None else events
    env = Recording(events)
    env.seed(seed)
    model = SACWithActorRate("MlpPolicy", env, learning_starts=40, train_freq=4, gradient_steps=2, batch_size=16,
                             buffer_size=1000, seed=seed, device="cpu", policy_kwargs={"net_arch": [16, 16]},
                             overlap=overlap)
    model.set_logger(configure(None, []))
    model.learn(total_timesteps=steps)
    return model, events


@pytest.fixture
def updates(monkeypatch):
    """The gradient steps of each SB3 update, in order."""
    taken = []
    original = SAC.train

    def recorded(model, gradient_steps, batch_size=64):
        taken.append(gradient_steps)
        return original(model, gradient_steps, batch_size)

    monkeypatch.setattr(SAC, "train", recorded)
    return taken


def test_updates_are_taken_while_the_servers_step_and_as_many_as_sb3_takes(updates):
    torch.set_num_threads(1)
    plain, _ = run(False)
    plain_steps = sum(updates)
    updates.clear()
    events = []
    model, _ = run(True, events)
    assert sum(updates) == plain_steps > 0 and model._n_updates == plain._n_updates
    assert all(n == 1 for n in updates[:-1])  # 2 owed steps spread over the rollout's 4 vector steps
    assert model._owed_steps == 0


def test_each_update_falls_between_a_send_and_its_read(monkeypatch):
    torch.set_num_threads(1)
    events = []
    original = SAC.train

    def recorded(model, gradient_steps, batch_size=64):
        events.append("update")
        return original(model, gradient_steps, batch_size)

    monkeypatch.setattr(SAC, "train", recorded)
    run(True, events, steps=120)
    inside = [i for i, e in enumerate(events) if e == "update"]
    assert inside
    for i in inside[:-1]:  # the last one: the owed steps taken as learn returns
        assert events[i - 1] == "send" and events[i + 1] == "read", events[i - 2:i + 2]
    # 4 vector steps per rollout, 2 updates owed: one update in every other vector step
    sends_between = [events[a:b].count("send") for a, b in zip(inside[:-2], inside[1:-1])]
    assert set(sends_between) == {2}, sends_between


def test_same_seed_same_run_and_it_saves_as_plain_sac(tmp_path):
    torch.set_num_threads(1)
    a, _ = run(True, steps=120)
    b, _ = run(True, steps=120)
    for pa, pb in zip(a.policy.parameters(), b.policy.parameters()):
        assert torch.equal(pa, pb)
    a.save(tmp_path / "m.zip")
    loaded = SAC.load(tmp_path / "m.zip", device="cpu")
    assert not hasattr(loaded, "overlap") and not hasattr(loaded, "_overlapped_env")
    again = SACWithActorRate.load(tmp_path / "m.zip", device="cpu", overlap=True)
    assert again.overlap and again._owed_steps == 0


def test_a_run_stopped_within_a_rollout_takes_the_updates_sb3_takes(updates):
    """A callback that stops the run part way through a rollout (--max-minutes): the steps still owed are taken,
    each once, and the run has SB3's count (SB3 skips the cut rollout's update)."""
    from stable_baselines3.common.callbacks import BaseCallback

    class StopAt(BaseCallback):
        def _on_step(self):
            return self.num_timesteps < 91  # vector steps of 2 envs: stops in the middle of a 4-step rollout

    torch.set_num_threads(1)
    counts = []
    for overlap in (False, True):
        env = Recording([])
        env.seed(3)
        model = SACWithActorRate("MlpPolicy", env, learning_starts=40, train_freq=4, gradient_steps=2, batch_size=16,
                                 buffer_size=1000, seed=3, device="cpu", policy_kwargs={"net_arch": [16, 16]},
                                 overlap=overlap)
        model.set_logger(configure(None, []))
        model.learn(total_timesteps=200, callback=StopAt())
        counts.append((model._n_updates, sum(updates), model._owed_steps))
        updates.clear()
    assert counts[0][:2] == counts[1][:2] and counts[0][0] > 0 and counts[1][2] == 0, counts
