"""Export the deterministic actor of an SB3 SAC model to the JSON format read by policy/ (C++).

action = low + (tanh(mu(latent_pi(normalise(obs)))) + 1) / 2 * (high - low)

SB3 pitfalls handled here:
- net_arch: the hidden layers are read from the model's `latent_pi`, never assumed (SB3's default is
  2x256, the paper's 3x256).
- gSDE (use_sde=True): `mu` is still the deterministic mean; with clip_mean > 0 SB3 wraps it in a
  Hardtanh, which the runtime does not implement, so that case is refused with a clear error.
- VecNormalize statistics live outside the model zip: pass them (object or .pkl path) explicitly.

CLI: python -m guidewire_nav.export_actor model.zip out.json [--vecnormalize stats.pkl]
"""

from __future__ import annotations

import argparse
import copy
import json
import pickle
import subprocess
from pathlib import Path

import numpy as np
import torch.nn as nn

FORMAT = "guidewire-nav/actor/1"
_ACTIVATIONS = {nn.ReLU: "relu", nn.Tanh: "tanh", nn.Identity: "identity"}


def _git_commit() -> str | None:
    try:
        root = Path(__file__).resolve().parents[2]
        out = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, check=True)
        return out.stdout.strip()
    except Exception:  # noqa: BLE001 - no git is not an error for an export
        return None


def _linear(layer: nn.Linear, activation: str) -> dict:
    w = layer.weight.detach().cpu().double().numpy()
    return {
        "shape": [int(w.shape[0]), int(w.shape[1])],
        "weight": w.reshape(-1).tolist(),  # row-major (out, in)
        "bias": layer.bias.detach().cpu().double().numpy().tolist(),
        "activation": activation,
    }


def _actor_layers(actor) -> list[dict]:
    layers: list[dict] = []
    modules = list(actor.latent_pi)
    i = 0
    while i < len(modules):
        m = modules[i]
        if not isinstance(m, nn.Linear):
            raise ValueError(f"export_actor: unsupported module {m!r} in latent_pi (expected Linear + activation)")
        act = "identity"
        if i + 1 < len(modules) and not isinstance(modules[i + 1], nn.Linear):
            nxt = modules[i + 1]
            if type(nxt) not in _ACTIVATIONS:
                raise ValueError(f"export_actor: unsupported activation {nxt!r} (supported: ReLU, Tanh)")
            act = _ACTIVATIONS[type(nxt)]
            i += 1
        layers.append(_linear(m, act))
        i += 1
    mu = actor.mu
    if not isinstance(mu, nn.Linear):
        raise ValueError(
            f"export_actor: actor.mu is {mu!r}, not a plain Linear; with gSDE this is SB3's clip_mean Hardtanh, "
            "which the runtime does not support: train with use_sde=False or policy_kwargs clip_mean=0"
        )
    layers.append(_linear(mu, "identity"))
    return layers


def _load_vecnormalize(vecnormalize):
    if vecnormalize is None or hasattr(vecnormalize, "obs_rms"):
        return vecnormalize
    with open(vecnormalize, "rb") as f:
        return pickle.load(f)


def actor_to_dict(model, obs_layout: str, vecnormalize=None, training_settings: dict | None = None,
                  action_layout: str = "") -> dict:
    """SB3 SAC model (+ optional VecNormalize or its .pkl path) -> actor JSON dictionary. `action_layout`:
    the server's spec's; '' = by the action size (1: guidewire-nav/act/1, 2: guidewire-nav/act/2)."""
    policy = model.policy
    actor = policy.actor
    obs_space, act_space = model.observation_space, model.action_space
    if len(obs_space.shape) != 1 or len(act_space.shape) != 1:
        raise ValueError(f"export_actor: need flat Box spaces, got {obs_space} and {act_space}")
    if not getattr(policy, "squash_output", True) and not actor.use_sde:
        raise ValueError("export_actor: SAC actor without tanh squashing is not supported")
    layers = _actor_layers(actor)
    obs_size, action_size = int(obs_space.shape[0]), int(act_space.shape[0])
    if layers[0]["shape"][1] != obs_size or layers[-1]["shape"][0] != action_size:
        raise ValueError("export_actor: actor network sizes do not match the model spaces")

    norm = None
    vn = _load_vecnormalize(vecnormalize)
    if vn is not None and getattr(vn, "norm_obs", True):
        if isinstance(vn.obs_rms, dict):
            raise ValueError("export_actor: dict observations in VecNormalize are not supported")
        norm = {
            "mean": np.asarray(vn.obs_rms.mean, dtype=np.float64).tolist(),
            "var": np.asarray(vn.obs_rms.var, dtype=np.float64).tolist(),
            "clip": float(vn.clip_obs),
            "epsilon": float(vn.epsilon),
        }
        if len(norm["mean"]) != obs_size:
            raise ValueError(f"export_actor: VecNormalize has {len(norm['mean'])} obs entries, model has {obs_size}")

    return {
        "format": FORMAT,
        "obs_size": obs_size,
        "action_size": action_size,
        "obs_layout": obs_layout,
        "action_layout": action_layout or ("guidewire-nav/act/1" if action_size == 1 else "guidewire-nav/act/2"),
        "obs_normalization": norm,
        "layers": layers,
        "output": {
            "squash": "tanh",
            "low": np.asarray(act_space.low, dtype=np.float64).tolist(),
            "high": np.asarray(act_space.high, dtype=np.float64).tolist(),
        },
        "training_settings": training_settings or {},
        "git_commit": _git_commit(),
        "source": {"algorithm": "SB3 SAC", "use_sde": bool(actor.use_sde)},
    }


