"""GuidewireEnv: the gymnasium client of guidewire-server (checkers, determinism, vector envs, shutdown)."""

import math
import subprocess

import numpy as np
import pytest

from guidewire_nav.env import GuidewireEnv, RestartingEnv, ServerError, find_server_binary, make_env, start_server


@pytest.fixture(scope="module")
def server_bin():
    path = find_server_binary()
    if not path.is_file():
        pytest.skip(f"guidewire-server not built ({path}); set GW_SERVER_BIN or GW_BUILD_DIR")
    return path


@pytest.fixture(scope="module")
def env(server_bin):
    e = GuidewireEnv(anatomies="t1_straight_y")
    yield e
    e.close()


def test_spaces_follow_the_spec(env):
    assert env.observation_space.shape == (12,)  # the default task: the shipped actor's obs/3
    assert env.action_space.shape == (1,)
    assert env.observation_space.dtype == np.float32
    assert env.observation_names[9] == "omega"
    assert env.anatomy_names == ["t1_straight_y"]


def test_gymnasium_and_sb3_checkers_pass(env):
    from gymnasium.utils.env_checker import check_env as gym_check
    from stable_baselines3.common.env_checker import check_env as sb3_check

    gym_check(env, skip_render_check=True)
    sb3_check(env, warn=True)


def test_same_seed_and_actions_give_the_same_trajectory(env):
    def run(seed):
        obs, info = env.reset(seed=seed)
        trace = [obs]
        rewards = []
        for k in range(15):
            obs, r, term, trunc, _ = env.step(np.array([math.sin(k)], dtype=np.float32))
            trace.append(obs)
            rewards.append(r)
            if term or trunc:
                break
        return np.stack(trace), rewards, info

    a, ra, ia = run(123)
    b, rb, ib = run(123)
    c, _, ic = run(124)
    assert np.array_equal(a, b) and ra == rb
    assert ia["start_rotation_rad"] == ib["start_rotation_rad"]
    assert ic["start_rotation_rad"] != ia["start_rotation_rad"]


def test_reset_options_and_server_errors(env):
    _, info = env.reset(seed=1, options={"anatomy": "t1_straight_y", "target": 2})
    assert info["anatomy"] == "t1_straight_y" and info["target"] == 2
    with pytest.raises(ServerError, match="unknown anatomy"):
        env.reset(seed=1, options={"anatomy": "nowhere"})
    with pytest.raises(ServerError, match="valid targets"):
        env.reset(seed=1, options={"target": 99})
    env.reset(seed=1)
    with pytest.raises(ValueError, match="not finite"):
        env.step(np.array([np.nan]))
    with pytest.raises(ValueError, match="1 value"):
        env.step(np.array([0.1, 0.2]))
    obs, reward, *_ = env.step(np.array([0.2]))  # still usable
    assert np.all(np.isfinite(obs)) and math.isfinite(reward)


def test_connects_to_a_running_server_and_closes_cleanly(server_bin):
    proc, port = start_server("t1_straight_y")
    try:
        e1 = GuidewireEnv(host="127.0.0.1", port=port)
        e2 = GuidewireEnv(port=port)
        o1, _ = e1.reset(seed=5)
        o2, _ = e2.reset(seed=5)
        assert np.array_equal(o1, o2)  # one independent env per connection
        for action in (1.0, -0.5, 0.0):  # interleaved: each connection keeps its own episode
            assert np.array_equal(e1.step([action])[0], e2.step([action])[0])
        e1.close()
        e1.close()  # idempotent
        e2.close()
        assert proc.poll() is None  # closing clients does not stop a shared server
    finally:
        proc.terminate()
        assert proc.wait(timeout=10) == 0  # SIGTERM: clean exit


def test_own_server_is_stopped_on_close(server_bin):
    e = GuidewireEnv(anatomies="t1_straight_y")
    proc = e._proc
    assert proc is not None and proc.poll() is None
    e.close()
    assert proc.poll() == 0


def test_subproc_vec_env_with_one_server_per_env(server_bin):
    from stable_baselines3.common.vec_env import SubprocVecEnv

    venv = SubprocVecEnv([make_env(i, anatomies="t1_straight_y") for i in range(2)])
    try:
        venv.seed(7)
        obs = venv.reset()
        assert obs.shape == (2, 12)
        for _ in range(3):
            obs, rewards, dones, infos = venv.step(np.zeros((2, 1), dtype=np.float32))
        assert obs.shape == (2, 12) and rewards.shape == (2,)
        assert all("progress_mm" in i for i in infos)
    finally:
        venv.close()


