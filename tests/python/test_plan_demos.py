"""The planner's demonstrations as a data set (gw-plan-demos) and the actor cloned from them (gw-clone-plans)."""
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from conftest import app_or_skip as app
from guidewire_nav import clone_plans, plan_demos
from guidewire_nav.export_actor import widen_for_task

REPO = Path(__file__).resolve().parents[2]
T1 = REPO / "anatomies/train/t1_straight_y/t1_straight_y.stl"
SHIPPED = REPO / "policy/trained/sac_actor.json"


def one_anatomy_pool(tmp_path: Path) -> Path:
    """A pool index of one anatomy, the training Y (two targets); skips when plan is not built."""
    app("plan")
    index = tmp_path / "pool" / "index.json"
    index.parent.mkdir()
    index.write_text(json.dumps({"anatomies": [{"name": "y", "set": "train", "mesh": str(T1)}]}))
    return index


def test_plan_demos_plans_every_target_once_and_resumes(tmp_path):
    index, out = one_anatomy_pool(tmp_path), tmp_path / "demos"
    assert plan_demos.main(["--anatomies", str(index), "--out", str(out), "--max-episodes", "1", "--jobs", "1"]) == 0
    assert plan_demos.main(["--anatomies", str(index), "--out", str(out), "--jobs", "2"]) == 0  # the rest, not again
    lines = [json.loads(x) for x in (out / "plans.jsonl").read_text().splitlines()]
    assert sorted(d["target"] for d in lines) == [1, 2]
    assert len({d["seed"] for d in lines}) == 2  # each episode its own start
    assert len((out / "settings.jsonl").read_text().splitlines()) == 2
    for d in lines:
        assert d["found"] in ("strict", "procedure") and d["peak_tip_force_N"] <= 1.5
        pairs = [json.loads(x) for x in (out / "episodes" / d["demos"]).read_text().splitlines()]
        assert len(pairs) == d["steps"]
        assert all(len(p["obs"]) == 15 and len(p["action"]) == 2 for p in pairs)


def test_plan_demos_from_a_lead_in_records_it(tmp_path):
    index, out = one_anatomy_pool(tmp_path), tmp_path / "demos"
    plan_demos.main(["--anatomies", str(index), "--out", str(out), "--max-episodes", "1", "--lead-in", str(SHIPPED)])
    (line,) = [json.loads(x) for x in (out / "plans.jsonl").read_text().splitlines()]
    assert line["lead_in"]["outcome"] == "success" and line["lead_in"]["steps"] == line["steps"] > 0
    assert (out / "episodes" / line["demos"]).read_text() == ""  # it reached the target: nothing to relabel


def write_demos(folder: Path, episodes: int, steps: int, rng) -> None:
    """Episodes whose insertion falls with obs entry 14 (pull when the tip presses) and whose last
    insertion entry (12) copies the action, as a plan's held actions do."""
    (folder / "episodes").mkdir(parents=True)
    for e in range(episodes):
        with (folder / "episodes" / f"e{e}.jsonl").open("w") as f:
            for _ in range(steps):
                obs = rng.uniform(-1, 1, 15)
                action = [0.3 * obs[0], -0.8 * obs[14]]
                obs[12] = action[1]
                f.write(json.dumps({"obs": obs.tolist(), "action": action}) + "\n")


def actor_forward(d: dict, obs: np.ndarray) -> np.ndarray:
    """The exported actor's deterministic action, as policy/ computes it."""
    x = obs
    for layer in d["layers"]:
        x = np.asarray(layer["weight"]).reshape(layer["shape"]) @ x + np.asarray(layer["bias"])
        x = np.maximum(x, 0) if layer["activation"] == "relu" else x
    return np.tanh(x)


def test_clone_plans_fits_the_demonstrations_without_reading_the_last_insertion(tmp_path):
    rng = np.random.default_rng(0)
    write_demos(tmp_path / "demos", 10, 200, rng)
    out = tmp_path / "actor.json"
    assert clone_plans.main(["--demos", str(tmp_path / "demos"), "--init-actor", str(SHIPPED), "--out", str(out),
                             "--epochs", "60", "--learning-rate", "1e-3", "--seed", "3"]) == 0
    d = json.loads(out.read_text())
    template = widen_for_task(json.loads(SHIPPED.read_text()), "guidewire-nav/obs/8", "guidewire-nav/act/2")
    assert (d["obs_layout"], d["action_layout"], d["obs_size"]) == ("guidewire-nav/obs/8", "guidewire-nav/act/2", 15)
    assert [l["shape"] for l in d["layers"]] == [l["shape"] for l in template["layers"]]
    first = np.asarray(d["layers"][0]["weight"]).reshape(d["layers"][0]["shape"])
    assert not first[:, clone_plans.LAST_INSERTION].any()  # the copycat input is not read
    history = d["training_settings"]["history"]
    assert d["training_settings"]["held_out_mse"] < 0.5 * history[0]["held_out_mse"]
    obs = rng.uniform(-1, 1, (200, 15))
    insertion = np.array([actor_forward(d, o)[1] for o in obs])
    pressed = np.abs(obs[:, 14]) > 0.3
    assert np.mean(np.sign(insertion[pressed]) == -np.sign(obs[pressed, 14])) > 0.9  # pulls when the tip presses

    again = tmp_path / "again.json"
    clone_plans.main(["--demos", str(tmp_path / "demos"), "--init-actor", str(SHIPPED), "--out", str(again),
                      "--epochs", "60", "--learning-rate", "1e-3", "--seed", "3"])
    assert json.loads(again.read_text())["layers"] == d["layers"]  # the same seed, the same actor

    navigate = app("navigate")  # the C++ runtime takes it as an actor of the generalist's task
    r = subprocess.run([navigate, "--anatomy", str(T1), "--target", "1", "--policy", str(out),
                        "--task", str(REPO / "training/tasks/generalist.json"), "--json"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr


def test_clone_plans_refuses_other_layouts_and_empty_sets(tmp_path):
    (tmp_path / "empty" / "episodes").mkdir(parents=True)
    with pytest.raises(SystemExit, match="no demonstrations"):
        clone_plans.main(["--demos", str(tmp_path / "empty"), "--init-actor", str(SHIPPED), "--out", "x.json"])
    (tmp_path / "short" / "episodes").mkdir(parents=True)
    (tmp_path / "short" / "episodes" / "e.jsonl").write_text(json.dumps({"obs": [0.0] * 14, "action": [0, 1]}) + "\n")
    with pytest.raises(SystemExit, match="sizes \\[14\\], expected 15"):
        clone_plans.main(["--demos", str(tmp_path / "short"), "--init-actor", str(SHIPPED), "--out", "x.json"])