def export_sac_actor(model, path, obs_layout: str = "unspecified", vecnormalize=None, training_settings=None,
                     action_layout: str = "") -> dict:
    """Write the deterministic actor of `model` to `path` (JSON); returns the dictionary written."""
    d = actor_to_dict(model, obs_layout, vecnormalize, training_settings, action_layout)
    Path(path).write_text(json.dumps(d, allow_nan=False))  # NaN weights: refuse, never write
    return d


PUSH_PULL_INSERTION_BIAS = 2.0  # tanh(2) = 0.96: a widened actor starts out pushing at 96% of the push speed


def widened_layers(d: dict, extra: int, what: str) -> list:
    """A copy of d's layers whose first takes `extra` more inputs, with zero weights (what: the caller, for errors)."""
    if d.get("obs_normalization"):
        raise ValueError(f"{what}: an actor with observation normalisation is not supported")
    layers = copy.deepcopy(d["layers"])
    rows, cols = layers[0]["shape"]
    w = np.asarray(layers[0]["weight"], dtype=np.float64).reshape(rows, cols)
    layers[0]["weight"] = np.hstack([w, np.zeros((rows, extra))]).reshape(-1).tolist()
    layers[0]["shape"] = [rows, cols + extra]
    return layers


def widen_to_push_pull(d: dict, insertion_bias: float = PUSH_PULL_INSERTION_BIAS) -> dict:
    """A rotation actor (obs/3, act/1) as the start of a push/pull actor (obs/5).

    in:  d, an actor dictionary of layout guidewire-nav/obs/3 and guidewire-nav/act/1
    out: a new dictionary of layouts obs/5 and act/2 whose rotation output is d's on every observation
         (the new inputs, the last insertion and the wrong-branch flag, get zero weights) and whose insertion
         output is tanh(insertion_bias) everywhere (zero weights). Why: started so, the push/pull run begins as
         the shipped rotation actor under a near-constant push and has to learn when to stop and pull back,
         not to aim again from scratch (the rotation actor took 94,522 steps for that)."""
    if d.get("obs_layout") != "guidewire-nav/obs/3" or d.get("action_size") != 1:
        raise ValueError(f"widen_to_push_pull: need an obs/3 rotation actor (action size 1), got "
                         f"{d.get('obs_layout')!r} with action size {d.get('action_size')!r}")
    layers = widened_layers(d, 2, "widen_to_push_pull")
    last = layers[-1]
    hidden = last["shape"][1]
    last["weight"] = list(last["weight"]) + [0.0] * hidden
    last["bias"] = list(last["bias"]) + [float(insertion_bias)]
    last["shape"] = [2, hidden]
    out = {**copy.deepcopy(d), "obs_size": layers[0]["shape"][1], "action_size": 2,
           "obs_layout": "guidewire-nav/obs/5",
           "action_layout": "guidewire-nav/act/2", "layers": layers,
           "output": {"squash": "tanh", "low": list(d["output"]["low"]) + [-1.0],
                      "high": list(d["output"]["high"]) + [1.0]}}
    out["source"] = {**d.get("source", {}), "widened_from": d.get("obs_layout")}
    return out


def widen_to_tip_force(d: dict) -> dict:
    """A push/pull actor (obs/5, act/2) as the start of one that also reads the tip's wall force (obs/8).

    in:  d, an actor dictionary of layout guidewire-nav/obs/5 and guidewire-nav/act/2
    out: a new dictionary of layout obs/8 whose outputs are d's on every observation (the tip-force input gets zero
         weights), so fine-tuning starts from the push/pull actor and learns what to do with the force."""
    if d.get("obs_layout") != "guidewire-nav/obs/5" or d.get("action_size") != 2:
        raise ValueError(f"widen_to_tip_force: need an obs/5 push/pull actor (action size 2), got "
                         f"{d.get('obs_layout')!r} with action size {d.get('action_size')!r}")
    layers = widened_layers(d, 1, "widen_to_tip_force")
    out = {**copy.deepcopy(d), "obs_size": layers[0]["shape"][1], "obs_layout": "guidewire-nav/obs/8", "layers": layers}
    out["source"] = {**d.get("source", {}), "widened_from": d.get("obs_layout")}
    return out


