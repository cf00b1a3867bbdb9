"""What a checkpoint's actor and critics make of the insertion: on the states of its own replay buffer, the actor's
deterministic insertion (quantiles), its log-std per action, the entropy coefficient, and how the critics value a
near-constant push (0.96, the start's) against the actor's own insertion (mean Q difference and dQ/d insertion
there). Written to tell whether a run that slows down does so because its critics prefer it.

    python results/generalist/insertion_probe.py RUN/checkpoints/sac_90000_steps.zip [--states 5000] [--wrong-branch]

--wrong-branch probes only the states with the wrong-branch flag raised (the tip in a wrong child: what a run with
--wrong-branch-starts is to learn to leave).

Input: an SB3 SAC checkpoint of an act/2 run (rotation, insertion) with its replay buffer beside it
(sac_replay_buffer_N_steps.pkl). Output: one JSON object on stdout.
"""
import argparse
import json
import pickle
import sys
from pathlib import Path

import numpy as np
import torch
from stable_baselines3 import SAC

PUSH = 0.96  # tanh(2): the widened start's insertion (export_actor.PUSH_PULL_INSERTION_BIAS)
WRONG_BRANCH = 13  # the wrong-branch flag's entry in obs/5 and obs/8 (task/observation.cpp's names)


def probe(zip_path: Path, states: int, wrong_branch: bool = False) -> dict:
    model = SAC.load(zip_path, device="cpu")
    buffer_path = zip_path.with_name(zip_path.name.replace("sac_", "sac_replay_buffer_").replace(".zip", ".pkl"))
    with open(buffer_path, "rb") as f:
        buffer = pickle.load(f)
    filled = buffer.buffer_size if buffer.full else buffer.pos
    obs = buffer.observations[:filled].reshape(-1, buffer.observations.shape[-1])
    if wrong_branch:
        obs = obs[obs[:, WRONG_BRANCH] > 0.5]
    obs = torch.as_tensor(obs[:states])
    with torch.no_grad():
        mean, log_std, _ = model.actor.get_action_dist_params(obs)
        own = torch.tanh(mean)
        push = own.clone()
        push[:, 1] = PUSH
        q_gap = (torch.min(*model.critic(obs, push)) - torch.min(*model.critic(obs, own))).squeeze(-1)
    at_push = push.clone().requires_grad_(True)
    (grad,) = torch.autograd.grad(torch.min(*model.critic(obs, at_push)).sum(), at_push)
    return {"checkpoint": str(zip_path), "states": int(obs.shape[0]), "gamma": model.gamma,
            "ent_coef": float(torch.exp(model.log_ent_coef).item()) if model.log_ent_coef is not None else None,
            "insertion_quantiles_5_25_50_75_95": np.quantile(own[:, 1].numpy(), [.05, .25, .5, .75, .95]).round(3).tolist(),
            "log_std_mean": log_std.mean(0).numpy().round(3).tolist(),
            "q_push_minus_q_own_mean": round(float(q_gap.mean()), 3),
            "dq_dinsertion_at_push_median": round(float(grad[:, 1].median()), 3)}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("checkpoint", type=Path)
    p.add_argument("--states", type=int, default=5000)
    p.add_argument("--wrong-branch", action="store_true", help="only states with the wrong-branch flag raised")
    args = p.parse_args(argv)
    if not args.checkpoint.is_file():
        sys.exit(f"error: {args.checkpoint}: no such checkpoint")
    json.dump(probe(args.checkpoint, args.states, args.wrong_branch), sys.stdout, indent=1)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
