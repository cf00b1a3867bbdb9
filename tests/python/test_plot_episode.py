"""guidewire_nav.plot_episode: a navigate trajectory becomes a per-step picture; unusable files are named."""

import json

from guidewire_nav import plot_episode

NAMES = ["theta_t_1", "theta_t_2", "theta_t_3", "theta_prev_1", "theta_prev_2", "theta_prev_3",
         "lambda_t", "lambda_prev", "action", "omega", "speed"]


def trajectory(n=30, with_observation=True):
    frames = {"time_s": [0.04 * k for k in range(n)], "tip": [[0, 0, 0.4 * k] for k in range(n)],
              "action": [0.0] + [0.5] * (n - 1), "agent_in_control": [10 <= k < 20 for k in range(n)]}
    trace = {"schema": "guidewire-nav/trajectory/1", "anatomy": "coronary", "controller": "sac-policy",
             "target_id": 2, "seed": 7, "outcome": "wrong_branch", "detail": "entered a wrong branch before goal 2 of 2",
             "num_frames": n, "frames": frames, "wire_shapes": []}
    if with_observation:
        trace["observation_names"] = NAMES
        frames["observation"] = [[1.0] * 6 + [1 - k / n, 1 - k / n, 0.5, None if k == 3 else -0.5, 1.0]
                                 for k in range(n)]
        frames["goal"] = [0 if k < 15 else 1 for k in range(n)]
    return trace


def test_control_spans():
    assert plot_episode.control_spans([False, True, True, False, True]) == [(1, 3), (4, 5)]
    assert plot_episode.control_spans([]) == []


def test_a_trajectory_becomes_a_png(tmp_path, capsys):
    path = tmp_path / "episode0_target2.json"
    path.write_text(json.dumps(trajectory()))
    assert plot_episode.main([str(path)]) == 0
    png = tmp_path / "episode0_target2_steps.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert str(png) in capsys.readouterr().out
    episode = plot_episode.load_episode(path)
    assert "wrong_branch" in episode["title"] and list(episode["goal"]).count(1) == 15
    assert "at the lost bifurcation" not in episode["title"]  # a file without omega_at_loss still loads
    aimed = trajectory()
    aimed["omega_at_loss"] = -0.993
    path.write_text(json.dumps(aimed))
    assert "omega -0.99 at the lost bifurcation" in plot_episode.load_episode(path)["title"]


def test_files_that_cannot_be_plotted_are_named(tmp_path, capsys):
    old = tmp_path / "old.json"
    old.write_text(json.dumps(trajectory(with_observation=False)))
    assert plot_episode.main([str(old)]) == 2
    assert "old.json" in capsys.readouterr().err
    garbage = tmp_path / "garbage.json"
    garbage.write_text("{not json")
    assert plot_episode.main([str(garbage)]) == 2
    assert "garbage.json" in capsys.readouterr().err
    bad = trajectory()
    bad["frames"]["observation"][4] = [0.0]
    shape = tmp_path / "shape.json"
    shape.write_text(json.dumps(bad))
    assert plot_episode.main([str(shape)]) == 2
    assert "observation names" in capsys.readouterr().err