def test_omega_plane_is_chosen_at_the_server_and_reported(server_bin):
    # Same episode, same actions: only omega (index 9) may differ between the two planes.
    ours = GuidewireEnv(anatomies="t3_out_of_plane_steep", options={"target": 1})
    paper = GuidewireEnv(anatomies="t3_out_of_plane_steep", options={"target": 1},
                         server_args=["--omega-plane", "correct_branch"])
    try:
        assert ours.spec_reply["obs_layout"] == "guidewire-nav/obs/3"
        assert paper.spec_reply["obs_layout"] == "guidewire-nav/obs/1"
        a, _ = ours.reset(seed=4)
        b, _ = paper.reset(seed=4)
        for _ in range(150):  # up to the 90-degree side branch
            a, *_ = ours.step(np.array([0.0], dtype=np.float32))
            b, *_ = paper.step(np.array([0.0], dtype=np.float32))
        assert len(a) == 12 and len(b) == 11  # obs/3 has omega's sine too
        assert np.array_equal(np.delete(a[:11], 9), np.delete(b, 9))
        assert a[9] != b[9]
    finally:
        ours.close()
        paper.close()


def test_force_cost_is_chosen_at_the_server_and_changes_only_the_reward(server_bin):
    # Same seed, same actions: the observations agree, and the costed reward is lower by the coefficient times
    # the newtons by which the step's peak node force (the info's wall_force_peak_node_mN) exceeds 1.5 N, never higher.
    plain = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1})
    costly = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1}, server_args=["--task", '{"reward_force_per_N": 2}'])
    try:
        assert plain.spec_reply["task"]["reward_force_per_N"] == 0.0
        assert costly.spec_reply["task"]["reward_force_per_N"] == 2.0
        plain.reset(seed=2)
        costly.reset(seed=2)
        touched = 0
        for _ in range(60):
            a, ra, *_ = plain.step(np.array([0.3], dtype=np.float32))
            b, rb, _, _, info = costly.step(np.array([0.3], dtype=np.float32))
            assert np.array_equal(a, b)
            over_safe_n = max(0.0, 1e-3 * info["wall_force_peak_node_mN"] - 1.5)
            assert rb == pytest.approx(ra - 2.0 * over_safe_n, abs=1e-9)
            touched += info["wall_force_peak_node_mN"] > 0
        assert touched > 0  # the wire touched the wall (the cost itself: tests/task/wall_force_test.cpp)
    finally:
        plain.close()
        costly.close()
    with pytest.raises(Exception):
        GuidewireEnv(anatomies="t1_straight_y", server_args=["--task", '{"reward_force_per_N": -1}'])


def test_force_limit_is_chosen_at_the_server_and_backs_the_wire_off(server_bin):
    # A limit far below what the wire presses with: once the wall force passes it the server reports physics
    # steps whose push it withheld, and the wire goes in less far than the same actions without the limit.
    plain = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1})
    limited = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1}, server_args=["--force-limit", "0.001"])
    try:
        assert plain.spec_reply["task"]["force_limit_N"] == 0.0
        assert limited.spec_reply["task"]["force_limit_N"] == 0.001
        plain.reset(seed=2)
        limited.reset(seed=2)
        held = 0
        for _ in range(60):
            *_, info_plain = plain.step(np.array([0.3], dtype=np.float32))
            *_, info = limited.step(np.array([0.3], dtype=np.float32))
            assert "push_held_steps" not in info_plain
            held += info["push_held_steps"]
        assert held > 0
        assert info["inserted_mm"] < info_plain["inserted_mm"]
    finally:
        plain.close()
        limited.close()
    with pytest.raises(Exception):
        GuidewireEnv(anatomies="t1_straight_y", server_args=["--force-limit", "-1"])


