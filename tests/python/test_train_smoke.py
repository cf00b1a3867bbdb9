"""CI smoke run of the training script: a few hundred SAC steps against two guidewire-servers, the
exported actor equal to SB3's deterministic action through the C++ runtime, and navigate driving
an episode with it (the path from training to the product, end to end)."""

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from guidewire_nav import app_path
from guidewire_nav.env import find_server_binary

REPO = Path(__file__).resolve().parents[2]


def _app(name: str) -> Path:
    path = app_path(name)
    if not path.is_file():
        pytest.skip(f"{name} not built ({path}); set GW_BUILD_DIR")
    return path


@pytest.fixture(scope="module")
def smoke_run(tmp_path_factory):
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    from guidewire_nav import train

    out = tmp_path_factory.mktemp("smoke")
    argv = ["--out", str(out), "--anatomies", "t1_straight_y", "--total-steps", "200", "--learning-starts", "100",
            "--envs", "2", "--eval-every", "0", "--eval-episodes", "1", "--checkpoint-every", "100",
            "--no-progress"]
    assert train.main(argv) == 0
    return out


def test_run_folder_has_logs_curve_checkpoints_and_summary(smoke_run):
    summary = json.loads((smoke_run / "summary.json").read_text())
    assert summary["steps"] >= 200
    assert summary["settings"]["net_arch"] == "256,256,256"  # the paper's 3x256, not SB3's 2x256 default
    assert summary["final_eval"]["episodes"] == 1
    assert (smoke_run / "training_curve.png").stat().st_size > 1000
    assert (smoke_run / "logs" / "progress.csv").is_file()
    assert any((smoke_run / "logs").glob("events.out.tfevents.*"))  # TensorBoard
    assert list((smoke_run / "checkpoints").glob("sac_*_steps.zip"))
    rows = (smoke_run / "monitor.monitor.csv").read_text().splitlines()
    assert rows[1].startswith("r,l,t")


