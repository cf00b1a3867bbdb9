"""Behaviour cloning of the procedure planner: an actor JSON fitted to plan_demos' (observation, action) pairs.

    gw-clone-plans --demos runs/demos_train --init-actor policy/trained/sac_actor.json \
        --out runs/clone/actor.json

Reads top to bottom: the data (every episode file of each DEMOS/episodes, obs/8 and act/2; a seeded tenth of the
episodes held out), the actor (the init actor widened to obs/8 and act/2 as gw-train widens it, so cloning starts
from the shipped aim), the fit (Adam on the squared error of the actor's deterministic action, tanh of its mean,
against the plan's, in minibatches, for --epochs passes), the export (the epoch with the lowest held-out error).

One input is masked: the last insertion (obs entry 12) is set to 0 in training and its first-layer weights are 0
in the exported actor, so the clone does not read it. Why: a plan holds each action for 5 env steps, so the last
insertion predicts the next one 4 times in 5 and a clone that reads it learns to repeat itself (the "copycat"
failure of behaviour cloning with action history, de Haan et al. 2019), not when to pull back.
"""
from __future__ import annotations

import argparse
import json
import random
import time
from pathlib import Path

import numpy as np
import torch
import torch.nn as nn

from guidewire_nav.export_actor import _git_commit, widen_for_task

OBS_LAYOUT, ACTION_LAYOUT = "guidewire-nav/obs/8", "guidewire-nav/act/2"
LAST_INSERTION = 12  # obs/5's entry: the insertion of the last env step (task/observation.hpp)