def test_reward_shape_is_chosen_at_the_server_and_changes_only_the_reward(server_bin):
    # Same seed, same actions: the observations agree, the rewards follow each server's sigmoid.
    paper = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1},
                         server_args=["--task", '{"reward": {"omega_centre": 0.1, "omega_slope": 5}}'])
    steep = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1})  # the default: the shipped actor's
    try:
        assert paper.spec_reply["task"]["reward"] == {"omega_centre": 0.1, "omega_slope": 5.0}
        assert steep.spec_reply["task"]["reward"] == {"omega_centre": -0.5, "omega_slope": 8.0}
        paper.reset(seed=2)
        steep.reset(seed=2)
        for _ in range(20):
            a, ra, *_ = paper.step(np.array([0.3], dtype=np.float32))
            b, rb, *_ = steep.step(np.array([0.3], dtype=np.float32))
            assert np.array_equal(a, b)
            omega, lam, act = float(a[9]), float(a[6]), float(a[8])
            rest = 0.5 * (1 - lam) - 0.2 * abs(act)
            assert ra == pytest.approx(2 / (1 + np.exp(5 * (omega - 0.1))) - 1 + rest, abs=1e-4)
            assert rb == pytest.approx(2 / (1 + np.exp(8 * (omega + 0.5))) - 1 + rest, abs=1e-4)
    finally:
        paper.close()
        steep.close()


def test_push_speed_is_a_server_setting_and_sets_the_advance_per_step(server_bin):
    # Same seed, no rotation: at 5 mm/s the tip closes on the target half as fast as at the default 10,
    # and the spec says which speed the server runs. A speed that is not > 0 stops the server by name.
    default = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1})
    slow = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1}, server_args=["--push-speed", "5"])
    try:
        assert default.spec_reply["task"]["push_mm_per_s"] == 10.0
        assert slow.spec_reply["task"]["push_mm_per_s"] == 5.0
        a, _ = default.reset(seed=4)
        b, _ = slow.reset(seed=4)
        assert np.array_equal(a, b)
        for _ in range(25):  # 10 mm and 5 mm in the straight access vessel
            a, *_ = default.step(np.zeros(1, dtype=np.float32))
            b, *_ = slow.step(np.zeros(1, dtype=np.float32))
        closed_default, closed_slow = 1.0 - float(a[6]), 1.0 - float(b[6])
        assert closed_default > 0.05
        assert closed_slow == pytest.approx(0.5 * closed_default, rel=0.15)
        assert 0.5 < float(b[10]) < 1.5  # s = v.c / push: normalised by the push speed
    finally:
        default.close()
        slow.close()
    refused = subprocess.run([str(server_bin), "--port", "0", "--anatomies", "t1_straight_y", "--push-speed", "0"],
                             capture_output=True, text=True, timeout=60)
    assert refused.returncode == 1
    assert "push_mm_per_s" in refused.stderr


def test_combined_junctions_are_layout_obs4_and_change_nothing_on_a_two_way_fork(server_bin):
    # obs/4 = obs/3 with combined junctions (docs/junctions.md): on a single Y fork every entry is the same.
    side = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1}, server_args=["--omega-side"])
    combined = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1},
                            server_args=["--omega-side", "--junctions", "combined"])
    try:
        assert combined.spec_reply["obs_layout"] == "guidewire-nav/obs/4"
        assert combined.spec_reply["task"]["observation"]["junctions"] == "combined"
        a, _ = side.reset(seed=5)
        b, _ = combined.reset(seed=5)
        for _ in range(40):
            a, *_ = side.step(np.array([-0.5], dtype=np.float32))
            b, *_ = combined.step(np.array([-0.5], dtype=np.float32))
            assert np.array_equal(a, b)
    finally:
        side.close()
        combined.close()


