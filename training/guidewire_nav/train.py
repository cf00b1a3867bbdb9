"""Train the zero-shot navigation policy: SB3 SAC against the C++ simulator over sockets.

Reads top to bottom: settings -> environments (one guidewire-server per worker, started again if it
dies) -> SAC with the paper's hyper-parameters (or the run's latest checkpoint with --resume) -> learn
with progress bar, logs, checkpoints and periodic evaluation -> export the deterministic actor to JSON
for the C++ runtime -> training-curve PNG.

    gw-train --total-steps 150000 --envs 2 --out runs/sac      # = python -m guidewire_nav.train ...
    gw-train --total-steps 300 --learning-starts 100 --out runs/smoke   # CI smoke run
    gw-train --total-steps 200000 --envs 2 --out runs/sac --resume     # on from runs/sac's last checkpoint

Paper (Scarponi et al., section 3.1): actor and critics 3x256, lr 1e-4, batch 256, buffer 10,000,
gamma 0.98, entropy coefficient learned, 1,000 warm-up steps, one gradient update per step; the 4
training anatomies, a random anatomy and target per episode; converged at ~120k steps.
"""

from __future__ import annotations

import argparse
import copy
import csv
import dataclasses
import json
import platform
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch
from stable_baselines3 import SAC
from stable_baselines3.common.callbacks import BaseCallback, CallbackList, CheckpointCallback
from stable_baselines3.common.logger import configure
from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv, VecEnvWrapper, VecMonitor


def arg(default, help: str):
    """A Settings field with its --help text (each flag's help is its comment)."""
    return field(default=default, metadata={"help": help})


@dataclass
class Settings:
    out: str = arg("runs/sac", "run folder: logs, checkpoints, actor.json, curve PNG")
    anatomies: str = arg("train", "anatomy set (or comma-separated names, mesh paths, a pool's index.json) "
                                  "the servers load")
    task: str = arg("", "task settings: a JSON file, or an inline JSON object, of TaskConfig fields "
                        "(docs/task_settings.md), sent as it is to every server (guidewire-server --task); '' = the "
                        "shipped rotation actor's task (obs/3, act/1). The paper's: training/tasks/paper.json; the "
                        "push/pull actor's: training/tasks/push_pull.json")
    init_model: str = arg("", "fine-tune: start from this SB3 SAC zip (e.g. a checkpoint)")
    init_actor: str = arg("", "fine-tune: start the actor from an exported actor JSON (fresh critics); when "
                              "the task's action is act/2 a rotation actor (obs/3, act/1) starts the rotation output, the "
                              "insertion output starts pushing (export_actor.widen_to_push_pull)")
    init_log_std: str = arg("-2.3", "with --init-actor: its log-std head (the JSON has only the mean); -2.3 = std "
                                    "~0.1 before tanh; one value for every action, or one per action (act/2: "
                                    "rotation,insertion; '-2.3,0.5' explores the speed while the actor is held)")
    actor_freeze_steps: int = arg(0, "environment steps the actor (and entropy coefficient) stay fixed while fresh "
                                     "critics learn its values; then ordinary SAC")
    anchor_weight: str = arg("0", "fine-tune: adds W * |a(s) - a_start(s)|^2 (deterministic actions on replayed "
                                  "states) to the actor loss, tying it to the actor it started from; one W for every "
                                  "action, or one per action (act/2: rotation,insertion; '10,0' holds the aim and "
                                  "leaves the speed free)")
    wrong_branch_starts: float = arg(0.0, "share of training episodes that start with the tip just inside a wrong "
                                          "child (wrong_branch_start.py: the scripted rule mirrored leads it in), so "
                                          "that leaving a wrong branch is learnt; needs obs/5 or obs/8, act/2 and a "
                                          "task with recovery_attempts > 0")
    wrong_branch_pullback: int = arg(0, "wrong-branch starts: pull a share of them back out of the child again, up to "
                                        "this many env steps, so that the tip starts short of the fork aimed into "
                                        "the wrong child (re-aiming learnt; 0: every start inside the child)")
    total_steps: int = arg(150_000, "environment steps over all workers")
    envs: int = arg(2, "parallel servers (SubprocVecEnv); 1 = in-process DummyVecEnv")
    seed: int = arg(0, "seed of numpy, torch, SAC and the environments' episodes")
    # SAC, paper defaults
    learning_rate: float = arg(1e-4, "Adam learning rate of actor, critics and entropy coefficient (paper)")
    actor_learning_rate: float = arg(0.0, "the actor's own rate (0 = --learning-rate); fine-tuning: Adam moves "
                                          "every weight ~lr per step however small the gradient (see SACWithActorRate)")
    batch_size: int = arg(256, "minibatch size of each gradient step (paper)")
    buffer_size: int = arg(10_000, "replay buffer size in transitions (paper)")
    gamma: float = arg(0.98, "discount factor (paper)")
    learning_starts: int = arg(1_000, "random-action warm-up steps before learning (paper)")
    train_freq: int = arg(1, "environment steps (per worker) between updates")
    gradient_steps: int = arg(-1, "gradient steps per update; -1: one per environment step over all workers "
                                  "(paper)")
    overlap: bool = arg(False, "take the gradient steps while the servers simulate the next env step, not between "
                               "env steps (OverlappedUpdates: the actions of one vector step in each --train-freq "
                               "come from the actor before that update; same seed, same run)")
    net_arch: str = arg("256,256,256", "hidden layers of the actor and the critics (SB3's default is only 2x256)")
    ent_coef: str = arg("auto", "entropy coefficient: 'auto' (learned, paper) or a number")
    device: str = arg("auto", "torch device: auto, cuda or cpu")
    torch_threads: int = arg(0, "torch's CPU threads (0: its default, one per core). Set 1 for each of several runs "
                                "sharing the cores: two default runs on 2 cores spin against each other (measured: "
                                "26 -> 2 steps/s; docs/training.md)")
    # logging, evaluation, checkpoints
    eval_every: int = arg(10_000, "steps between evaluations (0 = only at the end)")
    eval_episodes: int = arg(40, "seeded episodes per evaluation, over the training anatomies (0 = none: pick "
                                 "checkpoints later with the C++ `evaluate` or gw-score-checkpoints)")
    stop_at_success: float = arg(0.0, "stop early once an evaluation reaches this success rate (0 = never)")
    checkpoint_every: int = arg(25_000, "environment steps between SB3 checkpoints (checkpoints/sac_*.zip)")
    max_minutes: float = arg(0.0, "stop learning after this wall time (0 = run all --total-steps; a run cut by "
                                  "it is not reproducible step for step: prefer --total-steps)")
    resume: bool = arg(False, "continue the run in --out from its latest checkpoint (networks, optimisers, entropy "
                              "coefficient, replay buffer, step counter) up to --total-steps; the other settings "
                              "must be the run's (settings.json)")
    progress: bool = arg(True, "show a progress bar")
    step_cutoff: float = arg(10.0, "wall seconds a server may spend on one env step before it ends the episode "
                                   "(guidewire-server --step-cutoff): a wire jammed in a narrow vessel simulates "
                                   "slowly (docs/physics.md) and holds up every worker; lower it to keep the learner "
                                   "fed (the episodes then depend on the machine's speed)")
    servers: str = arg("", "connect to running servers 'host:port,host:port' instead of spawning them")
    ray: bool = arg(False, "simulation servers as Ray actors with these task settings, spread over the Ray "
                           "cluster and restarted when they die (the run goes on); needs the [cluster] extra, "
                           "docs/cluster.md")
    address: str = arg("", "with --ray: the Ray cluster to join ('auto' or HOST:PORT; '' = a local Ray on this "
                           "machine)")