def test_exported_actor_matches_sb3_through_policy_run(smoke_run):
    from stable_baselines3 import SAC

    actor = json.loads((smoke_run / "actor.json").read_text())
    assert actor["obs_layout"] == "guidewire-nav/obs/3"  # the default task: the shipped actor's
    assert actor["training_settings"]["steps"] >= 200
    assert actor["training_settings"]["task_settings"]["format"] == "guidewire-nav/task/1"
    model = SAC.load(smoke_run / "best_model.zip", device="cpu")
    rng = np.random.default_rng(3)
    low, high = model.observation_space.low, model.observation_space.high
    obs = rng.uniform(low, high, size=(64, low.size)).astype(np.float32)
    expected, _ = model.predict(obs, deterministic=True)
    text = "\n".join(" ".join(f"{v:.9g}" for v in row) for row in obs) + "\n"
    res = subprocess.run([str(_app("policy-run")), "--policy", str(smoke_run / "actor.json")], input=text,
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    got = np.array([[float(v) for v in line.split()] for line in res.stdout.splitlines()])
    np.testing.assert_allclose(got, expected, atol=1e-5)


def test_navigate_runs_the_exported_actor(smoke_run):
    t1 = REPO / "anatomies" / "train" / "t1_straight_y" / "t1_straight_y"
    res = subprocess.run([str(_app("navigate")), "--anatomy", f"{t1}.stl", "--centerline", f"{t1}.truth.json",
                          "--target", "1", "--policy", str(smoke_run / "actor.json"), "--json"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    summary = json.loads(res.stdout)
    assert summary["controller"] == "sac-policy"
    assert summary["episodes"] == 1
    assert summary["results"][0]["outcome"] in ("success", "wrong_branch", "stuck", "timeout")


def test_navigate_summary_counts_the_procedures_with_recovery():
    """The last line gives the strict count and, with --recovery, the procedures' count beside it (one
    push-only episode that enters the wrong branch, then is pulled back and reaches the target)."""
    t1 = REPO / "anatomies" / "train" / "t1_straight_y" / "t1_straight_y"
    res = subprocess.run([str(_app("navigate")), "--anatomy", f"{t1}.stl", "--centerline", f"{t1}.truth.json",
                          "--target", "1", "--seed", "2", "--controller", "push-only", "--recovery", "3"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    lines = res.stdout.splitlines()
    assert "-> wrong_branch" in lines[-2] and "with recovery -> success" in lines[-2]
    assert lines[-1].startswith("0/1 reached the target (0%, strict); with recovery 1/1 (100%) in ")


@pytest.mark.parametrize("args,fragment", [
    (["--target", "7", "--controller", "push-only"], "target 7 does not exist"),
    (["--target", "x", "--controller", "push-only"], "'x' is not a number"),
    (["--policy", "/nonexistent/actor.json"], "/nonexistent/actor.json"),
    (["--intermediate-target", "-5", "--controller", "push-only"], "intermediate_target_mm"),
])
def test_navigate_errors_are_one_clear_line(args, fragment):
    t1 = REPO / "anatomies" / "train" / "t1_straight_y" / "t1_straight_y"
    res = subprocess.run([str(_app("navigate")), "--anatomy", f"{t1}.stl", "--centerline", f"{t1}.truth.json", *args],
                         capture_output=True, text=True)
    assert res.returncode == 1
    assert fragment in res.stderr
    assert res.stderr.startswith("error: ")


def test_navigate_refuses_a_missing_mesh(tmp_path):
    res = subprocess.run([str(_app("navigate")), "--anatomy", str(tmp_path / "none.stl"), "--target", "1"],
                         capture_output=True, text=True)
    assert res.returncode == 1
    assert "none.stl" in res.stderr


def test_wall_time_budget_stops_training_and_still_exports(tmp_path):
    """--max-minutes ends learn() early (a lent GPU machine is held for minutes, not hours); with
    --eval-episodes 0 nothing is evaluated in Python and the final actor is exported."""
    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")
    from guidewire_nav import train

    argv = ["--out", str(tmp_path), "--anatomies", "t1_straight_y", "--total-steps", "5000",
            "--learning-starts", "50", "--envs", "1", "--eval-episodes", "0", "--max-minutes", "0.05",
            "--no-progress"]
    assert train.main(argv) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert 0 < summary["steps"] < 5000  # a run without the budget would reach 5000 (minutes)
    assert summary["final_eval"] is None and summary["best_success_rate"] is None
    assert not (tmp_path / "evaluations.jsonl").exists()
    assert json.loads((tmp_path / "actor.json").read_text())["obs_layout"] == "guidewire-nav/obs/3"


def test_fine_tuning_starts_from_the_given_networks(smoke_run, tmp_path):
    """--init-model continues from a saved SAC (here the smoke run's final model) under another task (a force
    cost and a force limit): the exported actor starts as that model's actor, not as a fresh network; the
    servers ran the --task given, and the run records it."""
    import torch
    from stable_baselines3 import SAC
    from guidewire_nav import train

    start = SAC.load(smoke_run / "final_model.zip", device="cpu")
    argv = ["--out", str(tmp_path), "--anatomies", "t1_straight_y", "--total-steps", "60", "--learning-starts", "1000",
            "--envs", "1", "--eval-episodes", "0",
            "--task", '{"reward_force_per_N": 0.5, "force_limit_N": 1.5}',
            "--no-progress", "--init-model", str(smoke_run / "final_model.zip")]
    assert train.main(argv) == 0
    tuned = SAC.load(tmp_path / "final_model.zip", device="cpu")
    # learning_starts > steps: no gradient step was taken, so the networks are the loaded ones.
    for a, b in zip(start.actor.parameters(), tuned.actor.parameters()):
        assert torch.equal(a, b)
    settings = json.loads((tmp_path / "settings.json").read_text())
    assert settings["init_model"].endswith("final_model.zip")
    # the run records the whole task its servers ran: the --task keys, and the defaults for the rest
    assert settings["task_settings"]["reward_force_per_N"] == 0.5
    assert settings["task_settings"]["force_limit_N"] == 1.5
    assert settings["task_settings"]["push_mm_per_s"] == 10.0
    assisted = train.server_args(train.Settings(task='{"recovery_attempts": 3, "recovery_assist": true}'))
    assert assisted[0] == "--task" and json.loads(assisted[1])["recovery_assist"] is True
    assert train.server_args(train.Settings()) == []  # the servers' defaults: the shipped actor's task
    # a jam-prone pool: a lower step cutoff for the servers (the server's own is 10 s, not repeated)
    assert train.server_args(train.Settings(step_cutoff=1.0)) == ["--step-cutoff", "1.0"]


def test_fine_tuning_from_an_exported_actor_keeps_it_while_the_critics_learn(smoke_run, tmp_path):
    """--init-actor loads an exported actor JSON (the shipped policy has no critic) into a fresh SAC;
    with --actor-freeze-steps past the run's end the critics take gradient steps and the actor's mean
    is still exactly the JSON's, and the exported actor.json equals the one it started from."""
    import torch
    from stable_baselines3 import SAC
    from guidewire_nav import train

    argv = ["--out", str(tmp_path), "--anatomies", "t1_straight_y", "--total-steps", "80", "--learning-starts", "20",
            "--batch-size", "16", "--envs", "1", "--eval-episodes", "0", "--no-progress",
            "--init-actor", str(smoke_run / "actor.json"), "--init-log-std", "-1.5", "--actor-freeze-steps", "1000",
            "--actor-learning-rate", "3e-6"]
    assert train.main(argv) == 0
    tuned = SAC.load(tmp_path / "final_model.zip", device="cpu")
    assert tuned.actor.log_std.bias.detach().numpy().tolist() == [-1.5]  # frozen: still the set value
    started = json.loads((smoke_run / "actor.json").read_text())["layers"]
    ended = json.loads((tmp_path / "actor.json").read_text())["layers"]
    for a, b in zip(started, ended):
        np.testing.assert_array_equal(a["weight"], b["weight"])
        np.testing.assert_array_equal(a["bias"], b["bias"])
    # the critics did learn: the target network, a copy at the start, now trails the critic (Polyak)
    moved = [not torch.equal(a, b) for a, b in zip(tuned.critic.parameters(), tuned.critic_target.parameters())]
    assert all(moved)
    settings = json.loads((tmp_path / "settings.json").read_text())
    assert settings["init_actor"].endswith("actor.json") and settings["actor_freeze_steps"] == 1000
    # the actor keeps its own rate through SB3's per-update schedule; the critics keep the shared one
    assert [g["lr"] for g in tuned.actor.optimizer.param_groups] == [3e-6]
    assert [g["lr"] for g in tuned.critic.optimizer.param_groups] == [settings["learning_rate"]]


def _visited_observations(steps: int = 60) -> np.ndarray:
    """Observations of one t1_straight_y episode under random actions (the states an anchor sees)."""
    from guidewire_nav.env import GuidewireEnv

    env = GuidewireEnv(anatomies="t1_straight_y")
    try:
        obs, _ = env.reset(seed=7)
        seen = [obs]
        for _ in range(steps):
            obs, _, terminated, truncated, _ = env.step(env.action_space.sample())
            seen.append(obs)
            if terminated or truncated:
                obs, _ = env.reset()
        return np.array(seen, dtype=np.float32)
    finally:
        env.close()


def test_anchor_holds_a_fine_tuned_actor_near_the_one_it_started_from(smoke_run, tmp_path):
    """At a fast actor rate (3e-3, no freeze) a fine-tuned actor leaves the one it started from;
    --anchor-weight pulls its actions back towards the start's on replayed states, so on the states an
    episode visits it moves much less than without the anchor."""
    import torch
    from stable_baselines3 import SAC
    from guidewire_nav import train
    from guidewire_nav.train import anchor_loss

    common = ["--anatomies", "t1_straight_y", "--total-steps", "300", "--learning-starts", "20",
              "--batch-size", "32", "--envs", "1", "--eval-episodes", "0", "--no-progress",
              "--init-actor", str(smoke_run / "actor.json"), "--actor-learning-rate", "3e-3"]
    assert train.main(["--out", str(tmp_path / "free")] + common) == 0
    assert train.main(["--out", str(tmp_path / "anchored"), "--anchor-weight", "100"] + common) == 0

    start = SAC.load(smoke_run / "best_model.zip", device="cpu").actor  # what actor.json was exported from
    obs = torch.as_tensor(_visited_observations())
    with torch.no_grad():
        moved = {name: anchor_loss(SAC.load(tmp_path / name / "final_model.zip", device="cpu").actor, start, obs).item()
                 for name in ("free", "anchored")}
    assert moved["free"] > 1e-3, moved  # the fast rate does move an unanchored actor
    assert moved["anchored"] < 0.1 * moved["free"], moved  # measured 3e-5 against 1e-2
    assert json.loads((tmp_path / "anchored" / "settings.json").read_text())["anchor_weight"] == "100"


def test_anchor_weights_one_for_every_action_or_one_per_action():
    """--anchor-weight W weighs every action's square by W; W1,W2 each its own (act/2: rotation, insertion), so
    '10,0' ties the aim to the start and leaves the speed free; a wrong count or a negative weight is refused."""
    import torch
    from guidewire_nav.train import anchor_loss, anchor_weights

    assert anchor_weights("10", 2) == [10.0, 10.0] and anchor_weights("10,0", 2) == [10.0, 0.0]
    for bad in ("1,2,3", "-1", "ten"):
        with pytest.raises(SystemExit, match="--anchor-weight"):
            anchor_weights(bad, 2)
    from guidewire_nav.train import per_action  # --init-log-std: any sign, one or one per action
    assert per_action("--init-log-std", "-2.3,0.5", 2) == [-2.3, 0.5] and per_action("--init-log-std", "-2", 2) == [-2, -2]
    with pytest.raises(SystemExit, match="--init-log-std -1,0,1: give one number, or 2"):
        per_action("--init-log-std", "-1,0,1", 2)

    obs = torch.zeros(4, 3)
    moved, start = fixed_actor([0.5, -1.0]), fixed_actor([0.0, 1.0])
    assert anchor_loss(moved, start, obs).item() == pytest.approx(0.25 + 4.0)
    assert anchor_loss(moved, start, obs, torch.tensor([10.0, 0.0])).item() == pytest.approx(2.5)


def fixed_actor(action):
    """An actor whose deterministic action is the constant `action`."""
    import torch

    class Fixed(torch.nn.Module):
        def __init__(self):
            super().__init__()
            self.action = torch.tensor(action)

        def forward(self, obs, deterministic=True):
            return self.action.expand(obs.shape[0], -1)

    return Fixed()


def test_the_anchor_leaves_wrong_branch_states_free():
    """States with the wrong-branch flag raised (--wrong-branch-starts' and any recovery's) are not held to the
    starting actor: it never acted there."""
    import torch
    from guidewire_nav.train import anchor_loss

    obs = torch.zeros(4, 15)
    obs[:2, 13] = 1.0  # two of four states in a wrong child
    moved, start = fixed_actor([0.5, -1.0]), fixed_actor([0.0, 1.0])
    assert anchor_loss(moved, start, obs).item() == pytest.approx(4.25)
    assert anchor_loss(moved, start, obs, free_index=13).item() == pytest.approx(4.25 / 2)
    assert anchor_loss(moved, start, obs, torch.tensor([10.0, 0.0]), 13).item() == pytest.approx(2.5 / 2)


def test_init_actor_refuses_a_network_of_another_shape(smoke_run, tmp_path):
    from guidewire_nav import train

    argv = ["--out", str(tmp_path), "--anatomies", "t1_straight_y", "--total-steps", "10", "--envs", "1",
            "--eval-episodes", "0", "--no-progress", "--net-arch", "64,64", "--init-actor", str(smoke_run / "actor.json")]
    with pytest.raises(ValueError, match=r"do not match the model's .*--net-arch"):
        train.main(argv)


def test_score_checkpoints_exports_and_scores_a_run(smoke_run, capsys):
    _app("navigate")
    from guidewire_nav import score_checkpoints

    assert score_checkpoints.main([str(smoke_run), "--steps", "100", "--episodes", "1", "--train-episode-scale", "0",
                                   "--threads", "2"]) == 0
    exported = json.loads((smoke_run / "scored" / "ckpt_100.json").read_text())
    assert exported["obs_layout"] == "guidewire-nav/obs/3"  # the run's task (settings.json): the default
    report = json.loads((smoke_run / "scores.json").read_text())
    s = report["scores"]["100"]
    assert s["validation_episodes"] == 15  # 4 + 4 + 3 + 4 validation targets, one episode each
    assert {name: sorted(map(int, t)) for name, t in s["validation"].items()} == {
        Path(mesh).stem: targets for mesh, targets in score_checkpoints.VALIDATION}
    # A count is what navigate itself says for that actor, anatomy, target and seed (1000, the default).
    mesh, targets = score_checkpoints.VALIDATION[0]
    alone = subprocess.run([str(_app("navigate")), "--anatomy", mesh, "--target", str(targets[0]), "--policy",
                            str(smoke_run / "scored" / "ckpt_100.json"), "--episodes", "1", "--seed", "1000", "--json"],
                           capture_output=True, text=True, cwd=REPO, check=True)
    assert s["validation"][Path(mesh).stem][str(targets[0])] == json.loads(alone.stdout)["outcomes"]["success"]
    assert "| 100 |" in capsys.readouterr().out

    # A checkpoint the run does not have is named, not a traceback.
    assert score_checkpoints.main([str(smoke_run), "--steps", "12345", "--train-episode-scale", "0"]) == 1
    assert "sac_12345_steps.zip: no such checkpoint" in capsys.readouterr().err


def test_init_actor_brings_its_layouts_into_the_task(tmp_path):
    """--init-actor: the task takes the actor's layouts where it names none (the paper's obs/1 actor fine-tunes in
    its own task without a --task), refuses a task naming others, and lets a rotation actor start a push/pull task."""
    from guidewire_nav import train

    paper = tmp_path / "paper_actor.json"
    paper.write_text(json.dumps({"obs_layout": "guidewire-nav/obs/1", "action_layout": "guidewire-nav/act/1",
                                 "action_size": 1, "layers": []}))
    args = train.server_args(train.Settings(init_actor=str(paper)))
    assert args[0] == "--task" and json.loads(args[1]) == {"observation": "guidewire-nav/obs/1",
                                                           "action": "guidewire-nav/act/1"}
    kept = json.loads(train.server_args(train.Settings(init_actor=str(paper), task='{"push_mm_per_s": 5}'))[1])
    assert kept["push_mm_per_s"] == 5 and kept["observation"] == "guidewire-nav/obs/1"
    with pytest.raises(SystemExit, match=r"obs/1 actor but --task sets observation guidewire-nav/obs/3"):
        train.server_args(train.Settings(init_actor=str(paper), task='{"observation": "guidewire-nav/obs/3"}'))
    push_pull = '{"action": "guidewire-nav/act/2", "observation": "guidewire-nav/obs/5"}'
    assert json.loads(train.server_args(train.Settings(init_actor=str(paper), task=push_pull))[1]) == json.loads(push_pull)
    with pytest.raises(SystemExit, match="--init-actor: .*no such file"):
        train.server_args(train.Settings(init_actor=str(tmp_path / "missing.json")))