def test_push_pull_is_layouts_obs5_act2_and_holds_the_wire_when_stopped(server_bin):
    # act/2 (docs/recovery.md): two action values, 14 observations; at insertion +1 the first 12 entries are
    # obs/3's bit for bit and the reward is Eq. 3 with the aim paid by its change, less the time cost; insertion 0
    # leaves the wire where it is and pays only the aim's change, less the time cost; one value is refused by the
    # client and the server alike, naming what the layout takes.
    side = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1}, server_args=["--omega-side"])
    pp = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1}, server_args=["--push-pull", "--recovery", "2"])
    try:
        assert pp.spec_reply["obs_layout"] == "guidewire-nav/obs/5"
        assert pp.spec_reply["action_layout"] == "guidewire-nav/act/2"
        assert side.spec_reply["action_layout"] == "guidewire-nav/act/1"
        assert pp.action_space.shape == (2,) and pp.observation_space.shape == (14,)
        assert pp.observation_names[-2:] == ["insertion", "wrong_branch"]
        assisted = GuidewireEnv(anatomies="t1_straight_y", options={"target": 1},
                                server_args=["--push-pull", "--recovery", "1", "--recovery-assist"])
        try:
            assert assisted.spec_reply["task"]["recovery_assist"] is True  # docs/recovery.md "Assisted recovery"
            assert pp.spec_reply["task"]["recovery_assist"] is False
        finally:
            assisted.close()
        assert pp.spec_reply["task"]["recovery_attempts"] == 2
        task = pp.spec_reply["task"]
        slope, centre, time_cost = task["reward"]["omega_slope"], task["reward"]["omega_centre"], task["reward_time_per_step"]
        assert time_cost == 0.25  # the shipped push/pull actor's
        aim = lambda w: 2 / (1 + np.exp(slope * (float(w) - centre))) - 1  # noqa: E731
        a, _ = side.reset(seed=6)
        b, _ = pp.reset(seed=6)
        for _ in range(30):
            before = b[9]
            a, ra, *_ = side.step(np.array([0.5], dtype=np.float32))
            b, rb, _, _, info = pp.step(np.array([0.5, 1.0], dtype=np.float32))
            assert np.array_equal(a, b[:12]) and b[12] == 1.0 and b[13] == 0.0
            assert rb == pytest.approx(ra - aim(before) - time_cost, abs=1e-5)
        inserted = info["inserted_mm"]
        for _ in range(5):
            before = b[9]
            b, r, *_, info = pp.step(np.array([0.0, 0.0], dtype=np.float32))
            assert r == pytest.approx(aim(b[9]) - aim(before) - time_cost, abs=1e-5) and b[12] == 0.0
        assert info["inserted_mm"] == pytest.approx(inserted)
        assert info["strict_end"] is False and info["recovery_attempts"] == 0
        with pytest.raises(ValueError, match="2 values"):
            pp.step(np.array([0.5], dtype=np.float32))
        with pytest.raises(ServerError, match="expected 2 numbers"):
            pp._request({"cmd": "step", "action": [0.5]})
    finally:
        side.close()
        pp.close()


def test_heart_rate_makes_the_anatomy_beat_and_is_reported(server_bin):
    # The shipped coronary beats with its own field (docs/beating_heart.md): the same start as the static vessel
    # (the wall is at rest at t = 0), then the observation changes as the tree moves under the wire.
    static = GuidewireEnv(anatomies="coronary", options={"target": 1})
    beating = GuidewireEnv(anatomies="coronary", options={"target": 1}, heart_rate_bpm=100)
    try:
        assert "heart_rate_bpm" not in static.spec_reply["anatomies"][0]
        assert beating.spec_reply["anatomies"][0]["heart_rate_bpm"] == 100.0
        a, _ = static.reset(seed=2)
        b, _ = beating.reset(seed=2)
        assert np.array_equal(a, b)
        differs = False
        for _ in range(12):
            a, *_ = static.step(np.zeros(1, dtype=np.float32))
            b, *_ = beating.step(np.zeros(1, dtype=np.float32))
            differs = differs or not np.array_equal(a, b)
        assert differs
    finally:
        static.close()
        beating.close()
    with pytest.raises(ValueError, match="heart_rate_bpm"):
        GuidewireEnv(port=1, heart_rate_bpm=60)
    # A mesh with no cardiac field of its own needs a motion file: refused by name.
    refused = subprocess.run([str(server_bin), "--port", "0", "--anatomies", "t1_straight_y", "--heart-rate", "60"],
                             capture_output=True, text=True, timeout=60)
    assert refused.returncode == 1
    assert "--motion" in refused.stderr


def test_a_step_the_server_cuts_off_ends_the_episode_and_training_goes_on(server_bin, capsys):
    # --step-cutoff 1e-9: every env step "runs away" (as a wire jammed in a 0.3 mm vessel crawls past the 10 s
    # default), and the server answers with an error. gw-train's RestartingEnv ends that episode as truncated and
    # starts the next one on the same server, instead of letting the error kill the training run.
    cut = RestartingEnv(lambda: GuidewireEnv(anatomies="t1_straight_y", server_args=["--step-cutoff", "1e-9"]))
    try:
        obs, _ = cut.reset(seed=3)
        for _ in range(2):
            o, reward, terminated, truncated, info = cut.step(np.array([0.1]))
            assert truncated and not terminated and reward == 0.0
            assert "time limit" in info["server_error"] and info["is_success"] is False
            assert np.array_equal(o, obs)
            obs, _ = cut.reset()  # the same server, a new episode
        assert cut.step_errors == 2 and cut.restarts == 0
        assert "episode ended by the server" in capsys.readouterr().err
    finally:
        cut.close()