def widen_for_task(d: dict, obs_layout: str, action_layout: str) -> dict:
    """An actor as the start of a task of these layouts: a rotation actor (act/1) starting an act/2 task is widened by
    widen_to_push_pull, an obs/5 actor starting an obs/8 task by widen_to_tip_force (both, in turn, for a rotation
    actor starting an obs/8 act/2 task); any other actor is returned as it is."""
    if action_layout == "guidewire-nav/act/2" and d.get("action_size") == 1:
        d = widen_to_push_pull(d)
    if obs_layout == "guidewire-nav/obs/8" and d.get("obs_layout") == "guidewire-nav/obs/5":
        d = widen_to_tip_force(d)
    return d


def load_actor_json(model, path, log_std: float | list = -2.3) -> dict:
    """The inverse of the export, for fine-tuning a shipped actor whose critic was not kept: copy the
    JSON's layers (`path`: a file, or the dictionary itself) into `model`'s actor (latent_pi + mu) and
    return the dictionary. The JSON holds only
    the deterministic mean, so the log-std head is set to a constant `log_std` (zero weights; one value, or one
    per action): -2.3 gives
    std ~0.1 before tanh, about what SAC's automatic entropy (target -1 for one action) settles at.
    Refuses, naming the mismatch, an actor whose layer shapes, activations, action bounds or observation
    normalisation differ from what `model` computes, rather than loading it half."""
    import torch

    d = path if isinstance(path, dict) else json.loads(Path(path).read_text())
    name = f"actor {d.get('obs_layout')}/{d.get('action_layout')}" if isinstance(path, dict) else path
    if d.get("format") != FORMAT:
        raise ValueError(f"load_actor_json: {name}: format {d.get('format')!r}, expected {FORMAT!r}")
    if d.get("obs_normalization"):
        raise ValueError(f"load_actor_json: {name}: has observation normalisation; SB3's MlpPolicy has none")
    actor = model.policy.actor
    if actor.use_sde:
        raise ValueError("load_actor_json: the model uses gSDE; its log-std is not a layer to set")
    want = _actor_layers(actor)
    have = d["layers"]
    if [(l["shape"], l["activation"]) for l in have] != [(l["shape"], l["activation"]) for l in want]:
        raise ValueError(f"load_actor_json: {name}: layers {[(l['shape'], l['activation']) for l in have]} do not "
                         f"match the model's {[(l['shape'], l['activation']) for l in want]} (check --net-arch)")
    for key in ("low", "high"):
        if not np.allclose(d["output"][key], getattr(model.action_space, key)):
            raise ValueError(f"load_actor_json: {name}: action {key} {d['output'][key]} differs from the model's "
                             f"{getattr(model.action_space, key).tolist()}")
    linears = [m for m in actor.latent_pi if isinstance(m, nn.Linear)] + [actor.mu]
    with torch.no_grad():
        for layer, saved in zip(linears, have):
            layer.weight.copy_(torch.tensor(saved["weight"]).reshape(saved["shape"]))
            layer.bias.copy_(torch.tensor(saved["bias"]))
        actor.log_std.weight.zero_()
        actor.log_std.bias.copy_(torch.as_tensor(log_std, dtype=actor.log_std.bias.dtype).expand_as(actor.log_std.bias))
    return d


def main(argv=None) -> None:
    from stable_baselines3 import SAC

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("model", help="SB3 SAC model .zip")
    p.add_argument("out", help="output actor .json")
    p.add_argument("--vecnormalize", help="VecNormalize statistics .pkl (not stored in the zip)")
    p.add_argument("--obs-layout", default="guidewire-nav/obs/3",
                   help="observation layout the model was trained on, the server's spec obs_layout (a gw-train "
                        "run's actor.json records it): guidewire-nav/obs/3 (the default task), guidewire-nav/obs/1 "
                        "(training/tasks/paper.json, the paper's omega), /obs/4, /obs/6 (junction readings) or "
                        "guidewire-nav/obs/5 (training/tasks/push_pull.json; docs/task_settings.md); default "
                        "%(default)s. The action layout follows the action size")
    a = p.parse_args(argv)
    model = SAC.load(a.model, device="cpu")
    export_sac_actor(model, a.out, obs_layout=a.obs_layout, vecnormalize=a.vecnormalize)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