class _HelpFormatter(argparse.RawDescriptionHelpFormatter, argparse.ArgumentDefaultsHelpFormatter):
    """The module docstring as written, and each flag's default after its help."""


def settings_parser() -> argparse.ArgumentParser:
    """One flag per Settings field: --total-steps for total_steps, --no-progress for a bool."""
    parser = argparse.ArgumentParser(prog="gw-train", description=__doc__, formatter_class=_HelpFormatter)
    for f in dataclasses.fields(Settings):
        flag = "--" + f.name.replace("_", "-")
        help_text = f.metadata["help"].replace("%", "%%")
        if f.type in ("bool", bool):
            parser.add_argument(flag, action=argparse.BooleanOptionalAction, default=f.default, help=help_text)
        else:
            kind = {"int": int, "float": float, "str": str}[str(f.type)]
            parser.add_argument(flag, type=kind, default=f.default, help=help_text)
    return parser


def parse_settings(argv=None) -> Settings:
    s = Settings(**vars(settings_parser().parse_args(argv)))
    if s.wrong_branch_pullback < 0:
        raise SystemExit(f"--wrong-branch-pullback {s.wrong_branch_pullback}: env steps, >= 0")
    if s.wrong_branch_pullback and not s.wrong_branch_starts:
        raise SystemExit("--wrong-branch-pullback: pulls wrong-branch starts back out; give --wrong-branch-starts F "
                         "(F > 0) with it")
    return s


def git_commit() -> str:
    try:
        root = Path(__file__).resolve().parents[2]
        rev = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, check=True)
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True)
        return rev.stdout.strip() + ("-dirty" if dirty.stdout.strip() else "")
    except Exception:  # noqa: BLE001 - a tarball checkout has no git; not an error for training
        return "unknown"


def read_json_argument(flag: str, text: str, hint: str):
    """The JSON a flag names: a file, or (starting with '{') the object itself. A missing file or text that is not
    JSON ends the run with one line naming the flag, the text and `hint`."""
    try:
        return json.loads(text) if text.startswith("{") else json.loads(Path(text).read_text())
    except FileNotFoundError:
        raise SystemExit(f"{flag}: {text}: no such file ({hint})")
    except json.JSONDecodeError as e:
        raise SystemExit(f"{flag}: {text}: not JSON ({e})")


def task_settings(s: Settings) -> dict:
    """The task JSON of --task (a file or an inline object); {} = the servers' defaults. Read once here so that
    every server, the run's settings.json and its resume check see the same object."""
    text = s.task.strip()
    if not text:
        return {}
    task = read_json_argument("--task", text, "give a task JSON file or an inline JSON object")
    if not isinstance(task, dict):
        raise SystemExit(f"--task: {text}: a task is a JSON object of TaskConfig fields (docs/task_settings.md)")
    return task


