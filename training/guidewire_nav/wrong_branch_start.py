"""Wrong-branch starts: a training curriculum for leaving a wrong branch (issue 64).

A controller that never enters a wrong branch in training never learns to pull out of one: under the generalist's
task (act/2, recovery 3) an episode goes on after the tip enters a wrong child, but the rotation actor the run starts
from aims well, so those states are rare (5-11% of episodes) and the learnt actor "pulls out but does not get in"
(results/generalist/README.md). This wrapper starts a share of the training episodes with the tip just inside a wrong
child, so the learner meets that state as often as it is asked to.

    env = WrongBranchStart(env, fraction=0.3, pullback_steps=15)

In:  an env whose observation has "omega" and "wrong_branch" (obs/5, obs/8: the push/pull layouts) and whose action
     is [rotation, insertion] (act/2); `fraction` of resets in [0, 1]; `pullback_steps` >= 0 (default 0).
Out: on reset, with probability `fraction` (the wrapper's own generator, seeded by the first seeded reset, so a
     seeded run stays seeded), the episode is first driven by the scripted rule mirrored (turn until the tip bends
     towards the wrong child, omega >= 0.95, then hold; push at full speed) until the wrong-branch flag rises, then
     moved by an offset drawn from -pullback_steps..25 env steps: pushed on that many steps (up to 10 mm) while the
     tip stays in the wrong child, or, where the offset is negative, pulled back at full speed with the rotation held
     until the flag falls and on to that many steps in all, so that the tip is just short of the fork and still aimed
     into the wrong child (where re-aiming is the task: the state the fifth version's first trial left unlearnt);
     that observation is the reset's, with info["wrong_branch_start"] = True, info["lead_in_steps"] and
     info["offset_steps"]. An episode whose
     lead-in ends without entering a wrong child (a path without a fork, a tip that went the right way anyway) is
     dropped and an ordinary reset follows. The lead-in's steps are the server's, not the learner's: they are not
     transitions, and they count against the episode's step limit as any step does.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from guidewire_nav.baselines import SCRIPTED_OMEGA_RELEASE, scripted_omega_action


class WrongBranchStart(gym.Wrapper):
    DEEPER_STEPS = 25  # at most this many env steps pushed past the entry (0.4 mm each under the default push)

    PULL_OUT_STEPS = 50  # a pulled-back start whose tip is still in the wrong child after this many pulls is dropped

    def __init__(self, env: gym.Env, fraction: float, pullback_steps: int = 0):
        super().__init__(env)
        if not 0.0 <= fraction <= 1.0:
            raise ValueError(f"wrong-branch start fraction must be within [0, 1], got {fraction}")
        if pullback_steps < 0:
            raise ValueError(f"wrong-branch pull-back must be >= 0 env steps, got {pullback_steps}")
        names = list(getattr(env, "observation_names", []))
        missing = [n for n in ("omega", "wrong_branch") if n not in names]
        if missing or env.action_space.shape != (2,):
            raise ValueError("wrong-branch starts need an observation with omega and wrong_branch (obs/5, obs/8) and "
                             f"the act/2 action; this env has observations {names} and action shape "
                             f"{env.action_space.shape}")
        task = getattr(env, "spec_reply", {}).get("task", {})
        if fraction > 0.0 and task.get("recovery_attempts", 1) == 0:
            raise ValueError("wrong-branch starts need a task whose episodes go on after a wrong child "
                             "(recovery_attempts > 0, e.g. training/tasks/generalist.json); this task ends them there")
        self.fraction = fraction
        self.pullback_steps = int(pullback_steps)
        self.observation_names = names
        self.omega_index = names.index("omega")
        self.flag_index = names.index("wrong_branch")
        self.rng = np.random.default_rng(0)
        self.started_in_wrong_branch = 0  # lead-ins that entered a wrong child (and, pulled back, left it)
        self.lead_ins_dropped = 0         # lead-ins that ended first

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            self.rng = np.random.default_rng(seed)
        obs, info = self.env.reset(seed=seed, options=options)
        if self.fraction <= 0.0 or self.rng.random() >= self.fraction:
            return obs, info
        for steps in range(1, 100_000):
            # the mirrored rule: -omega crosses the rule's release where omega reaches -release (0.95)
            rotation = scripted_omega_action(-float(obs[self.omega_index]), SCRIPTED_OMEGA_RELEASE)
            obs, _, terminated, truncated, _ = self.env.step(np.array([rotation, 1.0], dtype=np.float32))
            started = None
            if not (terminated or truncated):
                if obs[self.flag_index] < 0.5:
                    continue
                started = self._offset(obs, info, steps)
            if started is None:  # the episode ended during the lead-in: dropped, an ordinary episode instead
                self.lead_ins_dropped += 1
                return self.env.reset(options=options)
            return started
        raise RuntimeError("wrong-branch lead-in: the episode never ended")

    def _offset(self, obs, info, steps):
        """Moves the wire by an offset drawn from -pullback_steps..DEEPER_STEPS env steps from the entry, the rotation
        held. A push of k >= 0 steps puts the tip anywhere in the first ~10 mm of the wrong child, not only on its
        threshold (one pulled step undoes an entry), and stops early where the tip leaves it. A pull of k > 0 steps
        goes on until the tip is out of the wrong child (at most PULL_OUT_STEPS) and to k steps in all: the tip short
        of the fork, aimed into the wrong child. Out: the reset's (obs, info), or None where the episode ended
        meanwhile or a pull never took the tip out (the caller drops it)."""
        offset = int(self.rng.integers(-self.pullback_steps, self.DEEPER_STEPS + 1))
        if offset >= 0:
            for _ in range(offset):
                after, _, terminated, truncated, _ = self.env.step(np.array([0.0, 1.0], dtype=np.float32))
                if terminated or truncated:
                    return None
                if after[self.flag_index] < 0.5:  # a push that left the child: the last state inside it
                    break
                obs, steps = after, steps + 1
        else:
            for moved in range(1, max(-offset, self.PULL_OUT_STEPS) + 1):
                obs, _, terminated, truncated, _ = self.env.step(np.array([0.0, -1.0], dtype=np.float32))
                if terminated or truncated:
                    return None
                steps += 1
                if obs[self.flag_index] < 0.5 and moved >= -offset:
                    break
            else:  # the tip never left the wrong child
                return None
        self.started_in_wrong_branch += 1
        return obs, {**info, "wrong_branch_start": True, "lead_in_steps": steps, "offset_steps": offset}
