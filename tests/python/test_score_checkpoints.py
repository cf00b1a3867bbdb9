"""score_checkpoints runs actors through the C++ runtime on the validation trees and the training anatomies."""

import json
from pathlib import Path

import pytest

from guidewire_nav import score_checkpoints

REPO = Path(__file__).resolve().parents[2]
SHIPPED = REPO / "policy" / "trained" / "sac_actor.json"


def _built() -> None:
    try:
        score_checkpoints.app("navigate"), score_checkpoints.app("evaluate")
    except FileNotFoundError as e:
        pytest.skip(str(e))


def test_shipped_actor_scores_on_validation_trees_and_training_anatomies(tmp_path):
    _built()
    out = tmp_path / "scores.json"
    assert score_checkpoints.main(["--actors", str(SHIPPED), "--episodes", "1", "--train-episode-scale", "0.02",
                                   "--threads", "2", "--out", str(out)]) == 0
    s = json.loads(out.read_text())["scores"][str(SHIPPED)]
    assert s["validation_episodes"] == 15
    # The shipped actor (obs/3, 2026-11-30) reached all 150 validation episodes at 10 per target (seeds 1000+
    # and 2000+); the obs/2 actor before it 142 and 139. Push-only gets ~20% on such trees.
    assert s["validation_successes"] >= 9
    # The training row's 100 episodes at scale 0.02; the shipped actor reached 40 of 40 there (seeds 5000+).
    assert s["training_episodes"] == 2
    assert s["training_successes"] == 2


def test_a_broken_actor_file_is_a_clear_error(tmp_path, capsys):
    _built()
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "guidewire-nav/actor/1", "layers": []}')
    assert score_checkpoints.main(["--actors", str(bad), "--episodes", "1", "--train-episode-scale", "0"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "bad.json" in err


def test_needs_a_run_or_actors():
    with pytest.raises(SystemExit):
        score_checkpoints.main([])


def test_a_runs_layout_follows_its_settings():
    from guidewire_nav.env import find_server_binary
    from guidewire_nav.train import Settings, server_args

    if not find_server_binary().is_file():
        pytest.skip("guidewire-server not built; set GW_SERVER_BIN or GW_BUILD_DIR")

    # runs since --task: their task JSON ({} = the defaults, the shipped actor's obs/3)
    assert score_checkpoints.run_layout({"task": ""}) == "guidewire-nav/obs/3"
    assert score_checkpoints.run_layout({"task": '{"observation": "guidewire-nav/obs/1"}'}) == "guidewire-nav/obs/1"
    assert score_checkpoints.run_layout({"task": "training/tasks/push_pull.json"}) == "guidewire-nav/obs/5"
    # runs before it (settings.json with the observation flags); obs/2 and obs/7 are retired
    with pytest.raises(SystemExit, match="retired"):
        score_checkpoints.run_layout({})
    assert score_checkpoints.run_layout({"omega_plane": "correct_branch"}) == "guidewire-nav/obs/1"
    assert score_checkpoints.run_layout({"omega_plane": "approach", "omega_side": True}) == "guidewire-nav/obs/3"
    assert score_checkpoints.run_layout({"omega_side": True, "junctions": "combined"}) == "guidewire-nav/obs/4"
    # the servers get the task JSON as it is, one argument
    args = server_args(Settings(task='{"observation": {"junctions": "combined"}}'))
    assert args == ["--task", '{"observation":{"junctions":"combined"}}']
    assert server_args(Settings()) == []