def with_actor_layouts(task: dict, actor_path: str) -> dict:
    """--init-actor: the task takes the actor's observation and action layouts (its obs_layout, action_layout) where
    it does not name them, so an actor fine-tunes in its own task (the paper's obs/1 actor needs no --task); a task
    that names other layouts is refused, naming both. The mismatches allowed are the widenings: a rotation actor
    (act/1) starting an act/2 task, an obs/5 actor starting an obs/8 task, or both (export_actor.widen_for_task)."""
    actor = read_json_argument("--init-actor", actor_path, "give an exported actor JSON")
    if not isinstance(actor, dict):
        raise SystemExit(f"--init-actor: {actor_path}: not an actor JSON (an object with obs_layout and layers)")
    if task.get("action") == "guidewire-nav/act/2" and actor.get("action_size") == 1:
        return task  # widened: the push/pull task keeps its own layouts
    if task.get("observation") == "guidewire-nav/obs/8" and actor.get("obs_layout") == "guidewire-nav/obs/5":
        return task  # widened: the tip-force input starts with zero weights
    out = dict(task)
    for key, layout in (("observation", actor.get("obs_layout")), ("action", actor.get("action_layout"))):
        if not isinstance(layout, str) or not layout.startswith("guidewire-nav/"):
            continue  # an actor that does not say: the task's (or the defaults')
        if key not in out:
            out[key] = layout
        elif isinstance(out[key], str) and out[key] != layout:
            raise SystemExit(f"--init-actor: {actor_path} is a {layout} actor but --task sets {key} {out[key]}: drop "
                             f"the task's {key!r} (the actor's is taken) or start from an actor of that layout")
    return out


def server_args(s: Settings) -> list[str]:
    """The servers' command line: the task JSON as it is (the server checks it and names a bad key), and
    --step-cutoff when it is not the server's own 10 s."""
    task = task_settings(s)
    if s.init_actor:
        task = with_actor_layouts(task, s.init_actor)
    cutoff = ["--step-cutoff", repr(s.step_cutoff)] if s.step_cutoff != 10.0 else []  # 10: the server's own
    return (["--task", json.dumps(task, separators=(",", ":"))] if task else []) + cutoff


def make_env_fn(s: Settings, rank: int, eval_env: bool = False, ray_server=None, seed_offset: int = 0):
    """A thunk for (Subproc|Dummy)VecEnv: each worker starts (or connects to) its own server, started again
    when it dies (env.RestartingEnv); with --ray the server of its actor (ray_servers.ServerRef), reached
    again after the server restarts. `seed_offset`: a resumed run's episodes follow new seeds."""

    def thunk():
        from guidewire_nav.env import GuidewireEnv, RestartingEnv

        if ray_server is not None:
            from guidewire_nav.ray_servers import ServerEnv

            env = ServerEnv(ray_server)
        elif s.servers:  # remote servers, round-robin over the workers; they were started with their own set
            host, port = s.servers.split(",")[rank % len(s.servers.split(","))].rsplit(":", 1)
            env = GuidewireEnv(host=host, port=int(port))
        else:
            env = RestartingEnv(lambda: GuidewireEnv(anatomies=s.anatomies, server_args=server_args(s)),
                                name=f"server {rank}")
        if s.wrong_branch_starts > 0 and not eval_env:
            from guidewire_nav.wrong_branch_start import WrongBranchStart

            env = WrongBranchStart(env, s.wrong_branch_starts, s.wrong_branch_pullback)
        env.reset(seed=s.seed + 1000 * rank + (10**6 if eval_env else 0) + 10**7 * seed_offset)
        return env  # episode statistics come from VecMonitor over all workers

    return thunk


def evaluate(model, env, episodes: int, seed: int) -> dict:
    """Deterministic actor on `episodes` seeded episodes; the env draws anatomy and target per seed."""
    successes, lengths, returns, outcomes = 0, [], [], {}
    for k in range(episodes):
        obs, _ = env.reset(seed=seed + k)
        done, ret, n, info = False, 0.0, 0, {}
        while not done:
            action, _ = model.predict(obs, deterministic=True)
            obs, reward, terminated, truncated, info = env.step(action)
            ret += float(reward)
            n += 1
            done = terminated or truncated
        successes += bool(info["success"])
        outcome = next((k for k in ("success", "wrong_branch", "stuck", "step_limit") if info.get(k)), "other")
        if info.get("problem"):
            outcome = "diverged"
        outcomes[outcome] = outcomes.get(outcome, 0) + 1
        lengths.append(n)
        returns.append(ret)
    return {"episodes": episodes, "success_rate": successes / episodes, "mean_length": float(np.mean(lengths)),
            "mean_return": float(np.mean(returns)), "outcomes": outcomes}


def anchor_loss(actor, reference, obs, weights=None, free_index=None):
    """Mean squared distance between two SB3 actors' deterministic (tanh-squashed) actions on `obs`, each action's
    square times its weight (`weights`: one per action; None = 1 each). Measured on actions, not on the pre-tanh
    means, so a saturated action may keep any mean beyond it: only a change of behaviour costs. `free_index`: the
    observation entry of the wrong-branch flag (None: none): states with it raised are not held, as the starting
    actor never acted there (a rotation actor's strict episodes end at a wrong child) and what it would do there is
    no behaviour to keep (since 2026-12-07; the runs before held every state)."""
    squares = (actor(obs, deterministic=True) - reference(obs, deterministic=True)) ** 2
    if weights is not None:
        squares = squares * weights
    per_state = squares.sum(dim=-1)
    if free_index is not None:
        per_state = per_state * (obs[:, free_index] < 0.5)
    return per_state.mean()