def parse_args(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--demos", required=True, nargs="+", help="gw-plan-demos directories (their episodes/*.jsonl)")
    p.add_argument("--init-actor", required=True, help="the actor JSON cloning starts from (widened to obs/8, act/2)")
    p.add_argument("--out", required=True, help="the cloned actor JSON")
    p.add_argument("--epochs", type=int, default=30, help="passes over the training pairs")
    p.add_argument("--batch-size", type=int, default=256, help="pairs per gradient step")
    p.add_argument("--learning-rate", type=float, default=3e-4, help="Adam's step size")
    p.add_argument("--holdout", type=float, default=0.1, help="share of the episodes held out to pick the epoch")
    p.add_argument("--seed", type=int, default=1, help="the held-out episodes, the initial order, the minibatches")
    return p.parse_args(argv)


def load_episodes(folders: list[Path]) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Every episode's pairs: (name, obs (n, 15), action (n, 2)), folder by folder, in name order."""
    episodes = []
    for path in [p for demos in folders for p in sorted((demos / "episodes").glob("*.jsonl"))]:
        rows = [json.loads(x) for x in path.read_text().splitlines() if x.strip()]
        if rows:
            episodes.append((path.stem, np.array([r["obs"] for r in rows], dtype=np.float32),
                             np.array([r["action"] for r in rows], dtype=np.float32)))
    if not episodes:
        raise SystemExit(f"clone_plans: no demonstrations in {', '.join(str(d / 'episodes') for d in folders)}")
    obs_size = {e[1].shape[1] for e in episodes}
    if obs_size != {15}:
        raise SystemExit(f"clone_plans: observations of sizes {sorted(obs_size)}, expected 15 ({OBS_LAYOUT})")
    return episodes


def network_from_json(d: dict) -> nn.Sequential:
    """The actor's mean network (Linear + activation per layer; the last layer's output is the pre-tanh mean)."""
    acts = {"relu": nn.ReLU, "tanh": nn.Tanh, "identity": nn.Identity}
    modules = []
    for layer in d["layers"]:
        out_size, in_size = layer["shape"]
        linear = nn.Linear(in_size, out_size)
        with torch.no_grad():
            linear.weight.copy_(torch.tensor(layer["weight"], dtype=torch.float32).reshape(out_size, in_size))
            linear.bias.copy_(torch.tensor(layer["bias"], dtype=torch.float32))
        modules += [linear, acts[layer["activation"]]()]
    return nn.Sequential(*modules)


def network_to_json(net: nn.Sequential, template: dict, provenance: dict) -> dict:
    """The template actor with the network's weights (the masked input's weights zero) and where they came from."""
    out = json.loads(json.dumps(template))
    linears = [m for m in net if isinstance(m, nn.Linear)]
    for layer, linear in zip(out["layers"], linears):
        w = linear.weight.detach().double().numpy().copy()
        if layer is out["layers"][0]:
            w[:, LAST_INSERTION] = 0.0
        layer["weight"] = w.reshape(-1).tolist()
        layer["bias"] = linear.bias.detach().double().numpy().tolist()
    out["training_settings"] = provenance
    out["git_commit"] = _git_commit()
    out["source"] = {"algorithm": "behaviour cloning of procedure plans", "init": template.get("source", {})}
    return out


def squared_error(net: nn.Sequential, obs: torch.Tensor, action: torch.Tensor) -> torch.Tensor:
    return ((torch.tanh(net(obs)) - action) ** 2).mean()


def main(argv=None) -> int:
    args = parse_args(argv)
    random.seed(args.seed)
    np.random.seed(args.seed)
    torch.manual_seed(args.seed)
    torch.set_num_threads(1)

    # the data: episodes split (not pairs: one episode's pairs are alike), the last insertion masked
    episodes = load_episodes([Path(d) for d in args.demos])
    order = list(range(len(episodes)))
    random.Random(args.seed).shuffle(order)
    held = set(order[:max(1, int(round(args.holdout * len(episodes))))])
    def stack(keep):
        obs = np.concatenate([e[1] for i, e in enumerate(episodes) if keep(i)])
        obs[:, LAST_INSERTION] = 0.0
        return torch.tensor(obs), torch.tensor(np.concatenate([e[2] for i, e in enumerate(episodes) if keep(i)]))
    train_obs, train_act = stack(lambda i: i not in held)
    held_obs, held_act = stack(lambda i: i in held)

    # the actor: the init actor as gw-train widens it for the generalist's task
    template = widen_for_task(json.loads(Path(args.init_actor).read_text()), OBS_LAYOUT, ACTION_LAYOUT)
    net = network_from_json(template)
    optimiser = torch.optim.Adam(net.parameters(), lr=args.learning_rate)

    # the fit: the lowest held-out error's weights kept
    with torch.no_grad():
        best = (float(squared_error(net, held_obs, held_act)), 0, [p.clone() for p in net.parameters()])
    history = [{"epoch": 0, "held_out_mse": best[0]}]
    start = time.time()
    for epoch in range(1, args.epochs + 1):
        perm = torch.randperm(len(train_obs))
        total = 0.0
        for i in range(0, len(perm), args.batch_size):
            batch = perm[i:i + args.batch_size]
            loss = squared_error(net, train_obs[batch], train_act[batch])
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            total += float(loss.detach()) * len(batch)
        with torch.no_grad():
            held_mse = float(squared_error(net, held_obs, held_act))
        history.append({"epoch": epoch, "train_mse": total / len(perm), "held_out_mse": held_mse})
        print(json.dumps(history[-1]))
        if held_mse < best[0]:
            best = (held_mse, epoch, [p.clone() for p in net.parameters()])
    with torch.no_grad():
        for p, kept in zip(net.parameters(), best[2]):
            p.copy_(kept)

    # the export
    provenance = {"demos": [str(d) for d in args.demos], "episodes": len(episodes), "held_out_episodes": len(held),
                  "pairs": int(len(train_obs) + len(held_obs)), "epochs": args.epochs, "chosen_epoch": best[1],
                  "held_out_mse": best[0], "init_actor": str(args.init_actor), "seed": args.seed,
                  "learning_rate": args.learning_rate, "batch_size": args.batch_size,
                  "masked_inputs": [LAST_INSERTION], "seconds": round(time.time() - start, 1), "history": history}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(network_to_json(net, template, provenance), allow_nan=False))
    print(json.dumps({k: v for k, v in provenance.items() if k != "history"}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