def per_action(flag: str, text: str, action_size: int, minimum: float | None = None) -> list[float]:
    """A flag's value as one number per action: 'X' for every action, or 'X1,X2,...' one per action. Refuses, naming
    the flag, a count that is neither 1 nor the action size, or a number below `minimum`."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise SystemExit(f"{flag} {text}: give a number, or one per action separated by commas") from None
    if len(values) == 1:
        values *= action_size
    if len(values) != action_size or (minimum is not None and min(values) < minimum):
        bound = f" >= {minimum:g}" if minimum is not None else ""
        raise SystemExit(f"{flag} {text}: give one number{bound}, or {action_size} (one per action of the task's "
                         f"action layout)")
    return values


def anchor_weights(text: str, action_size: int) -> list[float]:
    """--anchor-weight as one weight >= 0 per action."""
    return per_action("--anchor-weight", text, action_size, minimum=0.0)


class SACWithActorRate(SAC):
    """SAC whose actor may learn at its own rate (``actor_learning_rate`` > 0; 0 = the common one).

    SB3 resets every optimiser to the one schedule before each update, so the actor's rate is set after
    that. Why: Adam steps each weight by ~lr whatever the gradient's size, so a fresh critic's noisy
    gradients move a good actor as fast as useful ones would (2,000 updates at 1e-4 were seen to cut the
    shipped actor's successes on the validation trees from 98 to 69 of 110: policy/trained/README.md).
    ``SACWithActorRate.load(path, actor_learning_rate=r, ...)`` sets it too (SB3 load sets keyword
    arguments as attributes)."""

    def __init__(self, *args, actor_learning_rate: float = 0.0, overlap: bool = False, **kwargs):
        self.actor_learning_rate = actor_learning_rate
        self.overlap = overlap
        self._owed_steps, self._owed_batch = 0, 0  # OverlappedUpdates: gradient steps owed, taken in the next rollout
        self._overlapped_env = None  # its wrapper of the training env
        super().__init__(*args, **kwargs)

    def _excluded_save_params(self) -> list[str]:
        return [*super()._excluded_save_params(), "actor_learning_rate", "overlap", "_owed_steps",
                "_owed_batch", "_overlapped_env"]  # plain SAC's zips

    def collect_rollouts(self, env, *args, **kwargs):
        """SB3's collection with torch on one thread: the actor's forward pass on a few observations gains
        nothing from more, and a second OpenMP thread spinning after it takes a core from the servers
        (gw-bench-train, 2 cores, 2 servers: 125 -> 170 env steps/s of collection). Gradient steps keep
        every thread; with --overlap they run within the collection, on its one thread, beside the servers."""
        threads = torch.get_num_threads()
        torch.set_num_threads(1)
        try:
            if self.overlap:
                env = OverlappedUpdates.around(env, self)
            return super().collect_rollouts(env, *args, **kwargs)
        finally:
            torch.set_num_threads(threads)

    def train(self, gradient_steps: int, batch_size: int = 64) -> None:
        """SB3's update; with --overlap only owed here (OverlappedUpdates takes it during the next rollout)."""
        if self.overlap:
            self._owed_steps, self._owed_batch = self._owed_steps + gradient_steps, batch_size
            return
        super().train(gradient_steps, batch_size)

    def take_owed_updates(self, steps: int) -> None:
        """`steps` of the owed gradient steps (at most those owed), then the policy back in collection mode."""
        steps = min(steps, self._owed_steps)
        if steps > 0:
            super().train(steps, self._owed_batch)
            self._owed_steps -= steps
            self.policy.set_training_mode(False)

    def learn(self, *args, **kwargs):
        """SB3's learn; with --overlap the steps still owed (the last update's, or a rollout's cut short) are
        taken before it returns (a saved model has every update of its steps)."""
        model = super().learn(*args, **kwargs)
        self.take_owed_updates(self._owed_steps)
        return model

    def _update_learning_rate(self, optimizers) -> None:
        super()._update_learning_rate(optimizers)
        if getattr(self, "actor_learning_rate", 0.0) > 0:
            for group in self.actor.optimizer.param_groups:
                group["lr"] = self.actor_learning_rate


class OverlappedUpdates(VecEnvWrapper):
    """The learner keeps up with the servers (issue 62 item 4): SB3 steps the servers, then takes its gradient
    steps while they wait. Here an update's gradient steps are owed instead, and taken during the next rollout's
    vector steps, between sending the actions (step_async: the servers simulate) and reading the results
    (step_wait), spread evenly over the rollout's --train-freq vector steps. The order of everything is fixed, so
    the same seed gives the same run; what changes against SB3's loop is that the actions of a rollout's vector
    steps come from the actor before the update that is taken during them (at most --train-freq vector steps
    older). With one worker (DummyVecEnv) the server steps in step_wait: no overlap, the same order."""

    def __init__(self, venv, model: "SACWithActorRate"):
        super().__init__(venv)
        self.model = model
        self.window, self.windows, self.total = 0, 1, 0

    @staticmethod
    def around(env, model) -> "OverlappedUpdates":
        """The wrapper of `env` for this rollout (made once per env, kept on the model), its plan: the steps owed
        now over the rollout's vector steps."""
        wrapper = model._overlapped_env
        if wrapper is None or wrapper.venv is not env:
            wrapper = model._overlapped_env = OverlappedUpdates(env, model)
        wrapper.window, wrapper.windows, wrapper.total = 0, max(1, model.train_freq.frequency), model._owed_steps
        return wrapper

    def step_async(self, actions) -> None:
        self.venv.step_async(actions)
        w, n, total = self.window, self.windows, self.total
        self.model.take_owed_updates(total * (w + 1) // n - total * w // n)  # spread evenly over the rollout
        self.window += 1

    def step_wait(self):
        return self.venv.step_wait()

    def reset(self):
        return self.venv.reset()


class ActorUpdates(BaseCallback):
    """Actor freeze and anchor, both for fine-tuning a good actor.

    Freeze: a fresh critic's early gradients would undo a good actor before the critic knows its values,
    so the actor's and the entropy coefficient's optimisers skip their steps for the first
    ``freeze_steps`` environment steps (critic updates go on; the buffer fills with the actor's own
    stochastic actions once learning_starts is past, so set --learning-starts low when fine-tuning from
    a good actor).
    Anchor: the training anatomies alone do not hold a fine-tuned actor's zero-shot behaviour in place
    (every update redrew it: policy/trained/README.md), so each actor step may also pull the actions on a
    replayed batch back towards ``reference`` (the starting actor; None = no anchor). SB3's SAC.train()
    calls zero_grad, actor_loss.backward, step; the anchor's gradient is added in between, in step."""

    def __init__(self, freeze_steps: int, reference=None, anchor_weights=None, batch_size: int = 256,
                 free_index=None):
        super().__init__()
        self.freeze_steps = freeze_steps
        self.reference = reference
        self.anchor_weights = anchor_weights  # a tensor, one weight per action
        self.free_index = free_index  # the wrong-branch flag's entry: states the anchor leaves free (anchor_loss)
        self.batch_size = batch_size
        self.frozen = freeze_steps > 0

    def _on_training_start(self) -> None:
        actor_opt, ent_opt = self.model.actor.optimizer, self.model.ent_coef_optimizer

        def actor_step(*args, **kwargs):
            if self.frozen:
                return None
            if self.reference is not None:
                obs = self.model.replay_buffer.sample(self.batch_size).observations
                loss = anchor_loss(self.model.actor, self.reference, obs, self.anchor_weights, self.free_index)
                loss.backward()
                self.logger.record("train/anchor_loss", loss.item())
            return type(actor_opt).step(actor_opt, *args, **kwargs)

        def ent_step(*args, **kwargs):
            return None if self.frozen else type(ent_opt).step(ent_opt, *args, **kwargs)

        actor_opt.step = actor_step  # instance attributes shadow Optimizer.step
        if ent_opt is not None:
            ent_opt.step = ent_step

    def _on_step(self) -> bool:
        self.frozen = self.num_timesteps < self.freeze_steps
        return True


class EvalCallback(BaseCallback):
    """Periodic evaluation (success rate over seeded episodes, appended to ``evals`` and
    out/evaluations.jsonl) keeping the best model in out/best_model.zip; stops learning once an
    evaluation reaches --stop-at-success or the --max-minutes budget (counted from ``start``) is spent."""

    def __init__(self, s: Settings, eval_env, out: Path, evals: list[dict], start: float):
        super().__init__()
        self.s, self.eval_env, self.out, self.evals, self.start = s, eval_env, out, evals, start
        self.next_eval = s.eval_every if s.eval_every > 0 else None
        self.best = -1.0

    def run_eval(self) -> bool:
        t0 = time.time()
        result = evaluate(self.model, self.eval_env, self.s.eval_episodes, seed=10_000)
        result.update(step=self.num_timesteps, wall_s=time.time() - self.start, eval_s=time.time() - t0)
        self.evals.append(result)
        self.logger.record("eval/success_rate", result["success_rate"])
        with open(self.out / "evaluations.jsonl", "a") as f:
            f.write(json.dumps(result) + "\n")
        if result["success_rate"] > self.best:
            self.best = result["success_rate"]
            self.model.save(self.out / "best_model.zip")
        return not (self.s.stop_at_success > 0 and result["success_rate"] >= self.s.stop_at_success)

    def _on_training_start(self) -> None:
        while self.next_eval is not None and self.next_eval <= self.model.num_timesteps:  # a resumed run
            self.next_eval += self.s.eval_every

    def _on_step(self) -> bool:
        if self.s.max_minutes > 0 and time.time() - self.start > 60 * self.s.max_minutes:
            return False  # wall-time budget spent: learn() returns, the rest of the script runs
        if self.s.eval_episodes <= 0:
            return True
        if self.next_eval is not None and self.num_timesteps >= self.next_eval:
            self.next_eval += self.s.eval_every
            return self.run_eval()
        return True


def plot_curve(out: Path, monitor_rows: list[dict], evals: list[dict], eval_label: str = "deterministic evaluation",
               anatomies: str = "train") -> None:
    """Left: episode returns. Right: success of the training episodes (stochastic policy) per 10k-step
    window, and the evaluations (deterministic actor) when there are any."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
    if monitor_rows:
        steps = np.cumsum([r["l"] for r in monitor_rows])
        rets = np.array([r["r"] for r in monitor_rows])
        window = max(1, min(50, len(rets) // 10))
        smooth = np.convolve(rets, np.ones(window) / window, mode="valid")
        ax1.plot(steps, rets, ".", alpha=0.25, label="episode return")
        ax1.plot(steps[window - 1:], smooth, label=f"mean of {window}")
        ax1.set_xlabel("environment steps")
        ax1.set_ylabel("return")
        ax1.legend()
        success = np.array([r["success"] for r in monitor_rows], dtype=float)
        bins = (steps - 1) // 10_000
        windows = np.unique(bins)
        rates = [100 * success[bins == b].mean() for b in windows]
        ax2.step(10_000 * windows + 5_000, rates, where="mid", color="tab:blue", alpha=0.6,
                 label="training episodes (stochastic), per 10k steps")
    if evals:
        ax2.plot([e["step"] for e in evals], [100 * e["success_rate"] for e in evals], "o-", color="tab:orange",
                 label=eval_label)
    if anatomies == "train":  # the paper's figure is for its 4 training anatomies (its Table 1)
        ax2.axhline(95, color="gray", ls="--", label="paper: 95%")
    ax2.set_ylim(0, 102)
    ax2.set_xlabel("environment steps")
    ax2.set_ylabel("success rate on the training anatomies [%]")
    ax2.legend(fontsize=8, loc="lower right")
    fig.suptitle("SAC on the 4 training anatomies" if anatomies == "train" else f"SAC on {anatomies} only")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def read_monitor(path: Path) -> list[dict]:
    """Episodes of SB3's monitor CSV (after its JSON header line): return, length and success."""
    if not path.exists():
        return []
    with open(path) as f:
        next(f)
        return [{"r": float(r["r"]), "l": int(r["l"]), "success": r.get("success") in ("True", "1", "1.0")}
                for r in csv.DictReader(f)]


def read_run_monitors(out: Path) -> list[dict]:
    """Every episode of a run in order: monitor.monitor.csv, then each resumed part's
    monitor_from_<step>.monitor.csv by step."""
    parts = sorted(out.glob("monitor_from_*.monitor.csv"), key=lambda p: int(p.name.split("_")[2].split(".")[0]))
    return [row for path in [out / "monitor.monitor.csv", *parts] for row in read_monitor(path)]


def latest_checkpoint(out: Path) -> tuple[int, Path, Path] | None:
    """(step, model zip, replay buffer) of the run's latest state that has both: a checkpoint
    (checkpoints/sac_<N>_steps.zip, sac_replay_buffer_<N>_steps.pkl) or the finished run's final_model.zip
    with final_replay_buffer.pkl."""
    found = []
    for zip_path in (out / "checkpoints").glob("sac_*_steps.zip"):
        step = int(zip_path.stem.split("_")[1])
        buffer = zip_path.parent / f"sac_replay_buffer_{step}_steps.pkl"
        if buffer.is_file():
            found.append((step, zip_path, buffer))
    final = out / "final_model.zip"
    if final.is_file() and (out / "final_replay_buffer.pkl").is_file():
        steps = json.loads((out / "summary.json").read_text())["steps"] if (out / "summary.json").is_file() else -1
        found.append((steps, final, out / "final_replay_buffer.pkl"))
    # at equal steps the final state: a checkpoint is written just before its step's transition is stored
    return max(found, key=lambda f: (f[0], f[1].name == "final_model.zip")) if found else None


def same(key: str, saved, value) -> bool:
    """A saved setting equals this one; the anchor weight is compared as numbers (a run before 2026-12-06 saved it as
    one float, now it is text: one weight or one per action; the initial log-std likewise)."""
    if key in ("anchor_weight", "init_log_std"):
        return [float(w) for w in str(saved).split(",")] == [float(w) for w in str(value).split(",")]
    return saved == value


def check_resumable(s: Settings, out: Path) -> tuple[int, Path, Path]:
    """The checkpoint --resume continues from; the run's settings must be these (but for the steps, the
    time budget, the progress bar, torch's thread count and resume itself)."""
    saved_path = out / "settings.json"
    if not saved_path.is_file():
        raise SystemExit(f"--resume: {saved_path} not found: no run to continue in {out}")
    saved = json.loads(saved_path.read_text())
    free = {"total_steps", "max_minutes", "progress", "resume", "torch_threads"}
    differ = [k for k, v in dataclasses.asdict(s).items() if k not in free and k in saved and not same(k, saved[k], v)]
    if differ:
        raise SystemExit("--resume: settings differ from the run's settings.json: " +
                         ", ".join(f"{k} = {getattr(s, k)!r} (run: {saved[k]!r})" for k in differ))
    latest = latest_checkpoint(out)
    if latest is None:
        raise SystemExit(f"--resume: no checkpoint with its replay buffer in {out}")
    if latest[0] >= s.total_steps:
        raise SystemExit(f"--resume: the run is at step {latest[0]}, --total-steps {s.total_steps} is not beyond it")
    return latest


def record_settings(s: Settings, out: Path, commit: str, command: str, resume_from, resumed_at: int) -> dict:
    """Settings phase. In: the settings, commit, command line and --resume's checkpoint (None: a new run). Writes
    out/settings.json: these settings, commit and command (a resumed run: the run's own settings, this resumption
    appended to their "resumed" list). Out: that record (the environments add the task to it)."""
    record = {**dataclasses.asdict(s), "commit": commit, "command": command}
    if resume_from:  # the run's settings stay; each resumption is recorded beside them
        saved = json.loads((out / "settings.json").read_text())
        saved.setdefault("resumed", []).append({"at_step": resumed_at, "from": str(resume_from[1]), **record})
        record = saved
    (out / "settings.json").write_text(json.dumps(record, indent=2))
    return record


def make_environments(s: Settings, out: Path, record: dict, resume_from, resumed_at: int):
    """Environments phase. In: the settings, the run's record, --resume's checkpoint and its step. Starts one server
    per worker and one for evaluation (Ray actors with --ray), the workers' monitor CSV (a resumed part: its own
    monitor_from_<step>), and writes the servers' whole task into settings.json. Out: (vec_env, eval_env, the Ray
    actor handles: keep them until the run ends)."""
    # one server per worker, episodes on a random training anatomy and target; with --ray the servers are Ray
    # actors (ray_servers.py), the evaluation's reserving no CPU (idle while the workers run)
    ray_servers, ray_actors = {}, {}
    if s.ray:
        from guidewire_nav.ray_servers import start_servers

        names = [f"server-{rank}" for rank in range(s.envs)] + ["server-eval"]
        ray_servers, ray_actors = start_servers(names, s.anatomies, server_args(s), s.address, {"server-eval": 0})
    fns = [make_env_fn(s, rank, ray_server=ray_servers.get(f"server-{rank}"), seed_offset=resumed_at)
           for rank in range(s.envs)]
    vec_env = SubprocVecEnv(fns) if s.envs > 1 else DummyVecEnv(fns)
    monitor = out / (f"monitor_from_{resumed_at}" if resume_from else "monitor")  # a resumed part: its own file
    vec_env = VecMonitor(vec_env, str(monitor), info_keywords=("success",))
    eval_env = make_env_fn(s, 0, eval_env=True, ray_server=ray_servers.get("server-eval"))()
    # the whole task the servers run (their spec: every TaskConfig field), beside the --task that chose it
    record.setdefault("task_settings", eval_env.unwrapped.spec_reply["task"])
    (out / "settings.json").write_text(json.dumps(record, indent=2))
    return vec_env, eval_env, ray_actors


def make_model(s: Settings, out: Path, vec_env, eval_env, resume_from):
    """Model phase. In: the settings, the environments and --resume's checkpoint. Out: the SAC model with the
    paper's settings: the run's own state (--resume), --init-model's networks or fresh ones, the actor from
    --init-actor if given (not over a resumed run's own); it logs to out/logs. And the anchor's reference (None
    without --anchor-weight): a frozen copy of the actor the run started from (--init-actor's or --init-model's,
    a resumed run's too; a run from scratch: its first actor)."""
    # the actor may get its own learning rate (SACWithActorRate)
    sac_settings = dict(
        learning_rate=s.learning_rate, buffer_size=s.buffer_size, batch_size=s.batch_size, gamma=s.gamma,
        learning_starts=s.learning_starts, train_freq=s.train_freq, gradient_steps=s.gradient_steps,
        seed=s.seed, device=s.device, verbose=0, actor_learning_rate=s.actor_learning_rate, overlap=s.overlap,
    )
    if resume_from:  # the run's own state: networks, optimisers, entropy coefficient, step counter, buffer
        model = SACWithActorRate.load(resume_from[1], env=vec_env, **sac_settings)
        model.load_replay_buffer(resume_from[2])
        # SB3 keeps one buffer row per vector step, n_envs transitions in each
        transitions = model.replay_buffer.size() * model.replay_buffer.n_envs
        print(f"[train] resumed {out} at step {model.num_timesteps} ({transitions} transitions "
              f"in the replay buffer)", file=sys.stderr)
    elif s.init_model:  # fine-tuning: the saved networks (and learned entropy coefficient), a fresh buffer
        model = SACWithActorRate.load(s.init_model, env=vec_env, **sac_settings)
    else:
        model = SACWithActorRate("MlpPolicy", vec_env, ent_coef=s.ent_coef,
                                 policy_kwargs={"net_arch": [int(n) for n in s.net_arch.split(",")]}, **sac_settings)
    # the actor the run started from, the anchor's reference: a resumed run keeps its own actor
    kept = copy.deepcopy(model.actor.state_dict()) if resume_from else None
    if s.init_actor:  # a shipped actor without its critics: only the mean is kept, the critics start fresh
        from guidewire_nav.export_actor import load_actor_json, widen_for_task

        spec = eval_env.unwrapped.spec_reply  # the task's layouts, as the server says them
        start_actor = widen_for_task(json.loads(Path(s.init_actor).read_text()), spec.get("obs_layout"),
                                     spec.get("action_layout"))
        load_actor_json(model, start_actor, log_std=per_action("--init-log-std", s.init_log_std,
                                                               model.action_space.shape[0]))
    elif s.init_model and resume_from:
        model.actor.load_state_dict(SAC.load(s.init_model, device="cpu").actor.state_dict())
    reference = None
    if max(anchor_weights(s.anchor_weight, model.action_space.shape[0])) > 0:
        reference = copy.deepcopy(model.actor).requires_grad_(False)
    if kept is not None:
        model.actor.load_state_dict(kept)
    model.set_logger(configure(str(out / "logs"), ["csv", "tensorboard"]))
    return model, reference


def learn(s: Settings, out: Path, model, reference, eval_env, resume_from) -> tuple[list[dict], float]:
    """Learning-loop phase. In: the settings, the model, the anchor's reference (make_model), the evaluation
    environment and --resume's checkpoint.
    Learns up to --total-steps with the callbacks (actor freeze and anchor, periodic evaluation keeping
    out/best_model.zip, checkpoints), saves out/final_model.zip and final_replay_buffer.pkl, evaluates the final
    model if the last evaluation was not at its step. Out: (the evaluations, a resumed run's earlier ones first;
    the wall time in s)."""
    # --- callbacks: actor freeze and anchor (fine-tuning), periodic evaluation keeping the best actor,
    # checkpoints
    weights = torch.tensor(anchor_weights(s.anchor_weight, model.action_space.shape[0]), dtype=torch.float32,
                           device=model.device)
    evals: list[dict] = []
    start = time.time()
    eval_cb = EvalCallback(s, eval_env, out, evals, start)
    names = list(getattr(eval_env.unwrapped, "observation_names", []))
    free_index = names.index("wrong_branch") if "wrong_branch" in names else None
    callbacks = CallbackList([ActorUpdates(s.actor_freeze_steps, reference, weights, s.batch_size, free_index), eval_cb,
                              CheckpointCallback(max(1, s.checkpoint_every // s.envs), str(out / "checkpoints"),
                                                 name_prefix="sac", save_replay_buffer=True)])

    # --- learn (a resumed run: the steps left, its counter going on, its evaluations kept)
    if resume_from and (out / "evaluations.jsonl").is_file():
        evals += [json.loads(line) for line in (out / "evaluations.jsonl").read_text().splitlines() if line.strip()]
        eval_cb.best = max((e["success_rate"] for e in evals), default=-1.0)
    elif not resume_from:
        (out / "evaluations.jsonl").unlink(missing_ok=True)
    model.learn(total_timesteps=s.total_steps - model.num_timesteps, callback=callbacks, progress_bar=s.progress,
                reset_num_timesteps=not resume_from)
    model.save(out / "final_model.zip")
    model.save_replay_buffer(out / "final_replay_buffer.pkl")  # so that a finished run can be continued
    if s.eval_episodes > 0 and (not evals or evals[-1]["step"] != model.num_timesteps):
        eval_cb.run_eval()
    wall = time.time() - start
    return evals, wall


def export_run(s: Settings, out: Path, model, eval_env, evals: list[dict], record: dict, command: str, commit: str,
               wall: float) -> dict:
    """Saving phase. In: the settings, the learned model, the evaluations, the run's record, command, commit and
    wall time. Writes out/actor.json (the best actor, deterministic tanh(mu), for the C++ runtime; the final model
    when no evaluation kept one) and out/summary.json. Out: the summary."""
    from guidewire_nav.export_actor import export_sac_actor

    best = SAC.load(out / "best_model.zip", device="cpu") if (out / "best_model.zip").exists() else model
    obs_layout = eval_env.unwrapped.spec_reply["obs_layout"]
    action_layout = eval_env.unwrapped.spec_reply.get("action_layout", "guidewire-nav/act/1")
    summary = {
        "command": command, "commit": commit, "settings": dataclasses.asdict(s),
        "task_settings": eval_env.unwrapped.spec_reply["task"],
        "steps": int(model.num_timesteps), "wall_time_s": round(wall, 1),
        "resumed_at_steps": [r["at_step"] for r in record.get("resumed", [])],
        "device": str(model.device), "machine": platform.processor() or platform.machine(),
        "torch_threads": torch.get_num_threads(),
        "best_success_rate": max((e["success_rate"] for e in evals), default=None),
        "final_eval": evals[-1] if evals else None,
    }
    export_sac_actor(best, out / "actor.json", obs_layout=obs_layout, training_settings=summary,
                     action_layout=action_layout)
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary


def close_environments(vec_env, eval_env, ray_actors: dict) -> None:
    """In: the environments and the Ray actor handles. Closes the environments; with --ray drops the handles
    (their servers end) and shuts Ray down."""
    vec_env.close()
    eval_env.close()
    if ray_actors:
        import ray

        ray_actors.clear()
        ray.shutdown()


def main(argv=None) -> int:
    # --- settings: the run's folder and settings.json; --resume: the checkpoint it continues from
    s = parse_settings(argv)
    out = Path(s.out)
    out.mkdir(parents=True, exist_ok=True)
    commit = git_commit()
    command = "python -m guidewire_nav.train " + " ".join(sys.argv[1:] if argv is None else argv)
    resume_from = check_resumable(s, out) if s.resume else None  # (step, model zip, replay buffer)
    resumed_at = resume_from[0] if resume_from else 0
    record = record_settings(s, out, commit, command, resume_from, resumed_at)

    if s.torch_threads > 0:
        torch.set_num_threads(s.torch_threads)
    # --- seeding: same seed, same run (up to nondeterministic GPU kernels)
    np.random.seed(s.seed)
    torch.manual_seed(s.seed)

    # --- environments: one server per worker (Ray actors with --ray) and one for evaluation
    vec_env, eval_env, ray_actors = make_environments(s, out, record, resume_from, resumed_at)

    # --- SAC with the paper's settings (or the run's latest checkpoint with --resume)
    model, reference = make_model(s, out, vec_env, eval_env, resume_from)

    # --- learn, with periodic evaluation and checkpoints
    evals, wall = learn(s, out, model, reference, eval_env, resume_from)

    # --- saving: the best actor for the C++ runtime, the summary, the training curve
    summary = export_run(s, out, model, eval_env, evals, record, command, commit, wall)
    plot_curve(out / "training_curve.png", read_run_monitors(out), evals, anatomies=s.anatomies)

    close_environments(vec_env, eval_env, ray_actors)
    print(json.dumps({k: summary[k] for k in ("steps", "wall_time_s", "best_success_rate")}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
